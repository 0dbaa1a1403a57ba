// The Vulkan port of TRMV's non-planar receiver falloff. See trmv_falloff_gpu.h; the shader is
// filters/trmv/falloff.comp.
#include "gpu/trmv_falloff_gpu.h"

#include "core/error.h"
#include "gpu/svgf_planes.h"
#include "gpu/svgf_shaders.h"

#include <glm/gtc/constants.hpp>

#include <string>

namespace rtdr {

namespace {

static_assert(kTrmvFalloffHalfPi == glm::half_pi<float>(), "the shader's pi/2 is the golden pass's float");

}  // namespace

TrmvFalloffOutput trmv_falloff_vulkan(VulkanContext& context, const TrmvReceiver& receiver, const TrmvMotion& shadow,
                                      const TrmvPreviousPositions& prev, const TrmvParams& params, double* ms) {
  check_trmv_falloff_sizes(receiver, shadow, prev);  // trmv_falloff_pass's checks
  const int w = receiver.position.width, h = receiver.position.height;
  TrmvFalloffOutput out{FloatPlane(w, h), FloatPlane(w, h)};
  if (out.theta.data.empty()) return out;

  // Each optional plane is given or empty; an empty one is one texel the shader never reads (falloff_shared.h).
  const bool has_prev = prev.position.width != 0, has_valid = shadow.valid.width != 0;
  const int pw = has_prev ? prev.position.width : 0, ph = has_prev ? prev.position.height : 0;
  const auto position = plane_buffer(context, w, h, TexelFormat::RGBA32F),
             normal = plane_buffer(context, w, h, TexelFormat::RGBA32F),
             mesh = plane_buffer(context, w, h, TexelFormat::R32UI),
             surface_motion = plane_buffer(context, w, h, TexelFormat::RG32F),
             motion = plane_buffer(context, w, h, TexelFormat::RG32F),
             valid = plane_buffer(context, shadow.valid.width, shadow.valid.height, TexelFormat::R32UI),
             prev_position = plane_buffer(context, pw, ph, TexelFormat::RGBA32F),
             prev_normal = plane_buffer(context, pw, ph, TexelFormat::RGBA32F),
             prev_mesh = plane_buffer(context, pw, ph, TexelFormat::R32UI);
  pack_rgb(receiver.position, *position);
  pack_rgb(receiver.normal, *normal);
  pack_ids(receiver.mesh, *mesh);
  pack_vec2(receiver.motion, *surface_motion);
  pack_vec2(shadow.motion, *motion);
  if (has_valid) pack_ids(shadow.valid, *valid);
  if (has_prev) {
    pack_rgb(prev.position, *prev_position);
    pack_rgb(prev.normal, *prev_normal);
    pack_ids(prev.mesh, *prev_mesh);
  }
  // (theta, alpha^V) per pixel.
  const auto theta_alpha = plane_buffer(context, w, h, TexelFormat::RG32F);

  const TrmvFalloffPush push = trmv_falloff_push(uint32_t(w), uint32_t(h), uint32_t(pw), uint32_t(ph), has_valid, params);
  const TrmvFalloffPlanes planes{position.get(), normal.get(),        mesh.get(),        surface_motion.get(), motion.get(),
                                 valid.get(),    prev_position.get(), prev_normal.get(), prev_mesh.get()};
  run_pass(
      context,
      [&](const SvgfShaders& shaders, ComputeBatch& batch) { shaders.trmv_falloff(batch, planes, *theta_alpha, push); },
      ms);

  out.theta = unpack_channel(*theta_alpha, w, h, 2, 0);
  out.alpha_v = unpack_channel(*theta_alpha, w, h, 2, 1);
  return out;
}

}  // namespace rtdr
