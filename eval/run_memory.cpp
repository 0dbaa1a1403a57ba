// What a run holds in memory at once, estimated before it starts. See run_memory.h.
#include "eval/run_memory.h"

#include "core/error.h"
#include "trace/gradients.h"

namespace rtdr {
namespace {

constexpr uint64_t kPlaneBytes = 4;  // a float or a uint32 per pixel (core/frame.h)
// The planes run_eval keeps of each reference frame: colour 3, display 3, direct luminance, depth, position 3.
constexpr uint64_t kReferencePlanes = 11;

std::string frames_of(uint64_t count, uint64_t planes) {
  return std::to_string(count) + (count == 1 ? " frame of " : " frames of ") + std::to_string(planes) + " planes";
}

}  // namespace

uint64_t frame_planes(const Frame& frame) { return frame.float_channels().size() + frame.uint_channels().size(); }

uint64_t frame_bytes(const Frame& frame) {
  uint64_t bytes = 0;
  for (const auto& [name, plane] : frame.float_channels()) bytes += plane.data.size() * sizeof(float);
  for (const auto& [name, plane] : frame.uint_channels()) bytes += plane.data.size() * sizeof(uint32_t);
  return bytes;
}

uint64_t rendered_frame_planes(const Scene& scene, const RenderSettings& settings, bool gradients) {
  RenderSettings one = settings;
  one.spp = 1;  // the layers do not depend on the samples per pixel, only the time does
  const Frame pixel = gradients ? render_frame_with_gradients(scene, 0, 1, 1, one, GradientParams{}, nullptr)
                                : render_frame(scene, 0, 1, 1, one);
  return frame_planes(pixel);
}

uint64_t method_planes(const Method& method) { return method.dump_channels().size(); }

RunPlanes render_planes(uint64_t frame, bool gradients) {
  const uint64_t frames = gradients ? 3 : 2;
  return {frames * frame, frames_of(frames, frame) + (gradients ? ": the frame, what it is made from, the previous"
                                                                : ": the frame and what it is made from")};
}

RunPlanes eval_planes(uint64_t frame, int frames, uint64_t most_method_planes, int input_sequences,
                      int reference_sequences) {
  const uint64_t n = uint64_t(std::max(frames, 1));
  const uint64_t inputs = uint64_t(std::max(input_sequences, 1)), references = uint64_t(std::max(reference_sequences, 1));
  const uint64_t planes = n * (inputs * frame + references * kReferencePlanes) + frame + most_method_planes;
  return {planes, frames_of(inputs * n, frame) + " of input, " + std::to_string(kReferencePlanes) +
                      " planes of each of " + std::to_string(references * n) +
                      " reference frames, a reference being rendered and a method's " +
                      std::to_string(most_method_planes) + " planes"};
}

RunPlanes bench_planes(uint64_t frame, int frames, uint64_t method) {
  const uint64_t n = uint64_t(std::max(frames, 1));
  return {n * frame + method, frames_of(n, frame) + (method ? " and the method's " + std::to_string(method) + " planes"
                                                            : std::string())};
}

uint64_t run_bytes(const RunPlanes& run, int width, int height) {
  const uint64_t pixels = uint64_t(std::max(width, 0)) * uint64_t(std::max(height, 0));  // below 2^62
  return saturating_product(saturating_product(run.planes, kPlaneBytes), pixels);
}

void require_run_fits(const std::string& command, int width, int height, const RunPlanes& run,
                      const MemoryBudget& budget) {
  const uint64_t bytes = run_bytes(run, width, height);
  if (bytes <= budget.bytes) return;
  throw Error("--size " + std::to_string(width) + "x" + std::to_string(height) + ": " + command +
              " would hold about " + format_bytes(bytes) + " (" + run.how + ", 4 bytes a pixel each), more than the " +
              format_bytes(budget.bytes) + " of memory available (bound by " + budget.bound_by +
              "); choose a smaller --size");
}

}  // namespace rtdr
