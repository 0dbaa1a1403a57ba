// The Vulkan port of SVGF temporal accumulation. See temporal_gpu.h; the shader is filters/svgf/temporal.comp.
#include "gpu/temporal_gpu.h"

#include "core/error.h"
#include "filters/svgf/temporal_shared.h"
#include "gpu/compute.h"

#include <bit>
#include <memory>
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
std::vector<float> floats_of(const Plane<T>& plane) {
  const float* first = reinterpret_cast<const float*>(plane.data.data());
  return std::vector<float>(first, first + plane.data.size() * (sizeof(T) / sizeof(float)));
}

// GpuBuffer holds floats; the mesh ids travel bit for bit (the shader reads those bindings as uint[]).
std::vector<float> floats_of(const UIntPlane& plane) {
  static_assert(sizeof(uint32_t) == sizeof(float));
  std::vector<float> bits(plane.data.size());
  for (size_t i = 0; i < bits.size(); ++i) bits[i] = std::bit_cast<float>(uint32_t(plane.data[i]));
  return bits;
}

// A buffer holding `values`; an empty plane (the first frame's history) gets one unread float, as a binding
// needs a buffer.
std::unique_ptr<GpuBuffer> input_buffer(VulkanContext& context, std::vector<float> values) {
  if (values.empty()) values.push_back(0.0f);
  auto buffer = std::make_unique<GpuBuffer>(context, values.size());
  buffer->upload(values);
  return buffer;
}

template <class P>
bool sized(const P& p, int w, int h) {
  return p.width == w && p.height == h;
}

bool surface_sized(const SurfacePlanes& s, int w, int h) {
  return sized(s.depth, w, h) && sized(s.depth_grad, w, h) && sized(s.normal, w, h) && sized(s.mesh, w, h);
}

}  // namespace

TemporalOutput temporal_vulkan(VulkanContext& context, const RgbPlane& noisy, const SurfacePlanes& cur,
                               const TemporalHistory& prev, const SvgfParams& params, double* ms) {
  // The size checks of temporal_pass (temporal.cpp's check_sizes).
  const int w = noisy.width, h = noisy.height;
  if (!surface_sized(cur, w, h) || !sized(cur.motion, w, h))
    throw Error("temporal_vulkan: the current G-buffer planes are not all " + std::to_string(w) + "x" +
                std::to_string(h) + " like the noisy colour");
  const bool has_history = prev.color.width != 0;
  const int pw = prev.color.width, ph = prev.color.height;
  if (has_history && (!sized(prev.moment1, pw, ph) || !sized(prev.moment2, pw, ph) || !sized(prev.length, pw, ph) ||
                      !surface_sized(prev.surface, pw, ph)))
    throw Error("temporal_vulkan: the history planes are not all " + std::to_string(pw) + "x" + std::to_string(ph) +
                " like the history colour");
  if (params.max_history < 0)
    throw Error("temporal_vulkan: max_history must be >= 0, got " + std::to_string(params.max_history));
  TemporalOutput out{RgbPlane(w, h), FloatPlane(w, h), FloatPlane(w, h), FloatPlane(w, h)};
  if (out.moment1.data.empty()) return out;

  // Bindings 0-16 in temporal.comp's order (temporal_shared.h).
  std::vector<std::unique_ptr<GpuBuffer>> buffers;
  for (std::vector<float> values :
       {floats_of(noisy), floats_of(cur.depth), floats_of(cur.depth_grad), floats_of(cur.normal),
        floats_of(cur.mesh), floats_of(cur.motion), floats_of(prev.color), floats_of(prev.moment1),
        floats_of(prev.moment2), floats_of(prev.length), floats_of(prev.surface.depth),
        floats_of(prev.surface.normal), floats_of(prev.surface.mesh)})
    buffers.push_back(input_buffer(context, std::move(values)));
  const size_t pixels = out.moment1.data.size();
  for (const size_t floats : {3 * pixels, pixels, pixels, pixels})
    buffers.push_back(std::make_unique<GpuBuffer>(context, floats));
  std::vector<const GpuBuffer*> bindings;
  for (const auto& buffer : buffers) bindings.push_back(buffer.get());
  if (bindings.size() != kTemporalBufferCount) throw Error("temporal_vulkan: binding count mismatch");

  ComputePipeline pipeline(context, load_shader("temporal"), kTemporalBufferCount, sizeof(TemporalPush));
  const TemporalPush push{uint32_t(w),
                          uint32_t(h),
                          uint32_t(has_history ? pw : 0),
                          uint32_t(has_history ? ph : 0),
                          has_history ? 1u : 0u,
                          uint32_t(params.max_history),
                          params.alpha,
                          params.alpha_moments,
                          params.temporal_depth_relative,
                          params.temporal_normal_cosine};
  // Enough 8x8 workgroups to cover the frame; the shader skips the overhang.
  const uint32_t groups_x = (push.width + kTemporalGroupSizeX - 1) / kTemporalGroupSizeX;
  const uint32_t groups_y = (push.height + kTemporalGroupSizeY - 1) / kTemporalGroupSizeY;
  pipeline.dispatch(bindings, &push, groups_x, groups_y, ms);

  const std::vector<float> color = buffers[13]->download(), moment1 = buffers[14]->download(),
                           moment2 = buffers[15]->download(), length = buffers[16]->download();
  for (size_t i = 0; i < pixels; ++i) {
    out.color.data[i] = glm::vec3(color[3 * i], color[3 * i + 1], color[3 * i + 2]);
    out.moment1.data[i] = moment1[i];
    out.moment2.data[i] = moment2[i];
    out.length.data[i] = length[i];
  }
  return out;
}

}  // namespace rtdr
