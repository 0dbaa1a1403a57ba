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
  const int w = color.width, h = color.height;
  const auto same_size = [&](const auto& p) { return p.width == w && p.height == h; };
  if (!same_size(variance) || !same_size(s.depth) || !same_size(s.depth_grad) || !same_size(s.normal) ||
      !same_size(s.mesh))
    throw Error("atrous_level_vulkan: colour, variance, depth, depth gradient, normal and mesh id must have the "
                "same size (colour is " + std::to_string(w) + "x" + std::to_string(h) + ")");
  if (level < 0 || level > 30) throw Error("atrous_level_vulkan: level must be in 0..30, got " + std::to_string(level));
  AtrousOutput out{RgbPlane(w, h), FloatPlane(w, h), FloatPlane(w, h)};
  if (out.color.data.empty()) return out;

  const auto in = illumination_buffer(context, w, h),
             surface = plane_buffer(context, w, h, TexelFormat::RGBA32F),
             grad = plane_buffer(context, w, h, TexelFormat::RG32F),
             filtered = illumination_buffer(context, w, h),
             prefiltered = plane_buffer(context, w, h, TexelFormat::RG32F);
  for (const int stream : {kDirectStream, kIndirectStream}) pack_illumination(stream, color, &variance, *in);
  pack_surface(s, *surface);
  pack_vec2(s.depth_grad, *grad);

  const AtrousPush push{uint32_t(w),    uint32_t(h),    level, params.sigma_z, params.sigma_n,
                        params.sigma_l, params.epsilon, 1u};
  run_pass(
      context,
      [&](const SvgfShaders& shaders, ComputeBatch& batch) {
        shaders.atrous(batch, *in, {surface.get(), grad.get(), nullptr, nullptr}, *filtered, *prefiltered, push,
                       params.kernel_size);
      },
      ms);

  out.color = unpack_illumination(*filtered, w, h, kDirectStream);
  out.variance = unpack_variance(*filtered, w, h, kDirectStream);
  out.prefiltered_variance = unpack_channel(*prefiltered, w, h, 2, 0);
  return out;
}

}  // namespace rtdr
