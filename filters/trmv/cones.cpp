// TRMV's six cones of incident radiance [TRMV21 Sec. 4.3, Eq. 9-11]. The layout, its derivation, the corrected
// re-shading, the estimator and the choices: filters/trmv/cones.h.
#include "filters/trmv/cones.h"

#include "core/geometry.h"

#include <glm/gtc/constants.hpp>

#include <algorithm>
#include <cmath>

namespace rtdr {
namespace {

constexpr double kPi = 3.14159265358979323846;

// Below this axis separation Eq. 10's gamma is 0/0 (exactly at a = 0) or lost to rounding; the overlap is the
// whole cap there. Omega falls with slope -2 sin theta_c (cones.h), so the step this leaves is < 2e-9 sr.
constexpr double kSameAxisSeparation = 1e-9;

// The transfer weights' cones stay this far (radians) short of touching their neighbours (cones.h).
constexpr float kTransferNeighbourGap = 0.001f;

// The part of a cap of half-angle theta that lies beyond a great circle whose plane passes gamma radians from
// the cap's axis (gamma < 0: the axis is beyond it) [Mazonka 2012]. Eq. 9 is twice this with gamma = a/2.
double cap_beyond_great_circle(double theta, double gamma) {
  // beta = arccos(sin gamma / sin theta_c) [TRMV21 Eq. 10]; clamped: the great circle misses the cap when
  // |gamma| >= theta_c (beta = 0 or pi).
  const double beta = std::acos(std::clamp(std::sin(gamma) / std::sin(theta), -1.0, 1.0));
  // phi = arccos(tan gamma / tan theta_c) [TRMV21 Eq. 10], clamped likewise.
  const double phi = std::acos(std::clamp(std::tan(gamma) / std::tan(theta), -1.0, 1.0));
  // Half of Omega = 4 (beta - phi cos theta_c) [TRMV21 Eq. 9]: one of the two equal halves of the lens.
  return 2.0 * (beta - phi * std::cos(theta));
}

// The six axes in the local frame: a_0 on the normal, a_1..a_5 on the ring at polar angle psi (cones.h).
ConeAxes local_axes(float psi) {
  ConeAxes axes{};
  axes[0] = glm::vec3(0.0f, 0.0f, 1.0f);
  for (int k = 1; k < kConeCount; ++k) {
    const double azimuth = 2.0 * kPi * double(k - 1) / double(kConeCount - 1);
    axes[size_t(k)] = glm::vec3(float(std::sin(psi) * std::cos(azimuth)), float(std::sin(psi) * std::sin(azimuth)),
                                float(std::cos(psi)));
  }
  return axes;
}

// The smallest angle between two of the axes: the ring's neighbours (66.87 degrees at psi*).
float smallest_axis_spacing(const ConeAxes& axes) {
  float spacing = glm::pi<float>();
  for (int k = 0; k < kConeCount; ++k)
    for (int m = k + 1; m < kConeCount; ++m)
      spacing = std::min(spacing, std::acos(std::clamp(glm::dot(axes[size_t(k)], axes[size_t(m)]), -1.0f, 1.0f)));
  return spacing;
}

}  // namespace

float cone_solid_angle(float theta_c) { return float(2.0 * kPi * (1.0 - std::cos(double(theta_c)))); }

float cone_overlap_solid_angle(float theta_c, float a) {
  const double theta = theta_c, alpha = a;
  // Axes 2 theta_c or more apart: the cones touch at most (Eq. 10's arccos would see arguments > 1).
  if (alpha >= 2.0 * theta) return 0.0f;
  // The same axis: the whole cap, where Eq. 10's gamma is 0/0.
  if (alpha < kSameAxisSeparation) return cone_solid_angle(theta_c);
  // gamma = arctan((cos theta_c - cos a cos theta_c) / (sin a cos theta_c)) [TRMV21 Eq. 10]: the angle from
  // either axis to the plane through the two circles' crossings; a/2 for equal cones.
  const double gamma =
      std::atan((std::cos(theta) - std::cos(alpha) * std::cos(theta)) / (std::sin(alpha) * std::cos(theta)));
  // Omega = 4 (beta - phi cos theta_c) [TRMV21 Eq. 9]: the lens is the two caps' parts beyond that plane.
  return float(2.0 * cap_beyond_great_circle(theta, gamma));
}

float cone_solid_angle_above_horizon(float theta_c, float psi) {
  // The horizon is a great circle pi/2 - psi from the axis; what lies beyond it is below the horizon.
  const double below = cap_beyond_great_circle(theta_c, 0.5 * kPi - double(psi));
  return float(std::max(0.0, 2.0 * kPi * (1.0 - std::cos(double(theta_c))) - below));
}

float cone_covering_radius(float psi) {
  const double c = std::cos(kPi / 5.0);
  // rho: the polar angle of P, equidistant from a_0, a_1, a_2, tan rho = tan(psi/2) / cos(pi/5) (cones.h).
  const double rho = std::atan(std::tan(0.5 * double(psi)) / c);
  // d_E: the distance from E, on the horizon halfway between a_1 and a_2, to either (cones.h).
  const double d_e = std::acos(std::sin(double(psi)) * c);
  return float(std::max(rho, d_e));
}

bool cone_contains(float theta_c, glm::vec3 axis, glm::vec3 w) { return glm::dot(axis, w) >= std::cos(theta_c); }

std::array<float, kConeCount> cone_cosine_weights(const ConeAxes& axes, float theta_c, int n) {
  // Midpoint rule on the (u, phi) grid, u = sin^2 theta: cos theta dw = du dphi / 2, so every cell weighs
  // (1/n) (2 pi/n) / 2 = pi / n^2 of the cosine-weighted hemisphere (cones.h).
  std::array<double, kConeCount> sum{};
  for (int j = 0; j < n; ++j) {
    const double phi = 2.0 * kPi * (double(j) + 0.5) / double(n);
    for (int i = 0; i < n; ++i) {
      const double u = (double(i) + 0.5) / double(n);
      const glm::vec3 w(float(std::sqrt(u) * std::cos(phi)), float(std::sqrt(u) * std::sin(phi)),
                        float(std::sqrt(1.0 - u)));
      // N(w), the number of cones containing w, then each of them gets the partition weight 1 / N(w).
      std::array<bool, kConeCount> inside{};
      int count = 0;
      for (int k = 0; k < kConeCount; ++k) {
        inside[size_t(k)] = cone_contains(theta_c, axes[size_t(k)], w);
        count += inside[size_t(k)] ? 1 : 0;
      }
      for (int k = 0; k < kConeCount; ++k)
        if (inside[size_t(k)]) sum[size_t(k)] += 1.0 / double(count);
    }
  }
  // c_k = integral_H cos theta 1[w in k] / N(w) dw (cones.h, corrected Eq. 11).
  std::array<float, kConeCount> c{};
  for (int k = 0; k < kConeCount; ++k) c[size_t(k)] = float(kPi * sum[size_t(k)] / (double(n) * double(n)));
  return c;
}

ConeLayout make_cone_layout(float theta_c) {
  ConeLayout layout;
  layout.half_angle = theta_c;
  layout.axes = local_axes(kConeRingPolarAngle);
  layout.cosine_weight = cone_cosine_weights(layout.axes, theta_c, kConeQuadratureGrid);
  // The five ring cones are congruent, so their c_k are equal; the grid's azimuths do not repeat with the
  // ring's five-fold symmetry, and its rounding at their boundaries differs by a few 1e-5. Each takes their
  // mean, which keeps sum_k c_k and leaves only the error of c_0, below 1e-6 (cones.h).
  float c_ring = 0.0f;
  for (int k = 1; k < kConeCount; ++k) c_ring += layout.cosine_weight[size_t(k)] / float(kConeCount - 1);
  for (int k = 1; k < kConeCount; ++k) layout.cosine_weight[size_t(k)] = c_ring;
  for (int k = 0; k < kConeCount; ++k) {
    const float psi_k = std::acos(std::clamp(layout.axes[size_t(k)].z, -1.0f, 1.0f));  // the axis' polar angle
    layout.solid_angle[size_t(k)] = cone_solid_angle_above_horizon(theta_c, psi_k);
  }
  // theta_T: Eq. 9-10's cones for the transfer weights, short of overlapping their neighbours (cones.h).
  layout.transfer_half_angle = std::min(theta_c, 0.5f * (smallest_axis_spacing(layout.axes) - kTransferNeighbourGap));
  return layout;
}

ConeAxes cone_axes(const ConeLayout& layout, glm::vec3 n) {
  glm::vec3 t, b;
  orthonormal_basis(n, t, b);  // core/geometry.h
  ConeAxes world{};
  // a_k in world space: its local coordinates on (t, b, n).
  for (int k = 0; k < kConeCount; ++k) {
    const glm::vec3 a = layout.axes[size_t(k)];
    world[size_t(k)] = a.x * t + a.y * b + a.z * n;
  }
  return world;
}

void add_cone_sample(const ConeLayout& layout, const ConeAxes& axes, glm::vec3 w, glm::vec3 L_in, float pdf,
                     ConeValues& Lhat) {
  // No sample (pdf 0), or a direction the re-shading does not integrate (axes[0] is the normal).
  if (!(pdf > 0.0f) || glm::dot(w, axes[0]) <= 0.0f) return;
  for (int k = 0; k < kConeCount; ++k) {
    const float omega_k = layout.solid_angle[size_t(k)];
    // Lhat_k = L_in(w) 1[w in cone k] / (pdf(w) Omega_k^+): unbiased for the cone's mean above the horizon.
    if (omega_k > 0.0f && cone_contains(layout.half_angle, axes[size_t(k)], w))
      Lhat[size_t(k)] += L_in / (pdf * omega_k);
  }
}

void add_cone_sample(const ConeLayout& layout, glm::vec3 n, glm::vec3 w, glm::vec3 L_in, float pdf,
                     ConeValues& Lhat) {
  add_cone_sample(layout, cone_axes(layout, n), w, L_in, pdf, Lhat);
}

glm::vec3 reshade_cones(const ConeLayout& layout, const ConeValues& L) {
  glm::vec3 sum_cL(0.0f);
  for (int k = 0; k < kConeCount; ++k) sum_cL += layout.cosine_weight[size_t(k)] * L[size_t(k)];
  // L_o = (1/pi) sum_k c_k L_k [TRMV21 Eq. 11, with the cosine: cones.h].
  return sum_cL / glm::pi<float>();
}

glm::vec3 reshade_cones_literal(const ConeValues& L) {
  glm::vec3 sum_L(0.0f);
  for (const glm::vec3& L_k : L) sum_L += L_k;
  // L = f_r sum_k L_k pi/3, f_r = 1/pi [TRMV21 Eq. 11 as printed].
  return (1.0f / glm::pi<float>()) * sum_L * (glm::pi<float>() / 3.0f);
}

float cone_share_in_hemisphere(float theta_c, glm::vec3 axis, glm::vec3 n_target, glm::vec3 n_source) {
  glm::vec3 t, b;
  orthonormal_basis(axis, t, b);  // core/geometry.h
  const double cos_c = std::cos(double(theta_c));
  int above_target = 0, above_both = 0;
  // kConeShareGrid^2 directions uniform in the cap's solid angle: cos uniform in [cos theta_c, 1], azimuth uniform,
  // at the cells' midpoints (cones.h).
  for (int i = 0; i < kConeShareGrid; ++i) {
    const double cos_t = 1.0 - (double(i) + 0.5) / double(kConeShareGrid) * (1.0 - cos_c);
    const double sin_t = std::sqrt(std::max(0.0, 1.0 - cos_t * cos_t));
    for (int j = 0; j < kConeShareGrid; ++j) {
      const double phi = 2.0 * kPi * (double(j) + 0.5) / double(kConeShareGrid);
      const glm::vec3 w = float(sin_t * std::cos(phi)) * t + float(sin_t * std::sin(phi)) * b + float(cos_t) * axis;
      if (!(glm::dot(w, n_target) > 0.0f)) continue;  // below the target's horizon: not in Omega_k^+
      ++above_target;
      above_both += glm::dot(w, n_source) > 0.0f ? 1 : 0;
    }
  }
  // f_k = Omega(C_k, H_t, H_s) / Omega(C_k, H_t) [TRMV21 Fig. 7].
  return above_target > 0 ? float(above_both) / float(above_target) : 0.0f;
}

ConeTransfer transfer_cones(const ConeLayout& layout, glm::vec3 n_target, glm::vec3 n_source, const ConeValues& source,
                            bool full) {
  const ConeAxes a = cone_axes(layout, n_target);  // a_k, the target's axes
  const ConeAxes b = cone_axes(layout, n_source);  // b_m, the source's axes
  glm::vec3 mean(0.0f);
  for (const glm::vec3& L_m : source) mean += L_m / float(kConeCount);
  ConeTransfer out;
  for (int k = 0; k < kConeCount; ++k) {
    glm::vec3 sum_wL(0.0f);
    float sum_w = 0.0f;
    for (int m = 0; m < kConeCount; ++m) {
      const float angle = std::acos(std::clamp(glm::dot(a[size_t(k)], b[size_t(m)]), -1.0f, 1.0f));
      // The weight: the overlap of cone k and source cone m [TRMV21 Sec. 4.3, Eq. 9-10] at theta_T.
      const float w_km = cone_overlap_solid_angle(layout.transfer_half_angle, angle);
      sum_wL += w_km * source[size_t(m)];
      sum_w += w_km;
    }
    if (full) {  // the former transfer: all of it, the source's mean where nothing overlaps (cones.h)
      out.values[size_t(k)] = sum_w > 0.0f ? sum_wL / sum_w : mean;
      out.share[size_t(k)] = 1.0f;
      continue;
    }
    // No source cone overlaps cone k: nothing to carry, frame i's own (share 0) (cones.h).
    if (!(sum_w > 0.0f)) continue;
    out.values[size_t(k)] = sum_wL / sum_w;
    // f_k: the share of cone k inside the source's hemisphere [TRMV21 Sec. 4.3, Fig. 7].
    out.share[size_t(k)] = cone_share_in_hemisphere(layout.half_angle, a[size_t(k)], n_target, n_source);
  }
  return out;
}

ConeValues blend_transferred(const ConeTransfer& transfer, const ConeValues& current) {
  ConeValues out{};
  for (int k = 0; k < kConeCount; ++k) {
    const float f = transfer.share[size_t(k)];
    // H_k = f_k L'_k + (1 - f_k) L~_k [TRMV21 Fig. 7]: the spatial content of frame i for the rest.
    out[size_t(k)] = f * transfer.values[size_t(k)] + (1.0f - f) * current[size_t(k)];
  }
  return out;
}

}  // namespace rtdr
