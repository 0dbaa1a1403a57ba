// The Vulkan port of TAA. See taa_gpu.h; the shader is filters/taa/taa.comp.
#include "gpu/taa_gpu.h"

#include "core/error.h"
#include "gpu/svgf_planes.h"
#include "gpu/svgf_shaders.h"

#include <string>

namespace rtdr {

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

  // An empty history still needs a buffer at binding 1: one texel the shader never reads (has_history = 0).
  const bool has_history = history.width != 0;
  const int w = current.width, h = current.height;
  const auto current_buffer = plane_buffer(context, w, h, TexelFormat::RGBA32F),
             history_buffer = plane_buffer(context, history.width, history.height, TexelFormat::RGBA32F),
             motion_buffer = plane_buffer(context, w, h, TexelFormat::RG32F),
             out_buffer = plane_buffer(context, w, h, TexelFormat::RGBA32F);
  pack_rgb(current, *current_buffer);
  if (has_history) pack_rgb(history, *history_buffer);
  pack_vec2(motion, *motion_buffer);

  const TaaPush push = taa_push(uint32_t(w), uint32_t(h), params, jitter, has_history);
  run_pass(
      context,
      [&](const SvgfShaders& shaders, ComputeBatch& batch) {
        shaders.taa(batch, *current_buffer, *history_buffer, *motion_buffer, *out_buffer, push);
      },
      ms);
  return unpack_rgb(*out_buffer, w, h);
}

}  // namespace rtdr
