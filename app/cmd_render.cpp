// rtdr render: a scene's frames, one multi-layer EXR per frame (G-buffer, motion, path-traced radiance)
// plus a PNG preview. --spp N > 1 renders reference frames. --gradients renders A-SVGF's input: each frame with
// the gradient samples carried from the frame before it (trace/gradients.h), so frames are rendered in order,
// and a range A-B with A > 0 continues from frame A-1 in --out, or renders frames 0 to A-1 first (not written).
#include "app/commands.h"
#include "app/preview.h"
#include "app/sequence.h"
#include "core/atomic_file.h"
#include "core/error.h"
#include "core/exr_io.h"
#include "core/parallel.h"
#include "core/progress.h"
#include "eval/run_memory.h"
#include "scenes/gltf_loader.h"
#include "trace/gradients.h"
#include "trace/render_frame.h"
#include "trace/true_change.h"

#include <chrono>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <optional>

namespace rtdr {
namespace {

struct RenderOptions {
  std::string scene = "pillars";
  std::string frames = "0-9";
  std::string size = "640x360";
  std::string out = "out/render";
  RenderSettings settings;
  bool gradients = false;
  GradientParams gradient;
  bool true_change = false;
};

// With --gradients, frame A-1 of the range A-B: read from --out where a gradient render left it, else rendered
// from frame 0 (std::nullopt for A = 0). Says which.
std::optional<Frame> frame_before(const RenderOptions& o, const Scene& scene, const FrameRange& frames, Size size) {
  if (frames.first == 0) return std::nullopt;
  const std::string path = frame_path(o.out, frames.first - 1, "exr");
  std::error_code ec;
  if (std::filesystem::exists(path, ec)) {
    Frame prev = read_exr(path);
    if (prev.width() != size.width || prev.height() != size.height)
      throw Error("--gradients: frame " + std::to_string(frames.first - 1) + " in --out ('" + path + "') is " +
                  std::to_string(prev.width()) + "x" + std::to_string(prev.height()) + ", not " + o.size);
    if (!prev.uint_channels().count("gradient.source"))
      throw Error("--gradients: frame " + std::to_string(frames.first - 1) + " in --out ('" + path +
                  "') was not rendered with --gradients; render from frame 0 or into another --out");
    std::printf("gradients: continuing from frame %d in %s\n", frames.first - 1, path.c_str());
    return prev;
  }
  std::printf("gradients: frame %d is not in %s: rendering frames 0-%d first (not written)\n", frames.first - 1,
              o.out.c_str(), frames.first - 1);
  std::optional<Frame> prev;
  for (int f = 0; f < frames.first; ++f)
    prev = render_frame_with_gradients(scene, f, size.width, size.height, o.settings, o.gradient,
                                       prev ? &*prev : nullptr);
  return prev;
}

void run_render(const RenderOptions& o) {
  // Validate every argument before doing any work, so bad input never leaves partial output.
  const Size size = parse_size(o.size);
  const FrameRange frames = parse_frames(o.frames);
  const Scene scene = load_scene(o.scene);
  if (o.gradients) {
    validate(o.gradient);
    if (o.settings.spp != 1)
      throw Error("--gradients compares two 1-spp samples per gradient pixel: use --spp 1, not " +
                  std::to_string(o.settings.spp));
  }
  if (o.gradients && o.true_change)
    throw Error("--true-change measures a frame's own surface samples: render it without --gradients");
  // What the run will hold, against the memory there is (eval/run_memory.h), before any work.
  require_run_fits("render", size.width, size.height,
                   render_planes(rendered_frame_planes(scene, o.settings, o.gradients), o.gradients), memory_budget());
  std::optional<Frame> prev = o.gradients ? frame_before(o, scene, frames, size) : std::nullopt;
  StagedOutputDir out(o.out);  // the frames appear when the last one is done; a failed run leaves none

  const auto start = std::chrono::steady_clock::now();
  TraceStats total;
  for (int f = frames.first; f <= frames.last; ++f) {  // no overflow: last <= kMaxFrameIndex
    TraceStats stats;
    Frame frame;
    if (o.true_change) {
      frame = render_true_change_frame(scene, f, size.width, size.height, o.settings, &stats);
    } else if (o.gradients) {
      frame = render_frame_with_gradients(scene, f, size.width, size.height, o.settings, o.gradient,
                                          prev ? &*prev : nullptr, &stats);
    } else if (o.settings.spp > 1) {  // a reference frame takes a while: show progress
      ProgressBar bar("frame " + std::to_string(f) + ", " + std::to_string(o.settings.spp) + " spp", uint64_t(size.height));
      frame = render_frame(scene, f, size.width, size.height, o.settings, &stats, [&](int rows) { bar.advance(uint64_t(rows)); });
    } else {
      frame = render_frame(scene, f, size.width, size.height, o.settings, &stats);
    }
    require_finite_output(frame, "frame " + std::to_string(f) + " of scene '" + scene.name + "'",
                          [](const std::string&) { return std::string("render"); });
    write_exr(out.file(frame_name(f, "exr")), frame);
    write_preview_png(out.file(frame_name(f, "png")), frame);
    if (o.gradients) prev = std::move(frame);
    std::printf("frame %d  t = %.4f s  %.2f Mrays/s  -> %s\n", f, scene.time_of_frame(f), 1e-6 * double(stats.rays) / stats.seconds,
                frame_path(o.out, f, "exr").c_str());
    total.rays += stats.rays;
    total.seconds += stats.seconds;
  }
  out.commit();
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  const int count = frames.last - frames.first + 1;
  std::printf("rendered %d frame(s) of '%s' at %dx%d, %d spp, in %.2f s; EXR layers in docs/buffers.md, previews *.png\n",
              count, scene.name.c_str(), size.width, size.height, o.settings.spp, seconds);
  std::printf("path tracer: %llu rays in %.2f s = %.2f Mrays/s (%d threads)\n", (unsigned long long)total.rays,
              total.seconds, 1e-6 * double(total.rays) / total.seconds, thread_count());
}

}  // namespace

Command add_render_command(CLI::App& app) {
  auto o = std::make_shared<RenderOptions>();
  CLI::App* sub = app.add_subcommand("render", "render a scene's frames (G-buffer, motion, 1 spp or reference radiance) to multi-layer EXR files");
  sub->add_option("--scene", o->scene, "shipped scene name (see scenes/) or path to a .gltf file")
      ->capture_default_str();
  sub->add_option("--frames", o->frames, frames_help(", or one frame A; frame f is at t = f/fps"))
      ->capture_default_str();
  sub->add_option("--size", o->size, "image size WIDTHxHEIGHT; refused when the run would not fit in the memory available")
      ->capture_default_str();
  sub->add_option("--out", o->out, "output directory (created if missing)")->capture_default_str();
  sub->add_option("--spp", o->settings.spp, "samples per pixel: 1 for denoiser input, e.g. 1024 for reference frames")
      ->check(CLI::Range(1, 1 << 20))->capture_default_str();
  sub->add_option("--seed", o->settings.seed, "global seed; every pixel's seed derives from it and the frame")
      ->capture_default_str();
  sub->add_option("--max-bounces", o->settings.trace.max_bounces, "indirect bounces after the primary hit")
      ->check(CLI::Range(0, 1024))->capture_default_str();
  sub->add_option("--shading-samples", o->settings.trace.shading_samples,
                  "TRMV's input: add direct.shading, the unshadowed direct light from this many light samples per "
                  "pixel (trace/shading.h; 64 is what rtdr eval uses); 0 leaves it out")
      ->check(CLI::Range(0, 1024))->capture_default_str();
  sub->add_flag("--gradients", o->gradients,
                "A-SVGF's input: merge gradient samples carried from the previous frame (trace/gradients.h)");
  add_gradient_flags(sub, o->gradient);
  sub->add_flag("--true-change", o->true_change,
                "A-SVGF's yardstick: add truth.prev_direct and truth.prev_indirect, each pixel's surface sample shaded "
                "under the previous frame's poses, lights and eye with the same seeds (trace/true_change.h)");
  return {sub, [o] { run_render(*o); }};
}

}  // namespace rtdr
