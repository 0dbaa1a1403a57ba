// The edge-stopping functions of SVGF [SVGF17 Sec. 4.4, Eq. 3-5]. Plain scalar functions, written as the paper
// writes them; each is a weight in [0, 1] that falls as q looks less like the same surface as p.
//
// Depth: linear view depth instead of the paper's clip-space depth.
// The paper "assume[s] a local linear model for the surface depths" built from "screen-space partial derivatives
// of clip-space depth" [SVGF17 Sec. 4.4]. Clip-space depth after the perspective divide is A + B / z, and on a
// plane 1/z is an affine function of the screen position, so for clip-space depth the linear model is exact on
// planes. Our depth.Z is linear view depth z (docs/buffers.md), which is not affine on a plane: along a tap,
//   z(q) = z(p) / (1 - t),   t = grad z(p) . (q - p) / z(p),
// so |z(p) - z(q)| = |grad z(p) . (p - q)| / |1 - t|. The linear model is exact to first order in t, the tap's
// relative depth change, which stays small except at grazing angles with far taps. This first-order model on
// linear depth is also what Falcor's SVGF does (linear z and its screen derivative). Note what Eq. 3 measures
// either way: on a tilted plane every tap gets exp(-1 / sigma_z) (the depth changes by the predicted amount;
// with our linear depth the exponent carries the extra factor 1 / |1 - t|), and on a plane facing the camera
// every tap gets 1 (no change predicted, none found: 0 / epsilon).
#include "filters/svgf/edge_stopping.h"

#include <algorithm>
#include <cmath>

namespace rtdr {

float weight_depth(float z_p, float z_q, glm::vec2 grad_z_p, glm::vec2 offset_pq, float sigma_z, float epsilon) {
  // The depth change the local plane predicts over p - q, scaled by sigma_z [SVGF17 Eq. 3, denominator].
  const float predicted = sigma_z * std::abs(glm::dot(grad_z_p, offset_pq)) + epsilon;
  // w_z = exp(-|z(p) - z(q)| / predicted) [SVGF17 Eq. 3]. At q = p: 0 / epsilon = 0, so w_z = 1 exactly
  // (epsilon > 0 keeps 0 / 0 away).
  return std::exp(-std::abs(z_p - z_q) / predicted);
}

float weight_normal(glm::vec3 n_p, glm::vec3 n_q, float sigma_n) {
  // w_n = max(0, n(p) . n(q))^sigma_n [SVGF17 Eq. 4]: a cosine lobe; back-facing pairs get 0.
  return std::pow(std::max(0.0f, glm::dot(n_p, n_q)), sigma_n);
}

float luminance_scale(float variance_prefiltered_p, float sigma_l, float epsilon) {
  // The luminance change one would expect from noise alone: sigma_l standard deviations of the prefiltered
  // variance g3x3(Var(l(p))) [SVGF17 Eq. 5, denominator]. A variance from moments (mu_2 - mu_1^2) can be
  // negative by rounding; it is taken as 0, as the square root of a variance must be of a non-negative number.
  return sigma_l * std::sqrt(std::max(0.0f, variance_prefiltered_p)) + epsilon;
}

float weight_luminance(float l_p, float l_q, float variance_prefiltered_p, float sigma_l, float epsilon) {
  // w_l = exp(-|l(p) - l(q)| / (sigma_l sqrt(g3x3(Var(l(p)))) + epsilon)) [SVGF17 Eq. 5]; 1 at q = p.
  return std::exp(-std::abs(l_p - l_q) / luminance_scale(variance_prefiltered_p, sigma_l, epsilon));
}

}  // namespace rtdr
