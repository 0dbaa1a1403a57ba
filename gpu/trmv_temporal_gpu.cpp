// The Vulkan port of TRMV's temporal pass. See trmv_temporal_gpu.h; the shader is filters/trmv/temporal.comp.
#include "gpu/trmv_temporal_gpu.h"

#include "core/error.h"
#include "gpu/svgf_planes.h"
#include "gpu/svgf_shaders.h"

#include <memory>
#include <string>

namespace rtdr {

namespace {

// Channel w of record i of a buffer of 4-float records (pack_rgb wrote 0 there).
void set_w(GpuBuffer& records, size_t i, float w) { records.data()[4 * i + 3] = w; }

}  // namespace

void pack_trmv_vector(const TrmvMotion& motion, GpuBuffer& out) {
  const size_t pixels = motion.motion.data.size();
  float* d = out.data();
  for (size_t i = 0; i < pixels; ++i) {
    const bool valid = motion.valid.width == 0 || motion.valid.data[i] != 0;
    const uint32_t test = motion.test.width == 0 ? kTrmvTestNone : motion.test.data[i];
    d[4 * i] = motion.motion.data[i].x;
    d[4 * i + 1] = motion.motion.data[i].y;
    d[4 * i + 2] = valid ? float(1u + test) : 0.0f;  // the code (temporal_shared.h)
    d[4 * i + 3] = 0.0f;
  }
}

void pack_trmv_reshaded(const TrmvMotion& motion, GpuBuffer& out) {
  pack_rgb(motion.reshaded, out);
  for (size_t i = 0; i < motion.reshaded_valid.data.size(); ++i)
    set_w(out, i, motion.reshaded_valid.data[i] != 0 ? 1.0f : 0.0f);
}

TrmvTemporalOutput trmv_temporal_vulkan(VulkanContext& context, const RgbPlane& filtered, const SurfacePlanes& cur,
                                        const TrmvMotion& motion, const TrmvHistory& prev, const FloatPlane& alpha,
                                        const TrmvParams& params, const SvgfParams& svgf, double* ms) {
  check_trmv_temporal_sizes(filtered, cur, motion, prev, alpha);  // trmv_temporal_pass's checks
  if (params.clamp_radius < 0)
    throw Error("trmv_temporal_vulkan: clamp_radius must be >= 0, got " + std::to_string(params.clamp_radius));
  const int w = filtered.width, h = filtered.height;
  TrmvTemporalOutput out{RgbPlane(w, h), RgbPlane(w, h), RgbPlane(w, h), FloatPlane(w, h)};
  if (out.alpha.data.empty()) return out;

  // Each optional plane is given or empty; an empty one is one texel the shader never reads (temporal_shared.h).
  const bool has_history = prev.color.width != 0, has_reshaded = motion.reshaded.width != 0,
             has_alpha = alpha.width != 0;
  const int pw = has_history ? prev.color.width : 0, ph = has_history ? prev.color.height : 0;
  const auto rgba = [&](int pw_, int ph_) { return plane_buffer(context, pw_, ph_, TexelFormat::RGBA32F); };
  const auto filtered_buffer = rgba(w, h), surface = rgba(w, h), vector = rgba(w, h),
             reshaded_buffer = rgba(motion.reshaded.width, motion.reshaded.height), prev_color = rgba(pw, ph),
             prev_surface = rgba(pw, ph);
  const auto alpha_buffer = plane_buffer(context, alpha.width, alpha.height, TexelFormat::RG32F),
             mesh_buffer = plane_buffer(context, w, h, TexelFormat::R32UI),
             depth_grad = plane_buffer(context, w, h, TexelFormat::RG32F),
             prev_mesh = plane_buffer(context, pw, ph, TexelFormat::R32UI);
  pack_rgb(filtered, *filtered_buffer);
  // The alpha plane as the falloff port writes it, (theta, alpha^V); theta is not read.
  if (has_alpha)
    for (size_t i = 0; i < alpha.data.size(); ++i) alpha_buffer->data()[2 * i + 1] = alpha.data[i];
  pack_ids(cur.mesh, *mesh_buffer);
  pack_surface(cur, *surface);
  pack_vec2(cur.depth_grad, *depth_grad);
  pack_trmv_vector(motion, *vector);
  if (has_reshaded) pack_trmv_reshaded(motion, *reshaded_buffer);
  if (has_history) {
    pack_rgb(prev.color, *prev_color);
    pack_ids(prev.surface.mesh, *prev_mesh);
    pack_surface(prev.surface, *prev_surface);
  }
  // (cbar_i, alpha), then the fetched and the clamped history.
  const auto color_alpha = rgba(w, h), fetched = rgba(w, h), clamped = rgba(w, h);

  const TrmvTemporalPush push = trmv_temporal_push(uint32_t(w), uint32_t(h), uint32_t(pw), uint32_t(ph), has_reshaded,
                                                   has_alpha, params, svgf);
  const TrmvTemporalPlanes planes{filtered_buffer.get(), mesh_buffer.get(), surface.get(),   depth_grad.get(),
                                  vector.get(),          reshaded_buffer.get(), prev_color.get(), prev_mesh.get(),
                                  prev_surface.get(),    alpha_buffer.get()};
  run_pass(
      context,
      [&](const SvgfShaders& shaders, ComputeBatch& batch) {
        shaders.trmv_temporal(batch, planes, *color_alpha, *fetched, *clamped, push);
      },
      ms);

  out.color = unpack_rgb(*color_alpha, w, h);
  out.alpha = unpack_channel(*color_alpha, w, h, 4, 3);
  out.fetched = unpack_rgb(*fetched, w, h);
  out.clamped = unpack_rgb(*clamped, w, h);
  return out;
}

}  // namespace rtdr
