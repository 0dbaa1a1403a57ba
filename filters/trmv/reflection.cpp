// TRMV's glossy filter, the BRDF lobe's footprint [TRMV21 Sec. 5, after LLK*19]. The kernel and the choices:
// filters/trmv/reflection.h.
#include "filters/trmv/reflection.h"

#include "core/error.h"
#include "core/parallel.h"
#include "filters/svgf/edge_stopping.h"
#include "filters/trmv/spatial.h"

#include <cmath>
#include <string>

namespace rtdr {

TrmvFootprint TrmvFootprint::from_frame(const Frame& frame) {
  return {frame.float_channel("glossy.footprint.XX"), frame.float_channel("glossy.footprint.XY"),
          frame.float_channel("glossy.footprint.YY"), frame.uint_channel("glossy.footprint.valid")};
}

glm::mat2 trmv_reflection_precision(const TrmvFootprint& f, int radius, int x, int y) {
  if (f.valid.at(x, y) == 0) {
    // No footprint: wider than any window; the window's round Gaussian, std radius / 3 (reflection.h).
    const float sigma = float(radius) / 3.0f;
    return glm::mat2(1.0f / (sigma * sigma));
  }
  // S = Sigma_i + I / 12: the lobe's footprint and the pixel's own spread (reflection.h).
  const float a = f.xx.at(x, y) + kTrmvPixelVariance, b = f.xy.at(x, y), d = f.yy.at(x, y) + kTrmvPixelVariance;
  // S^-1 = [d -b; -b a] / (a d - b^2); a d - b^2 >= (1/12)^2 > 0 since Sigma_i is positive semi-definite.
  const float det = a * d - b * b;
  return glm::mat2(d / det, -b / det, -b / det, a / det);
}

float trmv_reflection_weight(const glm::mat2& precision, glm::vec2 d) {
  // g(d) = exp(-d^T S^-1 d / 2): the footprint's Gaussian, peak 1 [TRMV21 Sec. 4.2, LLK*19].
  return std::exp(-0.5f * glm::dot(d, precision * d));
}

glm::vec3 trmv_reflection_pixel(const RgbPlane& c, const SurfacePlanes& s, const TrmvFootprint& f, int radius,
                                const SvgfParams& edges, int x, int y, Probe* probe) {
  note(probe, "window radius", float(radius), "the shadow filter's, scaled (footprint.h)");
  if (!s.covered(x, y)) return c.at(x, y);  // no surface: passed through
  const glm::mat2 precision = trmv_reflection_precision(f, radius, x, y);
  note(probe, "footprint", float(f.valid.at(x, y)), "glossy.footprint.valid");
  note(probe, "S^-1 (xx, yy)", glm::vec2(precision[0][0], precision[1][1]), "[LLK*19] the lobe's footprint");
  const float z_p = s.depth.at(x, y);
  const glm::vec2 grad_z_p = s.depth_grad.at(x, y);
  const glm::vec3 n_p = s.normal.at(x, y);
  float sum_w = 1.0f;          // the centre's weight, 1 (reflection.h)
  glm::vec3 sum_wc = c.at(x, y);
  for (int dy = -radius; dy <= radius; ++dy)
    for (int dx = -radius; dx <= radius; ++dx) {
      if (dx == 0 && dy == 0) continue;  // the centre is in the sums already
      const int qx = x + dx, qy = y + dy;
      if (!inside(c, qx, qy) || !s.covered(qx, qy)) continue;  // skipped; the weights that remain renormalise
      const glm::vec2 d{float(dx), float(dy)};  // q - p
      const float g = trmv_reflection_weight(precision, d);
      const float w_z = weight_depth(z_p, s.depth.at(qx, qy), grad_z_p, -d, edges.sigma_z, edges.epsilon);
      const float w_n = weight_normal(n_p, s.normal.at(qx, qy), edges.sigma_n);
      const float w = g * w_z * w_n;
      sum_w += w;
      sum_wc += w * c.at(qx, qy);
    }
  note(probe, "sum w", sum_w, "[LLK*19] the lobe filter's normaliser");
  // c~(p) = sum g w_z w_n c(q) / sum g w_z w_n.
  const glm::vec3 out = sum_wc / sum_w;
  note(probe, "c~", out, "[TRMV21 Sec. 5] glossy, filtered");
  return out;
}

void check_trmv_reflection_sizes(const RgbPlane& c, const SurfacePlanes& s, const TrmvFootprint& f) {
  check_trmv_surface_sizes(c.width, c.height, s, "trmv reflection filter");
  if (!has_size(f.xx, c.width, c.height) || !has_size(f.xy, c.width, c.height) ||
      !has_size(f.yy, c.width, c.height) || !has_size(f.valid, c.width, c.height))
    throw Error("trmv reflection filter: the footprint planes are not " + std::to_string(c.width) + "x" +
                std::to_string(c.height) + " like the glossy light");
}

RgbPlane trmv_reflection_pass(const RgbPlane& c, const SurfacePlanes& s, const TrmvFootprint& f, int radius,
                              const SvgfParams& edges) {
  check_trmv_reflection_sizes(c, s, f);
  RgbPlane out(c.width, c.height);
  parallel_rows(c.height, [&](int y) {
    for (int x = 0; x < c.width; ++x) out.at(x, y) = trmv_reflection_pixel(c, s, f, radius, edges, x, y);
  });
  return out;
}

}  // namespace rtdr
