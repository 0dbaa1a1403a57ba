// SVGF temporal accumulation [SVGF17 Sec. 4.1, 4.2]. What the pass computes, its inputs, outputs, thresholds
// and deviations from the paper: filters/svgf/temporal.h.
#include "filters/svgf/temporal.h"

#include "core/color.h"
#include "core/error.h"
#include "core/parallel.h"

#include <algorithm>
#include <cmath>
#include <string>

namespace rtdr {
namespace {

// The history values at p': weighted sums while the taps are gathered, the resampled history afterwards.
struct HistorySample {
  glm::vec3 color{0.0f};
  float moment1 = 0.0f;
  float moment2 = 0.0f;
  float length = 0.0f;
};

void add_tap(HistorySample& h, const TemporalHistory& prev, glm::ivec2 q, float w) {
  h.color += w * prev.color.at(q.x, q.y);
  h.moment1 += w * prev.moment1.at(q.x, q.y);
  h.moment2 += w * prev.moment2.at(q.x, q.y);
  h.length += w * prev.length.at(q.x, q.y);
}

HistorySample scaled(const HistorySample& h, float s) { return {s * h.color, s * h.moment1, s * h.moment2, s * h.length}; }

std::string tap_label(const char* kind, glm::ivec2 d) {
  return std::string(kind) + " (" + std::to_string(d.x) + ", " + std::to_string(d.y) + ")";
}

// The 2x2 bilinear resampling of the history at p' [SVGF17 Sec. 4.1]. A tap that fails the consistency test
// is discarded and the consistent taps' weights are renormalised to sum to 1 (temporal.h, "Deviations").
// Returns false when no consistent tap carries any weight.
bool resample_bilinear(const SurfacePlanes& cur, const TemporalHistory& prev, int x, int y, glm::vec2 p_prev,
                       const SvgfParams& params, HistorySample& out, Probe* probe) {
  static const char* const kRenormalisedName[4] = {"w (0, 0) / sum", "w (1, 0) / sum", "w (0, 1) / sum",
                                                   "w (1, 1) / sum"};
  // Pixel centres sit at integer + 0.5, so the four centres around p' start at floor(p' - 0.5).
  const glm::vec2 s = p_prev - 0.5f;
  const glm::ivec2 q00 = glm::ivec2(glm::floor(s));
  // Where p' lies inside the square of those four centres: the bilinear interpolation parameters.
  const glm::vec2 f = s - glm::floor(s);
  note_group(probe, "bilinear");
  note(probe, "q00 = floor(p' - 0.5)", glm::vec2(q00));
  note(probe, "f = p' - 0.5 - q00", f);

  float w_good[4];
  float sum_good = 0.0f;
  HistorySample h;
  for (int k = 0; k < 4; ++k) {
    const glm::ivec2 d(k & 1, k >> 1);  // (0, 0), (1, 0), (0, 1), (1, 1)
    // Bilinear weight: (1 - f) towards the near centre, f towards the far one, on each axis.
    const float w = (d.x ? f.x : 1.0f - f.x) * (d.y ? f.y : 1.0f - f.y);
    note_group(probe, tap_label("bilinear tap", d));
    note(probe, "w_bilinear", w, "[SVGF17 Sec. 4.1] 2x2 bilinear");
    const bool ok = temporal_tap_consistent(cur, prev.surface, x, y, q00 + d, p_prev, params, probe);
    w_good[k] = ok ? w : 0.0f;
    sum_good += w_good[k];
    if (ok) add_tap(h, prev, q00 + d, w);
  }

  note_group(probe, "bilinear");
  note(probe, "sum of consistent weights", sum_good, "[SVGF17 Sec. 4.1] failed taps' weight redistributed");
  if (!(sum_good > 0.0f)) return false;
  for (int k = 0; k < 4; ++k) note(probe, kRenormalisedName[k], w_good[k] / sum_good);
  // sum_k w_k h_k / sum_k w_k over the consistent taps.
  out = scaled(h, 1.0f / sum_good);
  return true;
}

// The 3x3 fallback [SVGF17 Sec. 4.1, "a larger 3 x 3 filter to help find thin geometry such as foliage"]: the
// pixel whose square holds p' and its 8 neighbours, the consistent ones averaged with equal weights.
// Returns false when none is consistent.
bool resample_3x3(const SurfacePlanes& cur, const TemporalHistory& prev, int x, int y, glm::vec2 p_prev,
                  const SvgfParams& params, HistorySample& out, Probe* probe) {
  // The pixel containing p', i.e. the one whose centre is nearest to p'.
  const glm::ivec2 c = glm::ivec2(glm::floor(p_prev));
  HistorySample h;
  int count = 0;
  for (int dy = -1; dy <= 1; ++dy)
    for (int dx = -1; dx <= 1; ++dx) {
      note_group(probe, tap_label("3x3 tap", {dx, dy}));
      if (!temporal_tap_consistent(cur, prev.surface, x, y, c + glm::ivec2(dx, dy), p_prev, params, probe)) continue;
      add_tap(h, prev, c + glm::ivec2(dx, dy), 1.0f);
      ++count;
    }
  note_group(probe, "3x3 fallback");
  note(probe, "consistent taps", float(count), "[SVGF17 Sec. 4.1] 3x3 fallback");
  if (count == 0) return false;
  out = scaled(h, 1.0f / float(count));
  return true;
}

// The history of pixel (x, y): bilinear at p', else the 3x3 fallback; false means a disocclusion.
bool backproject_history(const SurfacePlanes& cur, const TemporalHistory& prev, int x, int y,
                         const SvgfParams& params, HistorySample& out, Probe* probe) {
  note_group(probe, "back-projection");
  const bool first_frame = prev.color.width == 0;
  note(probe, "first frame", float(first_frame));
  if (first_frame) return false;
  // p' = pixel centre + motion: where this pixel's surface point was in the previous frame, in pixels
  // [TRMV21 Eq. 1, the motion vector of SVGF17 Sec. 4.1].
  const glm::vec2 p_prev = glm::vec2(float(x) + 0.5f, float(y) + 0.5f) + cur.motion.at(x, y);
  note(probe, "p'", p_prev, "[SVGF17 Sec. 4.1] backproject");
  // More than a pixel outside the previous image no tap of either filter can be inside (false for a NaN p'
  // too). Testing this first keeps floor(p') within int range, e.g. for kMotionBehindCamera.
  const int w = prev.surface.width(), h = prev.surface.height();
  const bool near = p_prev.x > -1.0f && p_prev.y > -1.0f && p_prev.x < float(w) + 1.0f && p_prev.y < float(h) + 1.0f;
  note(probe, "p' within a pixel of the previous image", float(near));
  if (!near) return false;
  const bool bilinear = resample_bilinear(cur, prev, x, y, p_prev, params, out, probe);
  note_group(probe, "3x3 fallback");
  note(probe, "ran", float(!bilinear), "[SVGF17 Sec. 4.1] 'if no taps remain consistent'");
  return bilinear || resample_3x3(cur, prev, x, y, p_prev, params, out, probe);
}

// Disocclusion [SVGF17 Sec. 4.1]: the history is discarded, C'_i = C_i; the moments restart from this
// sample and the history length from 1.
TemporalPixel disocclusion(glm::vec3 C, float l, Probe* probe) {
  const TemporalPixel out{C, l, l * l, 1.0f};
  note_group(probe, "accumulate");
  note(probe, "C'_i = C_i", out.color, "[SVGF17 Sec. 4.1] disocclusion");
  note(probe, "mu1'_i = l", out.moment1, "[SVGF17 Sec. 4.2]");
  note(probe, "mu2'_i = l^2", out.moment2, "[SVGF17 Sec. 4.2]");
  note(probe, "n_i", out.length);
  return out;
}

// The exponential moving averages of colour and moments [SVGF17 Sec. 4.1, 4.2] with the history-length ramp, with
// the weights alpha (colour) and alpha_mu (moments): the table's, or A-SVGF's alpha_i and alpha_mu_i.
TemporalPixel accumulate(glm::vec3 C, float l, const HistorySample& h, const SvgfParams& params, float alpha_c,
                         float alpha_m, Probe* probe) {
  note_group(probe, "accumulate");
  // n_i = n_{i-1} + 1, capped at n_max when the table sets one (max_history > 0).
  float n = h.length + 1.0f;
  if (params.max_history > 0) n = std::min(n, float(params.max_history));
  note(probe, "n_i", n);
  // alpha_eff = max(alpha, 1/n): a running mean while 1/n > alpha, then the paper's EMA (a deviation, temporal.h).
  const float alpha = std::max(alpha_c, 1.0f / n);
  const float alpha_mu = std::max(alpha_m, 1.0f / n);
  note(probe, "alpha_eff", alpha, "[SVGF17 Sec. 4.1] alpha, Falcor's max(alpha, 1/n)");
  note(probe, "alpha_mu_eff", alpha_mu, "[SVGF17 Sec. 4.2] moments' alpha, max(alpha_mu, 1/n)");
  TemporalPixel out;
  out.length = n;
  // C'_i = alpha C_i + (1 - alpha) C'_{i-1}  [SVGF17 Sec. 4.1, unnumbered equation], A-SVGF's [ASVGF18 Eq. 1]
  out.color = alpha * C + (1.0f - alpha) * h.color;
  note(probe, "C'_i", out.color, "[SVGF17 Sec. 4.1] C' = alpha C + (1 - alpha) C'_{i-1}");
  // mu1'_i = alpha_mu l + (1 - alpha_mu) mu1'_{i-1}  [SVGF17 Sec. 4.2, accumulated like the colour]
  out.moment1 = alpha_mu * l + (1.0f - alpha_mu) * h.moment1;
  note(probe, "mu1'_i", out.moment1, "[SVGF17 Sec. 4.2] EMA of l");
  // mu2'_i = alpha_mu l^2 + (1 - alpha_mu) mu2'_{i-1}  [SVGF17 Sec. 4.2]
  out.moment2 = alpha_mu * (l * l) + (1.0f - alpha_mu) * h.moment2;
  note(probe, "mu2'_i", out.moment2, "[SVGF17 Sec. 4.2] EMA of l^2");
  return out;
}

template <class P>
bool sized(const P& p, int w, int h) {
  return p.width == w && p.height == h;
}

bool surface_sized(const SurfacePlanes& s, int w, int h) {
  return sized(s.depth, w, h) && sized(s.depth_grad, w, h) && sized(s.normal, w, h) && sized(s.mesh, w, h);
}

void check_sizes(const RgbPlane& noisy, const SurfacePlanes& cur, const TemporalHistory& prev) {
  const int w = noisy.width, h = noisy.height;
  if (!surface_sized(cur, w, h) || !sized(cur.motion, w, h))
    throw Error("temporal_pass: the current G-buffer planes are not all " + std::to_string(w) + "x" +
                std::to_string(h) + " like the noisy colour");
  if (prev.color.width == 0) return;  // first frame: no history to check
  const int pw = prev.color.width, ph = prev.color.height;
  if (!sized(prev.moment1, pw, ph) || !sized(prev.moment2, pw, ph) || !sized(prev.length, pw, ph) ||
      !surface_sized(prev.surface, pw, ph))
    throw Error("temporal_pass: the history planes are not all " + std::to_string(pw) + "x" + std::to_string(ph) +
                " like the history colour");
}

}  // namespace

bool temporal_tap_consistent(const SurfacePlanes& cur, const SurfacePlanes& prev, int x, int y, glm::ivec2 q,
                             glm::vec2 p_prev, const SvgfParams& params, Probe* probe) {
  // The tap's centre relative to p', in pixels.
  const glm::vec2 offset = glm::vec2(q) + 0.5f - p_prev;
  note(probe, "q", glm::vec2(q));
  note(probe, "q + 0.5 - p'", offset);
  // The tap must exist in the previous frame.
  const bool in_image = inside(prev.depth, q.x, q.y);
  note(probe, "inside", float(in_image), "[SVGF17 Sec. 4.1] viewport boundary");
  if (!in_image) {
    note(probe, "consistent", 0.0f, "[SVGF17 Sec. 4.1]");
    return false;
  }
  // Mesh ids compare exactly; a tap with no surface (kInvalidId) never matches a covered pixel.
  const bool same_mesh = prev.mesh.at(q.x, q.y) == cur.mesh.at(x, y);
  note(probe, "same mesh id", float(same_mesh), "[SVGF17 Sec. 4.1] mesh IDs");
  // Depth: |z - z'| <= temporal_depth_relative max(z, z') + |grad z(p) . (q - p')|  (temporal.h).
  const float z = cur.depth.at(x, y);
  const float z_prev = prev.depth.at(q.x, q.y);
  const float dz = std::abs(z - z_prev);
  const float dz_max =
      params.temporal_depth_relative * std::max(z, z_prev) + std::abs(glm::dot(cur.depth_grad.at(x, y), offset));
  const bool depth_ok = dz <= dz_max;
  note(probe, "z", z);
  note(probe, "z'", z_prev);
  note(probe, "|z - z'|", dz, "[SVGF17 Sec. 4.1] depths");
  note(probe, "depth tolerance", dz_max, "temporal_depth_relative max(z, z') + |grad z . (q - p')|");
  note(probe, "depth consistent", float(depth_ok));
  // Normal: n(p) . n'(q) >= temporal_normal_cosine (svgf_params.h).
  const float cos_n = glm::dot(cur.normal.at(x, y), prev.normal.at(q.x, q.y));
  const bool normal_ok = cos_n >= params.temporal_normal_cosine;
  note(probe, "n . n'", cos_n, "[SVGF17 Sec. 4.1] normals");
  note(probe, "normal consistent", float(normal_ok));
  const bool ok = same_mesh && depth_ok && normal_ok;
  note(probe, "consistent", float(ok), "[SVGF17 Sec. 4.1]");
  return ok;
}

TemporalPixel temporal_pixel(const RgbPlane& noisy, const SurfacePlanes& cur, const TemporalHistory& prev,
                             const SvgfParams& params, int x, int y, Probe* probe, const TemporalAdaptive* adaptive) {
  note_group(probe, "input");
  const bool covered = cur.covered(x, y);
  note(probe, "covered", float(covered));
  if (!covered) return {};  // no surface: colour, moments and length 0
  const glm::vec3 C = noisy.at(x, y);
  // l: the luminance of the noisy colour; l and l^2 are its first two raw moments [SVGF17 Sec. 4.2].
  const float l = luminance(C);
  note(probe, "C_i", C, "[SVGF17 Sec. 4.1]");
  note(probe, "l", l, "[SVGF17 Sec. 4.2] luminance");

  HistorySample h;
  const bool found = backproject_history(cur, prev, x, y, params, h, probe);
  note_group(probe, "history");
  note(probe, "found", float(found), "[SVGF17 Sec. 4.1] else disocclusion");
  if (!found) return disocclusion(C, l, probe);
  note(probe, "C'_{i-1}", h.color);
  note(probe, "mu1'_{i-1}", h.moment1);
  note(probe, "mu2'_{i-1}", h.moment2);
  note(probe, "weighted mean of the taps' n", h.length);
  // n_{i-1}: that mean rounded to whole frames. n counts frames and is compared with variance_min_history and
  // max_history, but a renormalised sum of equal lengths is not exactly that length in float
  // ((0.375 * 3 + 0.125 * 3 + 0.375 * 3) / 0.875 = 3.0000002). floor(x + 0.5), not round(): GLSL's round()
  // may go either way at .5.
  h.length = std::floor(h.length + 0.5f);
  note(probe, "n_{i-1}", h.length);
  // SVGF's constant weights, or A-SVGF's per pixel (made by its adaptive_alpha pass [ASVGF18 Eq. 15]).
  float alpha = params.alpha, alpha_mu = params.alpha_moments;
  if (adaptive) {
    const float lambda = adaptive->lambda->at(x, y);
    alpha = adaptive->alpha->at(x, y);
    alpha_mu = adaptive->alpha_moments->at(x, y);
    note(probe, "lambda", lambda, "[ASVGF18 Eq. 14], the maximum over 3x3 strata");
    note(probe, "alpha_i", alpha, "[ASVGF18 Eq. 15] (1 - lambda) alpha + lambda");
    note(probe, "alpha_mu_i", alpha_mu, "[ASVGF18 Eq. 15] for the moments");
    // The history keeps the weight 1 - lambda, and with restart_history its length falls alike, so that a dropped
    // history counts as a disocclusion [ASVGF18 Sec. 4] (temporal.h).
    if (adaptive->restart_history) {
      h.length *= 1.0f - lambda;
      note(probe, "(1 - lambda) n_{i-1}", h.length, "[ASVGF18 Sec. 4] a dropped history restarts");
    }
  }
  return accumulate(C, l, h, params, alpha, alpha_mu, probe);
}

TemporalOutput temporal_pass(const RgbPlane& noisy, const SurfacePlanes& cur, const TemporalHistory& prev,
                             const SvgfParams& params, const TemporalAdaptive* adaptive) {
  check_sizes(noisy, cur, prev);
  const auto frame_sized = [&](const FloatPlane* p) { return p && sized(*p, noisy.width, noisy.height); };
  if (adaptive && !(frame_sized(adaptive->lambda) && frame_sized(adaptive->alpha) &&
                    frame_sized(adaptive->alpha_moments)))
    throw Error("temporal pass: the lambda and alpha planes are not the frame's size");
  const int w = noisy.width, h = noisy.height;
  TemporalOutput out{RgbPlane(w, h), FloatPlane(w, h), FloatPlane(w, h), FloatPlane(w, h)};
  parallel_rows(h, [&](int y) {
    for (int x = 0; x < w; ++x) {
      const TemporalPixel p = temporal_pixel(noisy, cur, prev, params, x, y, nullptr, adaptive);
      out.color.at(x, y) = p.color;
      out.moment1.at(x, y) = p.moment1;
      out.moment2.at(x, y) = p.moment2;
      out.length.at(x, y) = p.length;
    }
  });
  return out;
}

}  // namespace rtdr
