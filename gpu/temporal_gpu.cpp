// The Vulkan port of SVGF temporal accumulation. See temporal_gpu.h; the shader is filters/svgf/temporal.comp.
#include "gpu/temporal_gpu.h"

#include "core/error.h"
#include "gpu/svgf_planes.h"
#include "gpu/svgf_shaders.h"

#include <memory>
#include <string>

namespace rtdr {

namespace {

template <class P>
bool sized(const P& p, int w, int h) {
  return p.width == w && p.height == h;
}

bool surface_sized(const SurfacePlanes& s, int w, int h) {
  return sized(s.depth, w, h) && sized(s.depth_grad, w, h) && sized(s.normal, w, h) && sized(s.mesh, w, h);
}

}  // namespace

TemporalOutput temporal_vulkan(VulkanContext& context, const RgbPlane& noisy, const SurfacePlanes& cur,
                               const TemporalHistory& prev, const SvgfParams& params, double* ms,
                               const TemporalAdaptive* adaptive) {
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
  const auto frame_sized = [&](const FloatPlane* p) { return p && sized(*p, w, h); };
  if (adaptive && !(frame_sized(adaptive->lambda) && frame_sized(adaptive->alpha) &&
                    frame_sized(adaptive->alpha_moments)))
    throw Error("temporal_vulkan: the lambda and alpha planes are not the frame's size");
  if (params.max_history < 0)
    throw Error("temporal_vulkan: max_history must be >= 0, got " + std::to_string(params.max_history));
  TemporalOutput out{RgbPlane(w, h), FloatPlane(w, h), FloatPlane(w, h), FloatPlane(w, h)};
  if (out.moment1.data.empty()) return out;

  const int hw = has_history ? pw : 0, hh = has_history ? ph : 0;
  const auto noisy_buffer = illumination_buffer(context, w, h),
             surface = plane_buffer(context, w, h, TexelFormat::RGBA32F),
             grad = plane_buffer(context, w, h, TexelFormat::RG32F),
             mesh = plane_buffer(context, w, h, TexelFormat::R32UI),
             motion = plane_buffer(context, w, h, TexelFormat::RG32F),
             prev_color = illumination_buffer(context, hw, hh),
             prev_moments = plane_buffer(context, hw, hh, TexelFormat::RGBA32F),
             prev_surface = plane_buffer(context, hw, hh, TexelFormat::RGBA32F),
             prev_mesh = plane_buffer(context, hw, hh, TexelFormat::R32UI);
  for (const int stream : {kDirectStream, kIndirectStream}) pack_illumination(stream, noisy, nullptr, *noisy_buffer);
  pack_surface(cur, *surface);
  pack_vec2(cur.depth_grad, *grad);
  pack_ids(cur.mesh, *mesh);
  pack_vec2(cur.motion, *motion);
  if (has_history) {
    for (const int stream : {kDirectStream, kIndirectStream})
      pack_illumination(stream, prev.color, nullptr, *prev_color);
    pack_moments(prev.moment1, prev.moment2, prev.length, *prev_moments);
    pack_surface(prev.surface, *prev_surface);
    pack_ids(prev.surface.mesh, *prev_mesh);
  }
  // Illumination records C' (both streams), then moments records (direct, indirect).
  const std::unique_ptr<GpuBuffer> outputs[3] = {illumination_buffer(context, w, h),
                                                 plane_buffer(context, w, h, TexelFormat::RGBA32F),
                                                 plane_buffer(context, w, h, TexelFormat::RGBA32F)};

  // A-SVGF's (lambda_max, alpha_i, alpha_mu_i, 0) records, as the adaptive alpha port writes them. Without
  // adaptive: one unread one.
  const auto weights = plane_buffer(context, adaptive ? w : 1, adaptive ? h : 1, TexelFormat::RGBA32F);
  if (adaptive)
    for (size_t i = 0; i < adaptive->lambda->data.size(); ++i) {
      weights->data()[4 * i + 0] = adaptive->lambda->data[i];
      weights->data()[4 * i + 1] = adaptive->alpha->data[i];
      weights->data()[4 * i + 2] = adaptive->alpha_moments->data[i];
    }

  TemporalPush push = temporal_push(uint32_t(w), uint32_t(h), uint32_t(hw), uint32_t(hh), params);
  push.adaptive = adaptive ? 1u : 0u;
  push.restart_history = adaptive && adaptive->restart_history ? 1u : 0u;
  // Both streams hold the same values; the indirect stream's outputs are not read back.
  run_pass(
      context,
      [&](const SvgfShaders& shaders, ComputeBatch& batch) {
        shaders.temporal(batch, *noisy_buffer, {surface.get(), grad.get(), mesh.get(), motion.get()},
                         {prev_color.get(), {prev_moments.get(), prev_moments.get()}, prev_surface.get(),
                          prev_mesh.get()},
                         *outputs[0], {outputs[1].get(), outputs[2].get()}, {weights.get(), weights.get()}, push);
      },
      ms);

  out.color = unpack_illumination(*outputs[0], w, h, kDirectStream);
  out.moment1 = unpack_channel(*outputs[1], w, h, 4, 0);
  out.moment2 = unpack_channel(*outputs[1], w, h, 4, 1);
  out.length = unpack_channel(*outputs[1], w, h, 4, 2);
  return out;
}

}  // namespace rtdr
