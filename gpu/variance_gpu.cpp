// The Vulkan port of SVGF variance estimation. See variance_gpu.h; the shader is filters/svgf/variance.comp.
#include "gpu/variance_gpu.h"

#include "core/error.h"
#include "filters/svgf/variance_shared.h"
#include "gpu/compute.h"

#include <bit>
#include <span>
#include <string>
#include <vector>

namespace rtdr {

namespace {

// The planes' data is already the shader's layout: glm::vec2 / glm::vec3 are 2 / 3 packed floats, pixels
// row-major.
static_assert(sizeof(glm::vec2) == 2 * sizeof(float));
static_assert(sizeof(glm::vec3) == 3 * sizeof(float));
template <class T>
std::span<const float> floats_of(const Plane<T>& plane) {
  return {reinterpret_cast<const float*>(plane.data.data()), plane.data.size() * (sizeof(T) / sizeof(float))};
}

// GpuBuffer holds floats; the mesh ids travel bit for bit (the shader reads that binding as uint[]).
std::vector<float> id_bits(const UIntPlane& plane) {
  static_assert(sizeof(uint32_t) == sizeof(float));
  std::vector<float> bits(plane.data.size());
  for (size_t i = 0; i < bits.size(); ++i) bits[i] = std::bit_cast<float>(uint32_t(plane.data[i]));
  return bits;
}

}  // namespace

FloatPlane variance_vulkan(VulkanContext& context, const TemporalOutput& t, const SurfacePlanes& cur,
                           const SvgfParams& params, double* ms) {
  const int w = cur.width(), h = cur.height();
  const auto sized = [&](const auto& p) { return p.width == w && p.height == h; };
  if (!sized(t.moment1) || !sized(t.moment2) || !sized(t.length) || !sized(cur.depth_grad) || !sized(cur.normal) ||
      !sized(cur.mesh))
    throw Error("variance_vulkan: the temporal output and G-buffer planes are not all " + std::to_string(w) + "x" +
                std::to_string(h));
  if (params.variance_min_history < 0)
    throw Error("variance_vulkan: variance_min_history must be >= 0, got " +
                std::to_string(params.variance_min_history));
  FloatPlane sigma2(w, h);
  if (sigma2.data.empty()) return sigma2;

  // Bindings 0-7 in variance.comp's order (variance_shared.h).
  const size_t pixels = sigma2.data.size();
  GpuBuffer moment1(context, pixels), moment2(context, pixels), length(context, pixels), depth(context, pixels),
      depth_grad(context, 2 * pixels), normal(context, 3 * pixels), mesh(context, pixels), out(context, pixels);
  moment1.upload(floats_of(t.moment1));
  moment2.upload(floats_of(t.moment2));
  length.upload(floats_of(t.length));
  depth.upload(floats_of(cur.depth));
  depth_grad.upload(floats_of(cur.depth_grad));
  normal.upload(floats_of(cur.normal));
  mesh.upload(id_bits(cur.mesh));

  ComputePipeline pipeline(context, load_shader("variance"), 8, sizeof(VariancePush));
  const VariancePush push{uint32_t(w),    uint32_t(h),    uint32_t(params.variance_min_history),
                          params.sigma_z, params.sigma_n, params.epsilon};
  // Enough 8x8 workgroups to cover the frame; the shader skips the overhang.
  const uint32_t groups_x = (push.width + kVarianceGroupSizeX - 1) / kVarianceGroupSizeX;
  const uint32_t groups_y = (push.height + kVarianceGroupSizeY - 1) / kVarianceGroupSizeY;
  pipeline.dispatch({&moment1, &moment2, &length, &depth, &depth_grad, &normal, &mesh, &out}, &push, groups_x,
                    groups_y, ms);

  const std::vector<float> result = out.download();
  for (size_t i = 0; i < pixels; ++i) sigma2.data[i] = result[i];
  return sigma2;
}

}  // namespace rtdr
