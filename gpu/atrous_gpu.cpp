// The Vulkan port of one a-trous level. See atrous_gpu.h; the shaders are filters/svgf/prefilter.comp and
// filters/svgf/atrous.comp.
#include "gpu/atrous_gpu.h"

#include "core/error.h"
#include "filters/svgf/atrous_shared.h"
#include "filters/svgf/prefilter.h"
#include "gpu/compute.h"

#include <span>
#include <string>

namespace rtdr {

// The numbers the shaders take from atrous_shared.h and the golden code from elsewhere must agree.
static_assert(kGaussian3[0] == kPrefilterEdge && kGaussian3[1] == kPrefilterCentre && kGaussian3[2] == kPrefilterEdge);

namespace {

// The planes' data are already the shaders' layout: glm::vec3 is 3 packed floats, glm::vec2 2, pixels row-major.
static_assert(sizeof(glm::vec3) == 3 * sizeof(float));
static_assert(sizeof(glm::vec2) == 2 * sizeof(float));
template <class T>
std::span<const float> floats_of(const Plane<T>& plane) {
  static_assert(sizeof(T) % sizeof(float) == 0);
  return {reinterpret_cast<const float*>(plane.data.data()), plane.data.size() * (sizeof(T) / sizeof(float))};
}

// A float buffer holding exactly `plane`.
template <class T>
void upload_plane(GpuBuffer& buffer, const Plane<T>& plane) {
  buffer.upload(floats_of(plane));
}

}  // namespace

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

  const size_t pixels = out.color.data.size();
  GpuBuffer colour_buffer(context, 3 * pixels), variance_buffer(context, pixels),
      prefiltered_buffer(context, pixels), depth_buffer(context, pixels), grad_buffer(context, 2 * pixels),
      normal_buffer(context, 3 * pixels), mesh_buffer(context, pixels), colour_out_buffer(context, 3 * pixels),
      variance_out_buffer(context, pixels);
  upload_plane(colour_buffer, color);
  upload_plane(variance_buffer, variance);
  upload_plane(depth_buffer, s.depth);
  upload_plane(grad_buffer, s.depth_grad);
  upload_plane(normal_buffer, s.normal);
  // Mesh ids travel as a uint buffer: the same 32 bits, copied, never converted.
  static_assert(sizeof(uint32_t) == sizeof(float));
  mesh_buffer.upload({reinterpret_cast<const float*>(s.mesh.data.data()), pixels});

  const AtrousPush push{uint32_t(w),          uint32_t(h),    level,          params.kernel_size,
                        params.sigma_z,       params.sigma_n, params.sigma_l, params.epsilon};
  // Enough 8x8 workgroups to cover the frame; the shaders skip the overhang.
  const uint32_t groups_x = (push.width + kAtrousGroupSizeX - 1) / kAtrousGroupSizeX;
  const uint32_t groups_y = (push.height + kAtrousGroupSizeY - 1) / kAtrousGroupSizeY;

  // g3x3(Var(c_i)), steering w_l [SVGF17 Eq. 5]; dispatch() waits, so the level below reads it complete.
  double prefilter_ms = 0.0, level_ms = 0.0;
  ComputePipeline prefilter(context, load_shader("prefilter"), 2, sizeof(AtrousPush));
  prefilter.dispatch({&variance_buffer, &prefiltered_buffer}, &push, groups_x, groups_y, &prefilter_ms);

  ComputePipeline atrous(context, load_shader("atrous"), 9, sizeof(AtrousPush));
  atrous.dispatch({&colour_buffer, &variance_buffer, &prefiltered_buffer, &depth_buffer, &grad_buffer,
                   &normal_buffer, &mesh_buffer, &colour_out_buffer, &variance_out_buffer},
                  &push, groups_x, groups_y, &level_ms);
  if (ms) *ms = prefilter_ms + level_ms;

  const std::vector<float> colour = colour_out_buffer.download();
  for (size_t i = 0; i < pixels; ++i) out.color.data[i] = glm::vec3(colour[3 * i], colour[3 * i + 1], colour[3 * i + 2]);
  out.variance.data = variance_out_buffer.download();
  out.prefiltered_variance.data = prefiltered_buffer.download();
  return out;
}

}  // namespace rtdr
