// The Vulkan port of A-SVGF's reconstruction of the gradient. See asvgf_atrous_gpu.h; the shader is
// filters/asvgf/gradient_atrous.comp.
#include "gpu/asvgf_atrous_gpu.h"

#include "core/error.h"
#include "gpu/asvgf_vulkan.h"
#include "gpu/svgf_planes.h"
#include "gpu/svgf_shaders.h"

#include <string>
#include <vector>

namespace rtdr {

GradientValues gradient_atrous_vulkan(VulkanContext& context, const GradientValues& in, const GradientImage& image,
                                      const SvgfParams& params, int iterations, int first_level, double* ms) {
  const int w = in.luminance.width, h = in.luminance.height;
  const auto sized = [&](const auto& p) { return p.width == w && p.height == h; };
  if (!sized(in.delta) || !sized(in.norm) || !sized(in.variance) || !sized(image.surface.depth) ||
      !sized(image.surface.depth_grad) || !sized(image.surface.normal) || !sized(image.surface.mesh))
    throw Error("gradient reconstruction: the values and the strata's geometry are not all " + std::to_string(w) +
                "x" + std::to_string(h));
  if (image.stratum_size < 1)
    throw Error("gradient reconstruction: stratum size " + std::to_string(image.stratum_size) + " < 1");
  if (iterations < 0 || first_level < 0 || first_level + iterations > 31)
    throw Error("gradient reconstruction: iterations " + std::to_string(first_level) + ".." +
                std::to_string(first_level + iterations - 1) + " outside 0..30");
  if (iterations == 0 || in.luminance.data.empty()) return in;

  // Two value buffers, read and written in turn: iteration k reads ping[k % 2] and writes ping[(k + 1) % 2].
  const std::unique_ptr<GpuBuffer> ping[2] = {plane_buffer(context, w, h, TexelFormat::RGBA32F),
                                              plane_buffer(context, w, h, TexelFormat::RGBA32F)};
  const auto surface = plane_buffer(context, w, h, TexelFormat::RGBA32F),
             depth_grad = plane_buffer(context, w, h, TexelFormat::RG32F),
             mesh = plane_buffer(context, w, h, TexelFormat::R32UI);
  float* values = ping[0]->data();
  for (size_t i = 0; i < in.luminance.data.size(); ++i) {
    values[4 * i + 0] = in.delta.data[i];
    values[4 * i + 1] = in.norm.data[i];
    values[4 * i + 2] = in.luminance.data[i];
    values[4 * i + 3] = in.variance.data[i];
  }
  pack_surface(image.surface, *surface);
  pack_vec2(image.surface.depth_grad, *depth_grad);
  pack_ids(image.surface.mesh, *mesh);

  const SvgfShaders shaders(context);
  ComputeBatch batch(context, uint32_t(iterations));
  std::vector<GradientAtrousPush> pushes;  // outlive run()
  pushes.reserve(size_t(iterations));
  for (int i = 0; i < iterations; ++i) {
    pushes.push_back(gradient_atrous_push(w, h, first_level + i, image.stratum_size, params));
    shaders.gradient_atrous(batch, *ping[i % 2], *surface, *depth_grad, *mesh, *ping[(i + 1) % 2], pushes.back());
  }
  batch.run();
  batch.total_time(ms);

  const GpuBuffer& result = *ping[iterations % 2];
  return GradientValues{unpack_channel(result, w, h, 4, 0), unpack_channel(result, w, h, 4, 1),
                        unpack_channel(result, w, h, 4, 2), unpack_channel(result, w, h, 4, 3)};
}

}  // namespace rtdr
