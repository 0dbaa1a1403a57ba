// The Vulkan port of TAA. See taa_gpu.h; the shader is filters/taa/taa.comp.
#include "gpu/taa_gpu.h"

#include "core/error.h"
#include "filters/taa/taa_shared.h"
#include "gpu/compute.h"

#include <span>
#include <string>

namespace rtdr {

namespace {

// RgbPlane and Vec2Plane data are already the shader's layout: glm::vec3 is 3 packed floats, glm::vec2 2, pixels
// row-major.
static_assert(sizeof(glm::vec3) == 3 * sizeof(float));
static_assert(sizeof(glm::vec2) == 2 * sizeof(float));
std::span<const float> rgb_floats(const RgbPlane& plane) {
  return {reinterpret_cast<const float*>(plane.data.data()), plane.data.size() * 3};
}
std::span<const float> xy_floats(const Vec2Plane& plane) {
  return {reinterpret_cast<const float*>(plane.data.data()), plane.data.size() * 2};
}

}  // namespace

RgbPlane taa_vulkan(VulkanContext& context, const RgbPlane& current, const RgbPlane& history, const Vec2Plane& motion,
                    const TaaParams& params, const TaaJitter& jitter, double* ms) {
  // The checks of taa_pass(), with its messages.
  validate(params);
  const std::string size = std::to_string(current.width) + "x" + std::to_string(current.height);
  if (motion.width != current.width || motion.height != current.height)
    throw Error("taa: motion must have the current frame's size " + size);
  if (history.width != 0 && (history.width != current.width || history.height != current.height))
    throw Error("taa: history must have the current frame's size " + size + " or be empty");
  RgbPlane out(current.width, current.height);
  if (out.data.empty()) return out;

  // Bindings 0-3 in taa.comp's order: current, history, motion, then the output. An empty history still needs a
  // buffer at binding 1: a 1-float placeholder the shader never reads (has_history = 0).
  const bool has_history = history.width != 0;
  const size_t floats = out.data.size() * 3;
  GpuBuffer current_buffer(context, floats), history_buffer(context, has_history ? floats : 1),
      motion_buffer(context, out.data.size() * 2), out_buffer(context, floats);
  current_buffer.upload(rgb_floats(current));
  if (has_history) history_buffer.upload(rgb_floats(history));
  motion_buffer.upload(xy_floats(motion));

  ComputePipeline pipeline(context, load_shader("taa"), 4, sizeof(TaaPush));
  const TaaPush push{.width = uint32_t(current.width),
                     .height = uint32_t(current.height),
                     .alpha = params.alpha,
                     .clip_history = params.clip_history ? 1u : 0u,
                     .jitter_current = jitter.current,
                     .jitter_previous = jitter.previous,
                     .has_history = has_history ? 1u : 0u,
                     .padding = 0};
  // Enough 8x8 workgroups to cover the frame; the shader skips the overhang.
  const uint32_t groups_x = (push.width + kTaaGroupSizeX - 1) / kTaaGroupSizeX;
  const uint32_t groups_y = (push.height + kTaaGroupSizeY - 1) / kTaaGroupSizeY;
  pipeline.dispatch({&current_buffer, &history_buffer, &motion_buffer, &out_buffer}, &push, groups_x, groups_y, ms);

  const std::vector<float> result = out_buffer.download();
  for (size_t i = 0; i < out.data.size(); ++i)
    out.data[i] = glm::vec3(result[3 * i], result[3 * i + 1], result[3 * i + 2]);
  return out;
}

}  // namespace rtdr
