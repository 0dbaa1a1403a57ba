// The Vulkan port of tone mapping. See tonemap_gpu.h; the shader is filters/svgf/tonemap.comp.
#include "gpu/tonemap_gpu.h"

#include "gpu/svgf_planes.h"
#include "gpu/svgf_shaders.h"


namespace rtdr {

RgbPlane tonemap_vulkan(VulkanContext& context, const RgbPlane& colour, const TonemapParams& params, double* ms) {
  validate(params);  // as tonemap() does
  RgbPlane display(colour.width, colour.height);
  if (display.data.empty()) return display;

  const auto colour_buffer = plane_buffer(context, colour.width, colour.height, TexelFormat::RGBA32F),
             display_buffer = plane_buffer(context, colour.width, colour.height, TexelFormat::RGBA32F);
  pack_rgb(colour, *colour_buffer);

  run_pass(
      context,
      [&](const SvgfShaders& shaders, ComputeBatch& batch) {
        shaders.tonemap(batch, *colour_buffer, *display_buffer,
                        tonemap_push(uint32_t(colour.width), uint32_t(colour.height), params));
      },
      ms);
  return unpack_rgb(*display_buffer, colour.width, colour.height);
}

}  // namespace rtdr
