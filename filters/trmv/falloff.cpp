// TRMV's non-planar receiver falloff [TRMV21 Eq. 4]. What the pass computes, its inputs, outputs, units and
// choices: filters/trmv/falloff.h.
#include "filters/trmv/falloff.h"

#include "core/error.h"
#include "core/parallel.h"
#include "filters/trmv/falloff_shared.h"

#include <glm/gtc/constants.hpp>

#include <algorithm>
#include <cmath>
#include <string>

namespace rtdr {
namespace {

// A static shadow: s^V_{i-1} within this relative distance of s_i has no direction (falloff.h); the value and why
// it is 1e-6: filters/trmv/falloff_shared.h, which the Vulkan port (filters/trmv/falloff.comp) reads too.
constexpr float kFalloffSamePointRelative = kTrmvFalloffSamePointRelative;

// No Eq. 4 evidence: theta = pi/2, alpha^V = alpha (falloff.h).
TrmvFalloffPixel no_evidence(float alpha, Probe* probe) {
  note(probe, "alpha^V = alpha", alpha, "no evidence for [TRMV21 Eq. 4]");
  return {glm::half_pi<float>(), alpha};
}

}  // namespace

void check_trmv_falloff_sizes(const TrmvReceiver& r, const TrmvMotion& shadow, const TrmvPreviousPositions& prev) {
  const int w = r.position.width, h = r.position.height;
  if (!has_size(r.normal, w, h) || !has_size(r.mesh, w, h) || !has_size(r.motion, w, h) ||
      !has_size(shadow.motion, w, h) || !empty_or_size(shadow.valid, w, h))
    throw Error("trmv falloff pass: the receiver's and the shadow motion's planes are not all " + std::to_string(w) +
                "x" + std::to_string(h));
  if (prev.position.width != 0 && (!has_size(prev.mesh, prev.position.width, prev.position.height) ||
                                   !has_size(prev.normal, prev.position.width, prev.position.height)))
    throw Error("trmv falloff pass: the previous id.mesh and geonormal are not the previous position's size");
}

float trmv_falloff_gaussian(float x, float sigma) {
  // G(x; 0, sigma) = exp(-x^2 / (2 sigma^2)), "with its peak value normalized to 1" [TRMV21 Eq. 4].
  return std::exp(-(x * x) / (2.0f * sigma * sigma));
}

float trmv_falloff_alpha(float theta, float alpha, float sigma) {
  // alpha^V = 1 - G(theta - pi/2; 0, sigma) (1 - alpha) [TRMV21 Eq. 4].
  return 1.0f - trmv_falloff_gaussian(theta - glm::half_pi<float>(), sigma) * (1.0f - alpha);
}

float trmv_falloff_theta(glm::vec3 s_i, glm::vec3 n_s_i, glm::vec3 s_v_prev) {
  const glm::vec3 d = s_v_prev - s_i;  // the direction s_i -> s^V_{i-1} [TRMV21 Sec. 4.1]
  const float len = glm::length(d);
  // A static shadow: no direction; it lies on the plane as far as anyone can tell (falloff.h).
  if (len < kFalloffSamePointRelative * (1.0f + glm::length(s_i))) return glm::half_pi<float>();
  // cos theta = n(s_i) . d / (|n(s_i)| |d|), clamped into [-1, 1] against rounding before acos.
  const float cos_theta = std::clamp(glm::dot(n_s_i, d) / (glm::length(n_s_i) * len), -1.0f, 1.0f);
  return std::acos(cos_theta);
}

bool trmv_falloff_carry_back(const TrmvReceiver& receiver, const TrmvPreviousPositions& prev, int x, int y,
                             glm::vec3& s, glm::vec3& n) {
  if (prev.position.width == 0) return false;
  // x_i + m: where the receiver point was in frame i-1 [TRMV21 Eq. 1]; the pixel holding it (range first, so that
  // floor() of a far-off vector stays within int range; false for NaN too).
  const glm::vec2 x_prev = glm::vec2(float(x) + 0.5f, float(y) + 0.5f) + receiver.motion.at(x, y);
  if (!(x_prev.x >= 0.0f && x_prev.y >= 0.0f && x_prev.x < float(prev.position.width) &&
        x_prev.y < float(prev.position.height)))
    return false;
  const glm::ivec2 q = glm::ivec2(glm::floor(x_prev));
  if (prev.mesh.at(q.x, q.y) != receiver.mesh.at(x, y)) return false;  // another surface there: not carried
  // T^{-1} s_i and n(T^{-1} s_i): the receiver's face in frame i-1 [TRMV21 Sec. 4.1, "inverse transformed"].
  s = prev.position.at(q.x, q.y);
  n = prev.normal.at(q.x, q.y);
  return true;
}

TrmvFalloffPixel trmv_falloff_pixel(const TrmvReceiver& receiver, const TrmvMotion& shadow,
                                    const TrmvPreviousPositions& prev, const TrmvParams& params, int x, int y,
                                    Probe* probe) {
  note_group(probe, "falloff");
  const bool covered = receiver.mesh.at(x, y) != kInvalidId;
  const bool valid = shadow.valid.width == 0 || shadow.valid.at(x, y) != 0;
  note(probe, "covered", float(covered));
  note(probe, "shadow vector valid", float(valid), "[TRMV21 Eq. 3]");
  if (!covered || !valid || prev.position.width == 0) return no_evidence(params.alpha, probe);
  // x^V_{i-1} = x_i + m^V: where the shadow point was in the previous frame [TRMV21 Eq. 3].
  const glm::vec2 x_v = glm::vec2(float(x) + 0.5f, float(y) + 0.5f) + shadow.motion.at(x, y);
  note(probe, "x^V_{i-1}", x_v, "[TRMV21 Eq. 3]");
  // The pixel containing x^V_{i-1}, whose centre is nearest to it. The range test comes first, so that floor()
  // of a far-off vector stays within int range (false for NaN too).
  const bool near = x_v.x >= 0.0f && x_v.y >= 0.0f && x_v.x < float(prev.position.width) &&
                    x_v.y < float(prev.position.height);
  if (!near) return no_evidence(params.alpha, probe);
  const glm::ivec2 q = glm::ivec2(glm::floor(x_v));
  if (prev.mesh.at(q.x, q.y) == kInvalidId) return no_evidence(params.alpha, probe);
  glm::vec3 s_i = receiver.position.at(x, y);
  glm::vec3 n_s_i = receiver.normal.at(x, y);
  // The receiver carried back to frame i-1, where s^V_{i-1} lies (falloff.h); else the current planes.
  const bool carried = params.falloff_carry != 0 && trmv_falloff_carry_back(receiver, prev, x, y, s_i, n_s_i);
  note(probe, "carried back", float(carried), "[TRMV21 Sec. 4.1] n(s_i) inverse transformed");
  // s^V_{i-1}: "the shading point of pixel x^V_{i-1}" in the previous frame [TRMV21 Sec. 4.1].
  const glm::vec3 s_v = prev.position.at(q.x, q.y);
  note(probe, "s_i", s_i);
  note(probe, "n(s_i)", n_s_i);
  note(probe, "s^V_{i-1}", s_v, "[TRMV21 Sec. 4.1] previous position, nearest pixel");
  TrmvFalloffPixel out;
  out.theta = trmv_falloff_theta(s_i, n_s_i, s_v);
  note(probe, "theta", out.theta, "[TRMV21 Eq. 4] angle(n(s_i), s_i -> s^V_{i-1}), radians");
  out.alpha_v = trmv_falloff_alpha(out.theta, params.alpha, params.falloff_sigma);
  note(probe, "alpha^V", out.alpha_v, "[TRMV21 Eq. 4] 1 - G(theta - pi/2; 0, sigma) (1 - alpha)");
  return out;
}

TrmvFalloffOutput trmv_falloff_pass(const TrmvReceiver& receiver, const TrmvMotion& shadow,
                                    const TrmvPreviousPositions& prev, const TrmvParams& params) {
  check_trmv_falloff_sizes(receiver, shadow, prev);
  const int w = receiver.position.width, h = receiver.position.height;
  TrmvFalloffOutput out{FloatPlane(w, h), FloatPlane(w, h)};
  parallel_rows(h, [&](int y) {
    for (int x = 0; x < w; ++x) {
      const TrmvFalloffPixel p = trmv_falloff_pixel(receiver, shadow, prev, params, x, y);
      out.theta.at(x, y) = p.theta;
      out.alpha_v.at(x, y) = p.alpha_v;
    }
  });
  return out;
}

}  // namespace rtdr
