// The Vulkan port of one a-trous level. See atrous_gpu.h; the shader is filters/svgf/atrous.comp, which filters
// two streams at once: here both hold the same values.
#include "gpu/atrous_gpu.h"

#include "core/error.h"
#include "filters/svgf/prefilter.h"
#include "gpu/svgf_planes.h"
#include "gpu/svgf_shaders.h"

#include <string>

namespace rtdr {

AtrousOutput atrous_level_vulkan(VulkanContext& context, const RgbPlane& color, const FloatPlane& variance,
                                 const SurfacePlanes& s, int level, const SvgfParams& params, double* ms) {
  atrous_kernel(params.kernel_size);  // throws on a bad kernel_size, as atrous_level does
  const int width = color.width, height = color.height;
  const auto same_size = [&](const auto& p) { return p.width == width && p.height == height; };
  if (!same_size(variance) || !same_size(s.depth) || !same_size(s.depth_grad) || !same_size(s.normal) ||
      !same_size(s.mesh))
    throw Error("atrous_level_vulkan: colour, variance, depth, depth gradient, normal and mesh id must have the "
                "same size (colour is " + std::to_string(width) + "x" + std::to_string(height) + ")");
  if (level < 0 || level > 30) throw Error("atrous_level_vulkan: level must be in 0..30, got " + std::to_string(level));
  AtrousOutput out{RgbPlane(width, height), FloatPlane(width, height), FloatPlane(width, height)};
  if (out.color.data.empty()) return out;

  const auto in = illumination_buffer(context, width, height),
             surface = plane_buffer(context, width, height, TexelFormat::RGBA32F),
             grad = plane_buffer(context, width, height, TexelFormat::RG32F),
             filtered = illumination_buffer(context, width, height),
             prefiltered = plane_buffer(context, width, height, TexelFormat::RG32F);
  for (const int stream : {kDirectStream, kIndirectStream}) pack_illumination(stream, color, &variance, *in);
  pack_surface(s, *surface);
  pack_vec2(s.depth_grad, *grad);

  const AtrousPush push = atrous_push(uint32_t(width), uint32_t(height), level, params, true);
  run_pass(
      context,
      [&](const SvgfShaders& shaders, ComputeBatch& batch) {
        shaders.atrous(batch, *in, {surface.get(), grad.get(), nullptr, nullptr}, *filtered, *prefiltered, push,
                       params.kernel_size);
      },
      ms);

  out.color = unpack_illumination(*filtered, width, height, kDirectStream);
  out.variance = unpack_variance(*filtered, width, height, kDirectStream);
  out.prefiltered_variance = unpack_channel(*prefiltered, width, height, 2, 0);
  return out;
}

}  // namespace rtdr
