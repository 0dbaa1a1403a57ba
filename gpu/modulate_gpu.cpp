// The Vulkan port of remodulation. See modulate_gpu.h; the shader is filters/svgf/modulate.comp.
#include "gpu/modulate_gpu.h"

#include "core/error.h"
#include "filters/svgf/modulate_shared.h"
#include "gpu/compute.h"

#include <span>
#include <string>

namespace rtdr {

namespace {

// An RgbPlane's data is already the shader's layout: glm::vec3 is 3 packed floats, pixels row-major.
static_assert(sizeof(glm::vec3) == 3 * sizeof(float));
std::span<const float> rgb_floats(const RgbPlane& plane) {
  return {reinterpret_cast<const float*>(plane.data.data()), plane.data.size() * 3};
}

}  // namespace

RgbPlane remodulate_vulkan(VulkanContext& context, const RgbPlane& direct, const RgbPlane& indirect,
                           const RgbPlane& albedo, const RgbPlane& emission, double* ms) {
  const auto same_size = [&](const RgbPlane& p) { return p.width == direct.width && p.height == direct.height; };
  if (!same_size(indirect) || !same_size(albedo) || !same_size(emission))
    throw Error("remodulate_vulkan: direct, indirect, albedo and emission must have the same size (direct is " +
                std::to_string(direct.width) + "x" + std::to_string(direct.height) + ")");
  RgbPlane colour(direct.width, direct.height);
  if (colour.data.empty()) return colour;

  // Bindings 0-4 in modulate.comp's order: the four inputs, then the colour.
  const size_t floats = colour.data.size() * 3;
  GpuBuffer direct_buffer(context, floats), indirect_buffer(context, floats), albedo_buffer(context, floats),
      emission_buffer(context, floats), colour_buffer(context, floats);
  direct_buffer.upload(rgb_floats(direct));
  indirect_buffer.upload(rgb_floats(indirect));
  albedo_buffer.upload(rgb_floats(albedo));
  emission_buffer.upload(rgb_floats(emission));

  ComputePipeline pipeline(context, load_shader("modulate"), 5, sizeof(ModulatePush));
  const ModulatePush push{uint32_t(direct.width), uint32_t(direct.height)};
  // Enough 8x8 workgroups to cover the frame; the shader skips the overhang.
  const uint32_t groups_x = (push.width + kModulateGroupSizeX - 1) / kModulateGroupSizeX;
  const uint32_t groups_y = (push.height + kModulateGroupSizeY - 1) / kModulateGroupSizeY;
  pipeline.dispatch({&direct_buffer, &indirect_buffer, &albedo_buffer, &emission_buffer, &colour_buffer}, &push,
                    groups_x, groups_y, ms);

  const std::vector<float> result = colour_buffer.download();
  for (size_t i = 0; i < colour.data.size(); ++i)
    colour.data[i] = glm::vec3(result[3 * i], result[3 * i + 1], result[3 * i + 2]);
  return colour;
}

}  // namespace rtdr
