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

TrmvTemporalOutput trmv_temporal_vulkan(VulkanContext& context, const RgbPlane& filtered, const UIntPlane& mesh,
                                        const TrmvMotion& motion, const TrmvHistory& prev, const FloatPlane& alpha,
                                        const TrmvParams& params, double* ms) {
  check_trmv_temporal_sizes(filtered, mesh, motion, prev, alpha);  // trmv_temporal_pass's checks
  if (params.clamp_radius < 0)
    throw Error("trmv_temporal_vulkan: clamp_radius must be >= 0, got " + std::to_string(params.clamp_radius));
  const int w = filtered.width, h = filtered.height;
  TrmvTemporalOutput out{RgbPlane(w, h), RgbPlane(w, h), RgbPlane(w, h), FloatPlane(w, h)};
  if (out.alpha.data.empty()) return out;

  // Each optional plane is given or empty; an empty one is one texel the shader never reads (temporal_shared.h).
  const bool has_history = prev.color.width != 0, has_valid = motion.valid.width != 0,
             has_reshaded = motion.reshaded.width != 0, has_alpha = alpha.width != 0;
  const int pw = has_history ? prev.color.width : 0, ph = has_history ? prev.color.height : 0;
  const auto filtered_buffer = plane_buffer(context, w, h, TexelFormat::RGBA32F),
             alpha_buffer = plane_buffer(context, alpha.width, alpha.height, TexelFormat::RG32F),
             mesh_buffer = plane_buffer(context, w, h, TexelFormat::R32UI),
             motion_buffer = plane_buffer(context, w, h, TexelFormat::RG32F),
             valid_buffer = plane_buffer(context, motion.valid.width, motion.valid.height, TexelFormat::R32UI),
             reshaded_buffer = plane_buffer(context, motion.reshaded.width, motion.reshaded.height,
                                            TexelFormat::RGBA32F),
             prev_color = plane_buffer(context, pw, ph, TexelFormat::RGBA32F),
             prev_mesh = plane_buffer(context, pw, ph, TexelFormat::R32UI);
  pack_rgb(filtered, *filtered_buffer);
  // The alpha plane as the falloff port writes it, (theta, alpha^V); theta is not read.
  if (has_alpha)
    for (size_t i = 0; i < alpha.data.size(); ++i) alpha_buffer->data()[2 * i + 1] = alpha.data[i];
  pack_ids(mesh, *mesh_buffer);
  pack_vec2(motion.motion, *motion_buffer);
  if (has_valid) pack_ids(motion.valid, *valid_buffer);
  // (re-shaded history, 1 where it is valid, else 0).
  if (has_reshaded) {
    pack_rgb(motion.reshaded, *reshaded_buffer);
    for (size_t i = 0; i < motion.reshaded_valid.data.size(); ++i)
      set_w(*reshaded_buffer, i, motion.reshaded_valid.data[i] != 0 ? 1.0f : 0.0f);
  }
  if (has_history) {
    pack_rgb(prev.color, *prev_color);
    pack_ids(prev.mesh, *prev_mesh);
  }
  // (cbar_i, alpha), then the fetched and the clamped history.
  const auto color_alpha = plane_buffer(context, w, h, TexelFormat::RGBA32F),
             fetched = plane_buffer(context, w, h, TexelFormat::RGBA32F),
             clamped = plane_buffer(context, w, h, TexelFormat::RGBA32F);

  const TrmvTemporalPush push = trmv_temporal_push(uint32_t(w), uint32_t(h), uint32_t(pw), uint32_t(ph), has_valid,
                                                   has_reshaded, has_alpha, params);
  const TrmvTemporalPlanes planes{filtered_buffer.get(), mesh_buffer.get(), motion_buffer.get(),
                                  valid_buffer.get(),    reshaded_buffer.get(), prev_color.get(),
                                  prev_mesh.get(),       alpha_buffer.get()};
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
