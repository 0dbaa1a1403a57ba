// The Vulkan port of tone mapping. See tonemap_gpu.h; the shader is filters/svgf/tonemap.comp.
#include "gpu/tonemap_gpu.h"

#include "filters/svgf/tonemap_shared.h"
#include "gpu/compute.h"

#include <span>

namespace rtdr {

namespace {

// An RgbPlane's data is already the shader's layout: glm::vec3 is 3 packed floats, pixels row-major.
static_assert(sizeof(glm::vec3) == 3 * sizeof(float));
std::span<const float> rgb_floats(const RgbPlane& plane) {
  return {reinterpret_cast<const float*>(plane.data.data()), plane.data.size() * 3};
}

}  // namespace

RgbPlane tonemap_vulkan(VulkanContext& context, const RgbPlane& colour, const TonemapParams& params, double* ms) {
  validate(params);  // as tonemap() does
  RgbPlane display(colour.width, colour.height);
  if (display.data.empty()) return display;

  // Bindings 0-1 in tonemap.comp's order: the HDR colour, then the display colour.
  const size_t floats = display.data.size() * 3;
  GpuBuffer colour_buffer(context, floats), display_buffer(context, floats);
  colour_buffer.upload(rgb_floats(colour));

  ComputePipeline pipeline(context, load_shader("tonemap"), 2, sizeof(TonemapPush));
  const TonemapPush push{uint32_t(colour.width), uint32_t(colour.height), params.exposure};
  // Enough 8x8 workgroups to cover the frame; the shader skips the overhang.
  const uint32_t groups_x = (push.width + kTonemapGroupSizeX - 1) / kTonemapGroupSizeX;
  const uint32_t groups_y = (push.height + kTonemapGroupSizeY - 1) / kTonemapGroupSizeY;
  pipeline.dispatch({&colour_buffer, &display_buffer}, &push, groups_x, groups_y, ms);

  const std::vector<float> result = display_buffer.download();
  for (size_t i = 0; i < display.data.size(); ++i)
    display.data[i] = glm::vec3(result[3 * i], result[3 * i + 1], result[3 * i + 2]);
  return display;
}

}  // namespace rtdr
