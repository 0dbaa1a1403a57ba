// TRMV's temporal blend [TRMV21 Eq. 2] and history clamp [TRMV21 Sec. 5]. What the pass computes, its inputs,
// outputs and choices: filters/trmv/temporal.h.
#include "filters/trmv/temporal.h"

#include "core/error.h"
#include "core/parallel.h"
#include "filters/svgf/temporal.h"
#include "filters/trmv/spatial.h"

#include <algorithm>
#include <cmath>
#include <string>

namespace rtdr {
namespace {

// No history: alpha = 1 and cbar_i = c~_i; the fetched and clamped histories are 0 (temporal.h).
TrmvTemporalPixel without_history(glm::vec3 c, Probe* probe) {
  TrmvTemporalPixel out;
  out.color = c;
  out.alpha = 1.0f;
  note_group(probe, "blend");
  note(probe, "alpha", out.alpha, "no history: alpha = 1");
  note(probe, "cbar_i = c~_i", out.color, "[TRMV21 Eq. 2] with alpha = 1");
  return out;
}

}  // namespace

void check_trmv_temporal_sizes(const RgbPlane& filtered, const SurfacePlanes& cur, const TrmvMotion& motion,
                               const TrmvHistory& prev, const FloatPlane& alpha) {
  const int w = filtered.width, h = filtered.height;
  check_trmv_surface_sizes(w, h, cur, "trmv temporal pass");
  if (!has_size(cur.motion, w, h) || !has_size(motion.motion, w, h) || !empty_or_size(motion.valid, w, h) ||
      !empty_or_size(motion.test, w, h) || !empty_or_size(alpha, w, h) || !empty_or_size(motion.reshaded, w, h) ||
      motion.reshaded_valid.width != motion.reshaded.width || motion.reshaded_valid.height != motion.reshaded.height)
    throw Error("trmv temporal pass: the motion, validity, test, alpha and re-shaded planes are not all " +
                std::to_string(w) + "x" + std::to_string(h) + " like c~");
  if (prev.color.width != 0)
    check_trmv_surface_sizes(prev.color.width, prev.color.height, prev.surface, "trmv temporal pass (history)");
}

bool trmv_tap_passes(uint32_t test, const SurfacePlanes& cur, const SurfacePlanes& prev, int x, int y, glm::ivec2 q,
                     glm::vec2 p_prev, const SvgfParams& svgf, Probe* probe) {
  // Outside the previous image, or no surface there: never a history.
  if (!inside(prev.depth, q.x, q.y) || prev.mesh.at(q.x, q.y) == kInvalidId) return false;
  // What the vector claims [TRMV21 Sec. 4] (temporal.h): none for the shadow vector and "Trad. (No clamp)".
  if (test == kTrmvTestNone) return true;
  // The dual and glossy vectors claim the same mesh (temporal.h).
  if (test == kTrmvTestMesh) return prev.mesh.at(q.x, q.y) == cur.mesh.at(x, y);
  // The surface vector claims the same surface point: SVGF's consistency test [SVGF17 Sec. 4.1].
  return temporal_tap_consistent(cur, prev, x, y, q, p_prev, svgf, probe);
}

bool trmv_history_taps(const SurfacePlanes& prev, glm::vec2 p_prev, const SurfacePlanes& cur, int x, int y,
                       uint32_t test, const SvgfParams& svgf, TrmvHistoryTaps& taps, Probe* probe) {
  note_group(probe, "fetch");
  note(probe, "x_{i-1}", p_prev, "[TRMV21 Eq. 2] pixel centre + m");
  note(probe, "test", float(test), "0 none, 1 same mesh, 2 SVGF's consistency [SVGF17 Sec. 4.1]");
  taps = {};
  const int w = prev.width(), h = prev.height();
  // More than a pixel off the previous image no tap can be inside (false for NaN too); this also keeps
  // floor(p_prev) within int range for far-off vectors such as kMotionBehindCamera.
  if (!(p_prev.x > -1.0f && p_prev.y > -1.0f && p_prev.x < float(w) + 1.0f && p_prev.y < float(h) + 1.0f)) return false;
  // Pixel centres sit at integer + 0.5: the four centres around p_prev start at floor(p_prev - 0.5), and f is
  // where p_prev lies in their square, the bilinear parameters.
  const glm::vec2 s = p_prev - 0.5f;
  const glm::ivec2 q00 = glm::ivec2(glm::floor(s));
  const glm::vec2 f = s - glm::floor(s);
  float sum_w = 0.0f;
  for (int k = 0; k < 4; ++k) {
    const glm::ivec2 d(k & 1, k >> 1);  // (0, 0), (1, 0), (0, 1), (1, 1)
    const glm::ivec2 q = q00 + d;
    // Outside the previous image, no surface there, or not what the vector claims: dropped.
    if (!trmv_tap_passes(test, cur, prev, x, y, q, p_prev, svgf)) continue;
    // Bilinear weight: (1 - f) towards the near centre, f towards the far one, on each axis.
    const float w_q = (d.x ? f.x : 1.0f - f.x) * (d.y ? f.y : 1.0f - f.y);
    taps.q[taps.count] = q;
    taps.w[taps.count] = w_q;
    ++taps.count;
    sum_w += w_q;
  }
  note(probe, "sum of kept bilinear weights", sum_w);
  if (!(sum_w > 0.0f)) return false;
  for (int k = 0; k < taps.count; ++k) taps.w[k] /= sum_w;  // renormalised over the kept taps
  return true;
}

glm::vec3 trmv_apply_taps(const RgbPlane& plane, const TrmvHistoryTaps& taps) {
  // cbar_{i-1}(x_{i-1}) = sum_q w_q cbar_{i-1}(q), the weights renormalised over the kept taps.
  glm::vec3 sum(0.0f);
  for (int k = 0; k < taps.count; ++k) sum += taps.w[k] * plane.at(taps.q[k].x, taps.q[k].y);
  return sum;
}

bool trmv_fetch_history(const TrmvHistory& prev, glm::vec2 p_prev, const SurfacePlanes& cur, int x, int y,
                        uint32_t test, const SvgfParams& svgf, glm::vec3& out, Probe* probe) {
  TrmvHistoryTaps taps;
  if (!trmv_history_taps(prev.surface, p_prev, cur, x, y, test, svgf, taps, probe)) return false;
  out = trmv_apply_taps(prev.color, taps);
  note(probe, "cbar_{i-1}(x_{i-1})", out, "[TRMV21 Eq. 2] bilinear, renormalised");
  return true;
}

glm::vec3 trmv_clamp_history(glm::vec3 history, const RgbPlane& filtered, const SurfacePlanes& cur, float gamma,
                             int radius, bool same_surface, const SvgfParams& svgf, int x, int y, Probe* probe) {
  note_group(probe, "clamp");
  note(probe, "gamma", gamma, "[TRMV21 Sec. 5] 3: TRMV, 1: Salvi's, 0: off");
  if (!(gamma > 0.0f)) return history;  // gamma = 0: no clamp ("Trad. (No clamp)")
  // The mean and the second raw moment of c~ over the window's pixels that see a surface (and with
  // `same_surface`, the centre's: SVGF's consistency test with this frame in place of the previous one, q - p the
  // offset), per channel.
  const glm::vec2 centre(float(x) + 0.5f, float(y) + 0.5f);
  glm::vec3 sum(0.0f), sum_sq(0.0f);
  int n = 0;
  for (int dy = -radius; dy <= radius; ++dy)
    for (int dx = -radius; dx <= radius; ++dx) {
      const int qx = x + dx, qy = y + dy;
      if (!inside(filtered, qx, qy) || !cur.covered(qx, qy)) continue;
      if (same_surface && !temporal_tap_consistent(cur, cur, x, y, {qx, qy}, centre, svgf)) continue;
      const glm::vec3 c = filtered.at(qx, qy);
      sum += c;
      sum_sq += c * c;
      ++n;
    }
  const glm::vec3 mu = sum / float(n);  // n >= 1: the centre sees a surface, and is its own surface
  // sigma = sqrt(E[c^2] - mu^2), the population standard deviation (rounding may make the difference < 0).
  const glm::vec3 sigma = glm::sqrt(glm::max(sum_sq / float(n) - mu * mu, glm::vec3(0.0f)));
  note(probe, "window pixels", float(n));
  note(probe, "mu", mu, "[TRMV21 Sec. 5] mean of c~ over the window");
  note(probe, "sigma", sigma, "[TRMV21 Sec. 5] std of c~ over the window");
  // cbar*_{i-1} = clamp(cbar_{i-1}, mu - gamma sigma, mu + gamma sigma), per channel [TRMV21 Sec. 5].
  const glm::vec3 clamped = glm::clamp(history, mu - gamma * sigma, mu + gamma * sigma);
  note(probe, "cbar*_{i-1}", clamped, "[TRMV21 Sec. 5] clamped to mu +- gamma sigma");
  return clamped;
}

TrmvTemporalPixel trmv_temporal_pixel(const RgbPlane& filtered, const SurfacePlanes& cur, const TrmvMotion& motion,
                                      const TrmvHistory& prev, const FloatPlane& alpha, const TrmvParams& params,
                                      const SvgfParams& svgf, int x, int y, Probe* probe) {
  note_group(probe, "input");
  const glm::vec3 c = filtered.at(x, y);
  note(probe, "c~_i", c, "[TRMV21 Eq. 2] spatially filtered");
  const bool covered = cur.covered(x, y);
  const bool first_frame = prev.color.width == 0;
  const bool valid = motion.valid.width == 0 || motion.valid.at(x, y) != 0;
  note(probe, "covered", float(covered));
  note(probe, "first frame", float(first_frame));
  note(probe, "vector valid", float(valid));
  if (!covered || first_frame || !valid) return without_history(c, probe);
  TrmvTemporalPixel out;
  if (motion.reshaded_valid.width != 0 && motion.reshaded_valid.at(x, y) != 0) {
    // A disoccluded pixel's history, re-shaded from the cones at x^O [TRMV21 Sec. 4.3, Eq. 11] (reshade.h).
    out.fetched = motion.reshaded.at(x, y);
    note_group(probe, "fetch");
    note(probe, "cbar_{i-1}, re-shaded", out.fetched, "[TRMV21 Eq. 11] from the cones at x^O");
  } else {
    // x_{i-1} = x_i + m(x_i): where this pixel's content was in the previous frame [TRMV21 Eq. 1].
    const glm::vec2 p_prev = glm::vec2(float(x) + 0.5f, float(y) + 0.5f) + motion.motion.at(x, y);
    const uint32_t test = motion.test.width == 0 ? kTrmvTestNone : motion.test.at(x, y);
    if (!trmv_fetch_history(prev, p_prev, cur, x, y, test, svgf, out.fetched, probe)) return without_history(c, probe);
  }
  out.clamped = trmv_clamp_history(out.fetched, filtered, cur, params.clamp_gamma, params.clamp_radius,
                                   params.history_test != 0, svgf, x, y, probe);
  note_group(probe, "blend");
  out.alpha = alpha.width == 0 ? params.alpha : alpha.at(x, y);
  note(probe, "alpha", out.alpha, "[TRMV21 Eq. 2] alpha, or alpha^V [TRMV21 Eq. 4]");
  // cbar_i(x_i) = alpha c~_i(x_i) + (1 - alpha) cbar*_{i-1}(x_{i-1})  [TRMV21 Eq. 2], the history clamped.
  out.color = out.alpha * c + (1.0f - out.alpha) * out.clamped;
  note(probe, "cbar_i", out.color, "[TRMV21 Eq. 2]");
  return out;
}

TrmvTemporalOutput trmv_temporal_pass(const RgbPlane& filtered, const SurfacePlanes& cur, const TrmvMotion& motion,
                                      const TrmvHistory& prev, const FloatPlane& alpha, const TrmvParams& params,
                                      const SvgfParams& svgf) {
  check_trmv_temporal_sizes(filtered, cur, motion, prev, alpha);
  const int w = filtered.width, h = filtered.height;
  TrmvTemporalOutput out{RgbPlane(w, h), RgbPlane(w, h), RgbPlane(w, h), FloatPlane(w, h)};
  parallel_rows(h, [&](int y) {
    for (int x = 0; x < w; ++x) {
      const TrmvTemporalPixel p = trmv_temporal_pixel(filtered, cur, motion, prev, alpha, params, svgf, x, y);
      out.color.at(x, y) = p.color;
      out.fetched.at(x, y) = p.fetched;
      out.clamped.at(x, y) = p.clamped;
      out.alpha.at(x, y) = p.alpha;
    }
  });
  return out;
}

}  // namespace rtdr
