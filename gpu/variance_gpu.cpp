// The Vulkan port of SVGF variance estimation. See variance_gpu.h; the shader is filters/svgf/variance.comp.
#include "gpu/variance_gpu.h"

#include "core/error.h"
#include "gpu/svgf_planes.h"
#include "gpu/svgf_shaders.h"

#include <string>

namespace rtdr {

FloatPlane variance_vulkan(VulkanContext& context, const TemporalOutput& t, const SurfacePlanes& cur,
                           const SvgfParams& params, double* ms) {
  const int w = cur.width(), h = cur.height();
  const auto sized = [&](const auto& p) { return p.width == w && p.height == h; };
  if (!sized(t.color) || !sized(t.moment1) || !sized(t.moment2) || !sized(t.length) || !sized(cur.depth_grad) ||
      !sized(cur.normal) || !sized(cur.mesh))
    throw Error("variance_vulkan: the temporal output and G-buffer planes are not all " + std::to_string(w) + "x" +
                std::to_string(h));
  if (params.variance_min_history < 0)
    throw Error("variance_vulkan: variance_min_history must be >= 0, got " +
                std::to_string(params.variance_min_history));
  FloatPlane sigma2(w, h);
  if (sigma2.data.empty()) return sigma2;

  // The temporal output as the shader reads it: illumination records C' and moments records.
  const auto illumination = illumination_buffer(context, w, h),
             moments = plane_buffer(context, w, h, TexelFormat::RGBA32F),
             surface = plane_buffer(context, w, h, TexelFormat::RGBA32F),
             grad = plane_buffer(context, w, h, TexelFormat::RG32F),
             out = illumination_buffer(context, w, h);
  for (const int stream : {kDirectStream, kIndirectStream}) pack_illumination(stream, t.color, nullptr, *illumination);
  pack_moments(t.moment1, t.moment2, t.length, *moments);
  pack_surface(cur, *surface);
  pack_vec2(cur.depth_grad, *grad);

  const VariancePush push = variance_push(uint32_t(w), uint32_t(h), params);
  // Both streams hold the same values; the indirect stream's output is not read back.
  run_pass(
      context,
      [&](const SvgfShaders& shaders, ComputeBatch& batch) {
        shaders.variance(batch, *illumination, {moments.get(), moments.get()},
                         {surface.get(), grad.get(), nullptr, nullptr}, *out, push);
      },
      ms);
  return unpack_variance(*out, w, h, kDirectStream);
}

}  // namespace rtdr
