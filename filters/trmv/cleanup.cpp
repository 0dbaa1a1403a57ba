// TRMV's clean-up filter [TRMV21 Sec. 5, Eq. 7-8]. What the pass computes, its inputs, outputs and choices:
// filters/trmv/cleanup.h.
#include "filters/trmv/cleanup.h"

#include "core/color.h"
#include "core/error.h"
#include "core/parallel.h"
#include "filters/trmv/spatial.h"

#include <algorithm>
#include <cmath>
#include <string>

namespace rtdr {

float trmv_weight_alpha(float alpha_v, float alpha) {
  // w_A(x_i) = (alpha^V(x_i) - alpha)^2 [TRMV21 Eq. 7].
  return (alpha_v - alpha) * (alpha_v - alpha);
}

float trmv_weight_clamp(glm::vec3 clamped, glm::vec3 fetched, float epsilon) {
  // w_C(x_i) = |cbar*_{i-1} - cbar_{i-1}| / (cbar_{i-1} + epsilon) [TRMV21 Eq. 8], on luminance (cleanup.h).
  return luminance(glm::abs(clamped - fetched)) / (luminance(fetched) + epsilon);
}

float trmv_cleanup_sigma(float w_a, float w_c, float sigma_max) {
  // The clean-up's standard deviation, min{w_A(x_i) + w_C(x_i), 5} [TRMV21 Sec. 5].
  return std::min(w_a + w_c, sigma_max);
}

TrmvCleanupWeights trmv_cleanup_weights_pixel(const TrmvTemporalOutput& temporal, const FloatPlane& alpha_v,
                                              const TrmvParams& params, int x, int y, Probe* probe) {
  note_group(probe, "clean-up weights");
  const float a_v = alpha_v.width == 0 ? params.alpha : alpha_v.at(x, y);
  note(probe, "alpha^V", a_v, "[TRMV21 Eq. 4], alpha without it");
  TrmvCleanupWeights out;
  out.w_a = trmv_weight_alpha(a_v, params.alpha);
  note(probe, "w_A", out.w_a, "[TRMV21 Eq. 7] (alpha^V - alpha)^2");
  note(probe, "cbar_{i-1}", temporal.fetched.at(x, y));
  note(probe, "cbar*_{i-1}", temporal.clamped.at(x, y));
  out.w_c = trmv_weight_clamp(temporal.clamped.at(x, y), temporal.fetched.at(x, y), params.cleanup_eps);
  note(probe, "w_C", out.w_c, "[TRMV21 Eq. 8] Y(|cbar* - cbar|) / (Y(cbar) + eps)");
  out.sigma = trmv_cleanup_sigma(out.w_a, out.w_c, params.cleanup_sigma_max);
  note(probe, "std", out.sigma, "[TRMV21 Sec. 5] min(w_A + w_C, 5), pixels");
  return out;
}

void check_trmv_cleanup_sizes(const TrmvTemporalOutput& temporal, const FloatPlane& alpha_v) {
  const int w = temporal.color.width, h = temporal.color.height;
  if (!has_size(temporal.fetched, w, h) || !has_size(temporal.clamped, w, h) || !empty_or_size(alpha_v, w, h))
    throw Error("trmv clean-up pass: the histories and alpha^V are not all " + std::to_string(w) + "x" +
                std::to_string(h) + " like cbar_i");
}

TrmvCleanupOutput trmv_cleanup_pass(const TrmvTemporalOutput& temporal, const FloatPlane& alpha_v,
                                    const SurfacePlanes& s, const TrmvParams& params, const SvgfParams& edges) {
  check_trmv_cleanup_sizes(temporal, alpha_v);
  const int w = temporal.color.width, h = temporal.color.height;
  TrmvCleanupOutput out{RgbPlane(), FloatPlane(w, h), FloatPlane(w, h), FloatPlane(w, h)};
  parallel_rows(h, [&](int y) {
    for (int x = 0; x < w; ++x) {
      const TrmvCleanupWeights p = trmv_cleanup_weights_pixel(temporal, alpha_v, params, x, y);
      out.w_a.at(x, y) = p.w_a;
      out.w_c.at(x, y) = p.w_c;
      out.sigma.at(x, y) = p.sigma;
    }
  });
  // The separable joint bilateral, "a fixed size 9x9" [TRMV21 Sec. 5]: radius (9 - 1) / 2 = 4, each 1-D pass
  // with the std of the pixel it computes (spatial.h).
  const int radius = (params.cleanup_size - 1) / 2;
  const RgbPlane rows = trmv_spatial_axis(temporal.color, s, kTrmvHorizontal, radius, out.sigma, 0.0f, edges);
  out.color = trmv_spatial_axis(rows, s, kTrmvVertical, radius, out.sigma, 0.0f, edges);
  return out;
}

}  // namespace rtdr
