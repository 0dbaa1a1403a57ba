// The Vulkan port of remodulation. See modulate_gpu.h; the shader is filters/svgf/modulate.comp.
#include "gpu/modulate_gpu.h"

#include "core/error.h"
#include "gpu/svgf_planes.h"
#include "gpu/svgf_shaders.h"

#include <string>

namespace rtdr {

RgbPlane remodulate_vulkan(VulkanContext& context, const RgbPlane& direct, const RgbPlane& indirect,
                           const RgbPlane& albedo, const RgbPlane& emission, double* ms) {
  const auto same_size = [&](const RgbPlane& p) { return p.width == direct.width && p.height == direct.height; };
  if (!same_size(indirect) || !same_size(albedo) || !same_size(emission))
    throw Error("remodulate_vulkan: direct, indirect, albedo and emission must have the same size (direct is " +
                std::to_string(direct.width) + "x" + std::to_string(direct.height) + ")");
  RgbPlane colour(direct.width, direct.height);
  if (colour.data.empty()) return colour;

  const int w = direct.width, h = direct.height;
  const auto illumination = illumination_buffer(context, w, h),
             albedo_buffer = plane_buffer(context, w, h, TexelFormat::RGBA32F),
             emission_buffer = plane_buffer(context, w, h, TexelFormat::RGBA32F),
             colour_buffer = plane_buffer(context, w, h, TexelFormat::RGBA32F);
  pack_illumination(kDirectStream, direct, nullptr, *illumination);
  pack_illumination(kIndirectStream, indirect, nullptr, *illumination);
  pack_rgb(albedo, *albedo_buffer);
  pack_rgb(emission, *emission_buffer);

  run_pass(
      context,
      [&](const SvgfShaders& shaders, ComputeBatch& batch) {
        shaders.modulate(batch, *illumination, *albedo_buffer, *emission_buffer, *colour_buffer,
                         modulate_push(uint32_t(w), uint32_t(h)));
      },
      ms);
  return unpack_rgb(*colour_buffer, w, h);
}

}  // namespace rtdr
