// SVGF variance estimation [SVGF17 Sec. 4.2]. What the pass computes, its inputs, outputs and the choices
// the paper leaves open: filters/svgf/variance.h.
#include "filters/svgf/variance.h"

#include "core/error.h"
#include "core/parallel.h"
#include "filters/svgf/edge_stopping.h"

#include <algorithm>
#include <string>

namespace rtdr {
namespace {

std::string tap_label(int dx, int dy) {
  return "7x7 tap (" + std::to_string(dx) + ", " + std::to_string(dy) + ")";
}

// sigma'^2 = mu2' - mu1'^2 [SVGF17 Sec. 4.2], clamped at 0: a variance is never negative, but the difference
// of two rounded moments can be (by a few ulps where the variance is 0).
float variance_from_moments(float mu1, float mu2, Probe* probe) {
  const float sigma2 = std::max(0.0f, mu2 - mu1 * mu1);
  note(probe, "sigma'^2 = max(0, mu2 - mu1^2)", sigma2, "[SVGF17 Sec. 4.2]");
  return sigma2;
}

}  // namespace

float variance_spatial_pixel(const TemporalOutput& t, const SurfacePlanes& cur, const SvgfParams& params, int x,
                             int y, Probe* probe) {
  const float z_p = cur.depth.at(x, y);
  const glm::vec2 grad_z_p = cur.depth_grad.at(x, y);
  const glm::vec3 n_p = cur.normal.at(x, y);
  float sum_w = 0.0f, mu1 = 0.0f, mu2 = 0.0f;
  for (int dy = -kVarianceSpatialRadius; dy <= kVarianceSpatialRadius; ++dy)
    for (int dx = -kVarianceSpatialRadius; dx <= kVarianceSpatialRadius; ++dx) {
      const int qx = x + dx, qy = y + dy;
      // Taps outside the image or on no surface hold no moments.
      if (!inside(cur.depth, qx, qy) || !cur.covered(qx, qy)) continue;
      note_group(probe, tap_label(dx, dy));
      // w_z with p - q = (-dx, -dy) [SVGF17 Eq. 3], w_n [SVGF17 Eq. 4]: "weights driven by depths and
      // world-space normals" [SVGF17 Sec. 4.2].
      const float w_z = weight_depth(z_p, cur.depth.at(qx, qy), grad_z_p, glm::vec2(-dx, -dy), params.sigma_z,
                                     params.epsilon);
      const float w_n = weight_normal(n_p, cur.normal.at(qx, qy), params.sigma_n);
      const float w = w_z * w_n;
      note(probe, "w_z", w_z, "[SVGF17 Eq. 3]");
      note(probe, "w_n", w_n, "[SVGF17 Eq. 4]");
      note(probe, "w = w_z w_n", w, "[SVGF17 Sec. 4.2] 7x7 bilateral");
      note(probe, "mu1'(q)", t.moment1.at(qx, qy));
      note(probe, "mu2'(q)", t.moment2.at(qx, qy));
      sum_w += w;
      mu1 += w * t.moment1.at(qx, qy);
      mu2 += w * t.moment2.at(qx, qy);
    }
  note_group(probe, "spatial estimate");
  note(probe, "sum w", sum_w);
  // The centre tap has w = 1 (w_z = exp(-0 / epsilon), epsilon > 0 by the table's range), so sum w >= 1
  // unless p's normal is degenerate (zero length: every w_n = 0) or NaN; then the pixel's own moments remain.
  if (!(sum_w > 0.0f)) return variance_from_moments(t.moment1.at(x, y), t.moment2.at(x, y), probe);
  // The weighted means of the moments: sum w mu'(q) / sum w.
  mu1 /= sum_w;
  mu2 /= sum_w;
  note(probe, "mu1 = sum w mu1' / sum w", mu1, "[SVGF17 Sec. 4.2]");
  note(probe, "mu2 = sum w mu2' / sum w", mu2, "[SVGF17 Sec. 4.2]");
  return variance_from_moments(mu1, mu2, probe);
}

bool variance_is_spatial(float n, const SvgfParams& params) { return !(n >= float(params.variance_min_history)); }

FloatPlane variance_spatial_plane(const FloatPlane& length, const UIntPlane& mesh, const SvgfParams& params) {
  FloatPlane spatial(length.width, length.height);
  for (size_t i = 0; i < spatial.data.size(); ++i)
    spatial.data[i] = mesh.data[i] != kInvalidId && variance_is_spatial(length.data[i], params) ? 1.0f : 0.0f;
  return spatial;
}

float variance_pixel(const TemporalOutput& t, const SurfacePlanes& cur, const SvgfParams& params, int x, int y,
                     Probe* probe) {
  note_group(probe, "variance");
  const bool covered = cur.covered(x, y);
  note(probe, "covered", float(covered));
  if (!covered) return 0.0f;  // no surface, no variance
  const float n = t.length.at(x, y);
  // "Where our temporal history is limited (<4 frames after a disocclusion), we instead estimate the variance
  // spatially" [SVGF17 Sec. 4.2]; 4 is variance_min_history.
  const bool temporal = !variance_is_spatial(n, params);
  note(probe, "n", n);
  note(probe, "temporal estimate (n >= variance_min_history)", float(temporal), "[SVGF17 Sec. 4.2]");
  if (!temporal) return variance_spatial_pixel(t, cur, params, x, y, probe);
  note(probe, "mu1'", t.moment1.at(x, y));
  note(probe, "mu2'", t.moment2.at(x, y));
  return variance_from_moments(t.moment1.at(x, y), t.moment2.at(x, y), probe);
}

FloatPlane variance_pass(const TemporalOutput& t, const SurfacePlanes& cur, const SvgfParams& params) {
  const int w = cur.width(), h = cur.height();
  const auto sized = [&](const auto& p) { return p.width == w && p.height == h; };
  if (!sized(t.moment1) || !sized(t.moment2) || !sized(t.length) || !sized(cur.depth_grad) || !sized(cur.normal) ||
      !sized(cur.mesh))
    throw Error("variance_pass: the temporal output and G-buffer planes are not all " + std::to_string(w) + "x" +
                std::to_string(h));
  FloatPlane sigma2(w, h);
  parallel_rows(h, [&](int y) {
    for (int x = 0; x < w; ++x) sigma2.at(x, y) = variance_pixel(t, cur, params, x, y);
  });
  return sigma2;
}

}  // namespace rtdr
