// The Vulkan port of A-SVGF's gradient image. See asvgf_gradient_gpu.h; the shader is
// filters/asvgf/gradient_image.comp.
#include "gpu/asvgf_gradient_gpu.h"

#include "core/error.h"
#include "gpu/asvgf_vulkan.h"
#include "gpu/svgf_planes.h"
#include "gpu/svgf_shaders.h"

#include <cstring>
#include <string>

namespace rtdr {

GradientImage gradient_image_vulkan(VulkanContext& context, const RgbPlane& noisy, const UIntPlane& source,
                                    const FloatPlane& prev_luminance, const SurfacePlanes& surface, int s,
                                    const GradientForm& form, double* ms) {
  // gradient_image's checks, and the grid it fills.
  GradientImage g = gradient_image_grid(noisy, source, prev_luminance, surface, s);
  const int w = noisy.width, h = noisy.height, sw = g.values.delta.width, sh = g.values.delta.height;
  if (g.values.delta.data.empty()) return g;

  const auto noisy_prev = plane_buffer(context, w, h, TexelFormat::RGBA32F),
             source_buffer = plane_buffer(context, w, h, TexelFormat::R32UI),
             surface_buffer = plane_buffer(context, w, h, TexelFormat::RGBA32F),
             depth_grad = plane_buffer(context, w, h, TexelFormat::RG32F),
             mesh = plane_buffer(context, w, h, TexelFormat::R32UI);
  // (C_i, f_{i-1}): gradient.prev_<stream> in w.
  pack_rgb(noisy, *noisy_prev);
  for (size_t i = 0; i < prev_luminance.data.size(); ++i) noisy_prev->data()[4 * i + 3] = prev_luminance.data[i];
  pack_ids(source, *source_buffer);
  pack_surface(surface, *surface_buffer);
  pack_vec2(surface.depth_grad, *depth_grad);
  pack_ids(surface.mesh, *mesh);
  const auto values = plane_buffer(context, sw, sh, TexelFormat::RGBA32F),
             surface_out = plane_buffer(context, sw, sh, TexelFormat::RGBA32F),
             depth_grad_out = plane_buffer(context, sw, sh, TexelFormat::RG32F),
             mesh_out = plane_buffer(context, sw, sh, TexelFormat::R32UI),
             samples = plane_buffer(context, sw, sh, TexelFormat::R32UI);

  const GradientImagePush push = gradient_image_push(w, h, sw, sh, s, form);
  const GradientImagePlanes planes{noisy_prev.get(), source_buffer.get(), surface_buffer.get(), depth_grad.get(),
                                   mesh.get()};
  run_pass(
      context,
      [&](const SvgfShaders& shaders, ComputeBatch& batch) {
        shaders.gradient_image(batch, planes, *values, *surface_out, *depth_grad_out, *mesh_out, *samples, push);
      },
      ms);

  // A stratum holds at most one gradient sample (gradient_image.h); the golden pass throws at the second.
  const float* ids = mesh_out->data();
  const float* counts = samples->data();
  for (int sy = 0; sy < sh; ++sy)
    for (int sx = 0; sx < sw; ++sx) {
      const size_t i = size_t(sy) * size_t(sw) + size_t(sx);
      uint32_t id, count;
      std::memcpy(&id, ids + i, sizeof(id));
      std::memcpy(&count, counts + i, sizeof(count));
      if (count > 1)
        throw Error("stratum (" + std::to_string(sx) + ", " + std::to_string(sy) + ") holds two gradient samples");
      g.surface.mesh.data[i] = id;
    }
  g.values.delta = unpack_channel(*values, sw, sh, 4, 0);
  g.values.norm = unpack_channel(*values, sw, sh, 4, 1);
  g.values.luminance = unpack_channel(*values, sw, sh, 4, 2);
  g.values.variance = unpack_channel(*values, sw, sh, 4, 3);
  g.surface.normal = unpack_rgb(*surface_out, sw, sh);
  g.surface.depth = unpack_channel(*surface_out, sw, sh, 4, 3);
  const FloatPlane gx = unpack_channel(*depth_grad_out, sw, sh, 2, 0),
                   gy = unpack_channel(*depth_grad_out, sw, sh, 2, 1);
  for (size_t i = 0; i < gx.data.size(); ++i) g.surface.depth_grad.data[i] = glm::vec2(gx.data[i], gy.data[i]);
  return g;
}

}  // namespace rtdr
