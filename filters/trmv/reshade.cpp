// TRMV's cone history and the re-shading of disoccluded pixels [TRMV21 Sec. 4.3, Eq. 11]. What the pass
// computes, its inputs, outputs and choices: filters/trmv/reshade.h.
#include "filters/trmv/reshade.h"

#include "core/error.h"
#include "core/parallel.h"
#include "filters/trmv/atrous.h"
#include "filters/trmv/spatial.h"

#include <cmath>
#include <string>

namespace rtdr {

TrmvConeInputs TrmvConeInputs::from_frame(const Frame& frame) {
  return {xyz_plane(frame, "path.direction"), rgb_plane(frame, "path.incoming"), frame.float_channel("path.pdf")};
}

ConeValues trmv_cone_estimate(const ConeLayout& layout, glm::vec3 normal, glm::vec3 direction, glm::vec3 incoming,
                              float pdf) {
  ConeValues lhat{};
  // One sample: Lhat_k = L_in(w) 1[w in cone k] / (p(w) Omega_k^+) [TRMV21 Sec. 4.3] (cones.h). No ray was
  // traced where p = 0 (no surface, or the BSDF sample failed): every cone stays 0.
  if (pdf > 0.0f) add_cone_sample(layout, normal, direction, incoming, pdf, lhat);
  return lhat;
}

bool trmv_cones_at(const TrmvConeHistory& prev, const ConeLayout& layout, glm::vec2 x_o, const SurfacePlanes& surface,
                   int x, int y, const ConeValues& current, bool full, ConeValues& out, Probe* probe) {
  note_group(probe, "cones at x^O");
  note(probe, "x^O", x_o, "[TRMV21 Eq. 6] pixel centre + motion.dual");
  if (prev.empty()) return false;
  // Off the previous image (false for NaN too); this also keeps floor(x^O) within int range for far-off vectors.
  const int w = prev.normal.width, h = prev.normal.height;
  if (!(x_o.x >= 0.0f && x_o.y >= 0.0f && x_o.x < float(w) && x_o.y < float(h))) return false;
  // The nearest pixel: the one whose square holds x^O (reshade.h), showing the pixel's own mesh (temporal.h's
  // test of the dual vector).
  const int qx = int(std::floor(x_o.x)), qy = int(std::floor(x_o.y));
  const uint32_t mesh_q = prev.surface.mesh.at(qx, qy);
  note(probe, "same mesh at x^O", float(mesh_q == surface.mesh.at(x, y)), "the dual vector's history test");
  if (mesh_q == kInvalidId || mesh_q != surface.mesh.at(x, y)) return false;
  ConeValues source;
  for (int k = 0; k < kConeCount; ++k) source[size_t(k)] = prev.cones[size_t(k)].at(qx, qy);
  // Re-oriented from the normal there to this pixel's, by the overlap of each pair of cones [TRMV21 Eq. 9-10],
  // each for the share of it the source's hemisphere covers [TRMV21 Sec. 4.3, Fig. 7].
  const glm::vec3 n_source = prev.normal.at(qx, qy), n = surface.normal.at(x, y);
  const ConeTransfer transfer = transfer_cones(layout, n, n_source, source, full);
  out = blend_transferred(transfer, current);
  note(probe, "n at x^O", n_source);
  note(probe, "n", n);
  for (int k = 0; k < kConeCount; ++k) {
    note(probe, "L'_k", transfer.values[size_t(k)], "[TRMV21 Sec. 4.3] transferred cone k");
    note(probe, "f_k", transfer.share[size_t(k)], "[TRMV21 Sec. 4.3] (Fig. 7) its share in the source's hemisphere");
    note(probe, "H_k", out[size_t(k)], "f_k L'_k + (1 - f_k) L~_k");
  }
  return true;
}

bool trmv_reshade_pixel(const TrmvConeHistory& prev, const ConeLayout& layout, const SurfacePlanes& surface,
                        const TrmvMotion& dual, const ConeValues& current, bool full, int x, int y, glm::vec3& out,
                        Probe* probe) {
  const bool disoccluded = surface.covered(x, y) && dual.valid.at(x, y) != 0;
  note_group(probe, "input");
  note(probe, "disoccluded", float(disoccluded), "[TRMV21 Eq. 6] motion.dual.valid");
  if (!disoccluded) return false;
  const glm::vec2 x_o = glm::vec2(float(x) + 0.5f, float(y) + 0.5f) + dual.motion.at(x, y);
  ConeValues cones;
  if (!trmv_cones_at(prev, layout, x_o, surface, x, y, current, full, cones, probe)) return false;
  // L_o = (1/pi) sum_k c_k H_k, demodulated: the history this pixel's own normal makes of them [TRMV21 Eq. 11].
  out = reshade_cones(layout, cones);
  note_group(probe, "re-shade");
  note(probe, "L_o", out, "[TRMV21 Eq. 11] with the cosine (cones.h)");
  return true;
}

namespace {

void check_sizes(const TrmvConeInputs& in, const SurfacePlanes& s, const TrmvMotion& dual) {
  const int w = s.width(), h = s.height();
  if (!has_size(in.direction, w, h) || !has_size(in.incoming, w, h) || !has_size(in.pdf, w, h) ||
      !has_size(dual.motion, w, h) || !has_size(dual.valid, w, h))
    throw Error("trmv re-shade pass: path.direction, path.incoming, path.pdf and motion.dual are not all " +
                std::to_string(w) + "x" + std::to_string(h) + " like the frame");
}

// Lbar_k = alpha L~_k + (1 - alpha) H_k at one pixel [TRMV21 Eq. 2, per cone]: H from x^O's cones where the
// dual vector applies, else fetched along the surface motion with `test`; no history: Lbar = L~.
void accumulate_cones_pixel(const std::array<RgbPlane, kConeCount>& filtered, const SurfacePlanes& s,
                            const TrmvMotion& dual, const TrmvConeHistory& prev, const ConeLayout& layout,
                            const TrmvParams& params, const SvgfParams& svgf, int x, int y, TrmvConeHistory& out) {
  const ConeValues current = trmv_cones_of(filtered, x, y);
  ConeValues history;
  bool has_history = false;
  if (dual.valid.at(x, y) != 0) {
    const glm::vec2 x_o = glm::vec2(float(x) + 0.5f, float(y) + 0.5f) + dual.motion.at(x, y);
    has_history = trmv_cones_at(prev, layout, x_o, s, x, y, current, params.cone_transfer == 0, history);
  } else if (!prev.empty()) {
    // Along the surface motion, with the surface vector's test (temporal.h), or none for forced reuse.
    const glm::vec2 p_prev = glm::vec2(float(x) + 0.5f, float(y) + 0.5f) + s.motion.at(x, y);
    const uint32_t test = params.history_test != 0 ? kTrmvTestSurface : kTrmvTestNone;
    TrmvHistoryTaps taps;
    has_history = trmv_history_taps(prev.surface, p_prev, s, x, y, test, svgf, taps);
    if (has_history)
      for (int k = 0; k < kConeCount; ++k) history[size_t(k)] = trmv_apply_taps(prev.cones[size_t(k)], taps);
  }
  const float alpha = params.alpha;
  for (int k = 0; k < kConeCount; ++k) {
    const glm::vec3 l = current[size_t(k)];
    out.cones[size_t(k)].at(x, y) = has_history ? alpha * l + (1.0f - alpha) * history[size_t(k)] : l;
  }
}

}  // namespace

ConeValues trmv_cones_of(const std::array<RgbPlane, kConeCount>& cones, int x, int y) {
  ConeValues out;
  for (int k = 0; k < kConeCount; ++k) out[size_t(k)] = cones[size_t(k)].at(x, y);
  return out;
}

std::array<RgbPlane, kConeCount> trmv_filtered_cones(const TrmvConeInputs& in, const SurfacePlanes& s,
                                                     const ConeLayout& layout, const TrmvConeFilter& filter,
                                                     const SvgfParams& svgf) {
  const int w = s.width(), h = s.height();
  // Lhat_k: each pixel's one-sample estimate of its six cones.
  std::array<RgbPlane, kConeCount> estimate;
  for (RgbPlane& e : estimate) e = RgbPlane(w, h);
  parallel_rows(h, [&](int y) {
    for (int x = 0; x < w; ++x) {
      if (!s.covered(x, y)) continue;
      const ConeValues lhat =
          trmv_cone_estimate(layout, s.normal.at(x, y), in.direction.at(x, y), in.incoming.at(x, y), in.pdf.at(x, y));
      for (int k = 0; k < kConeCount; ++k) estimate[size_t(k)].at(x, y) = lhat[size_t(k)];
    }
  });
  // L~_k: each cone filtered in space on its own, with the diffuse light's filter [TRMV21 Sec. 4.3, Sec. 5].
  std::array<RgbPlane, kConeCount> filtered;
  for (int k = 0; k < kConeCount; ++k)
    filtered[size_t(k)] = filter.atrous ? trmv_atrous_pass(estimate[size_t(k)], s, filter.levels, svgf)
                                        : trmv_spatial_pass(estimate[size_t(k)], s, filter.radius, filter.sigma, svgf);
  return filtered;
}

TrmvReshadeOutput trmv_reshade_pass(const TrmvConeInputs& in, const SurfacePlanes& s, const TrmvMotion& dual,
                                    const TrmvConeHistory& prev, const ConeLayout& layout,
                                    const TrmvConeFilter& filter, const TrmvParams& params, const SvgfParams& svgf) {
  check_sizes(in, s, dual);
  const int w = s.width(), h = s.height();
  TrmvReshadeOutput out;
  out.filtered = trmv_filtered_cones(in, s, layout, filter, svgf);
  const std::array<RgbPlane, kConeCount>& filtered = out.filtered;
  for (RgbPlane& c : out.history.cones) c = RgbPlane(w, h);
  out.history.normal = s.normal;
  out.history.surface = s;
  out.reshaded = RgbPlane(w, h);
  out.reshaded_valid = UIntPlane(w, h);
  const bool full = params.cone_transfer == 0;
  parallel_rows(h, [&](int y) {
    for (int x = 0; x < w; ++x) {
      if (!s.covered(x, y)) continue;
      glm::vec3 reshaded;
      if (trmv_reshade_pixel(prev, layout, s, dual, trmv_cones_of(filtered, x, y), full, x, y, reshaded))
        out.reshaded.at(x, y) = reshaded, out.reshaded_valid.at(x, y) = 1u;
      accumulate_cones_pixel(filtered, s, dual, prev, layout, params, svgf, x, y, out.history);
    }
  });
  return out;
}

}  // namespace rtdr
