// The Vulkan port of A-SVGF's adaptive temporal weight. See asvgf_alpha_gpu.h; the shader is
// filters/asvgf/adaptive_alpha.comp.
#include "gpu/asvgf_alpha_gpu.h"

#include "core/error.h"
#include "gpu/asvgf_vulkan.h"
#include "gpu/svgf_planes.h"
#include "gpu/svgf_shaders.h"

#include <string>

namespace rtdr {

AdaptiveAlpha adaptive_alpha_vulkan(VulkanContext& context, const GradientValues& g, int s, int width, int height,
                                    const AdaptiveAlphaParams& params, double* ms) {
  const int radius = params.radius;
  if (g.delta.width != g.norm.width || g.delta.height != g.norm.height)
    throw Error("adaptive_alpha_vulkan: delta^ is " + std::to_string(g.delta.width) + "x" +
                std::to_string(g.delta.height) + ", Delta^ " + std::to_string(g.norm.width) + "x" +
                std::to_string(g.norm.height));
  if (s < 1 || radius < 0 || width < 0 || height < 0)
    throw Error("adaptive_alpha_vulkan: needs s >= 1, radius >= 0 and a size >= 0, got s " + std::to_string(s) +
                ", radius " + std::to_string(radius));
  const int gw = g.norm.width, gh = g.norm.height;
  AdaptiveAlpha out{FloatPlane(gw, gh), FloatPlane(width, height), FloatPlane(width, height),
                    FloatPlane(width, height)};
  if (out.lambda.data.empty() && out.alpha.data.empty()) return out;

  // (delta^, Delta^, l, Var) per stratum, the reconstruction's records (l and Var are not read).
  const auto gradient_buffer = plane_buffer(context, gw, gh, TexelFormat::RGBA32F),
             alpha_buffer = plane_buffer(context, width, height, TexelFormat::RGBA32F),
             lambda_buffer = plane_buffer(context, gw, gh, TexelFormat::R32F);
  float* records = gradient_buffer->data();
  for (size_t i = 0; i < g.delta.data.size(); ++i) {
    records[4 * i + 0] = g.delta.data[i];
    records[4 * i + 1] = g.norm.data[i];
  }

  const AdaptiveAlphaPush push = adaptive_alpha_push(width, height, gw, gh, s, params);
  run_pass(
      context,
      [&](const SvgfShaders& shaders, ComputeBatch& batch) {
        shaders.adaptive_alpha(batch, *gradient_buffer, *alpha_buffer, *lambda_buffer, push);
      },
      ms);

  out.lambda = unpack_channel(*lambda_buffer, gw, gh, 1, 0);
  // (lambda_max, alpha_i, alpha_mu_i, 0) per pixel.
  out.lambda_max = unpack_channel(*alpha_buffer, width, height, 4, 0);
  out.alpha = unpack_channel(*alpha_buffer, width, height, 4, 1);
  out.alpha_moments = unpack_channel(*alpha_buffer, width, height, 4, 2);
  return out;
}

}  // namespace rtdr
