// Tests of TRMV's six cones of incident radiance [TRMV21 Sec. 4.3, Eq. 9-11] (filters/trmv/cones.cpp): Eq. 9-10
// against Monte Carlo and at both ends of its domain; the covering layout's derivation re-checked by brute force;
// the re-shading weights c_k; the furnace through the per-cone estimator for many normals (and the paper-literal
// Eq. 11's factor 2); the estimator's mean against quadrature; the transfer between two normals (identity,
// uniform fields, and a smooth field carried to a tilted normal better than copying the cones).
//
// Monte Carlo draws come from std::mt19937_64 with fixed seeds and the explicit mapping (x >> 11) 2^-53 to [0, 1),
// so every run draws the same numbers on every platform. The Monte Carlo bounds are 3 standard errors of the
// estimate, measured from the same samples.
#include "filters/trmv/cones.h"

#include <catch2/catch.hpp>

#include <glm/gtc/constants.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <random>
#include <vector>

using namespace rtdr;

namespace {

constexpr double kPi = 3.14159265358979323846;

double uniform01(std::mt19937_64& rng) { return double(rng() >> 11) * 0x1.0p-53; }

// A frame (t, b) around n built differently from cones.cpp's Duff basis (a helper axis and cross products), so
// that the test's directions do not share the layout's frame.
void test_frame(glm::vec3 n, glm::vec3& t, glm::vec3& b) {
  const glm::vec3 h = std::abs(n.x) < 0.9f ? glm::vec3(1.0f, 0.0f, 0.0f) : glm::vec3(0.0f, 1.0f, 0.0f);
  t = glm::normalize(glm::cross(h, n));
  b = glm::cross(n, t);
}

// The midpoint of cell (i, j) of an n x n grid, uniform in solid angle over the hemisphere around `normal`: z = cos
// theta uniform (Archimedes), azimuth rotated by `phase`. Every cell spans 2 pi / n^2 sr.
glm::vec3 hemisphere_cell(glm::vec3 normal, glm::vec3 t, glm::vec3 b, int n, int i, int j, double phase) {
  const double z = (double(i) + 0.5) / double(n);
  const double phi = 2.0 * kPi * (double(j) + 0.5) / double(n) + phase;
  const double r = std::sqrt(1.0 - z * z);
  return float(r * std::cos(phi)) * t + float(r * std::sin(phi)) * b + float(z) * normal;
}

// Point i of the spherical Fibonacci set of N points over the whole sphere (Gonzalez 2010, "Measurement of
// areas on a sphere using Fibonacci and latitude-longitude lattices"): z = 1 - (2i + 1)/N, azimuth 2 pi i times
// the golden ratio's fractional part. Equal areas 4 pi / N, and unlike a latitude-longitude grid no cone's
// boundary runs along its rows (a cap around the grid's pole counts to within half a row, ~1/n, on such a grid).
glm::vec3 fibonacci_direction(int64_t i, int64_t count) {
  const double z = 1.0 - (2.0 * double(i) + 1.0) / double(count);
  const double turns = double(i) * 0.6180339887498949;
  const double phi = 2.0 * kPi * (turns - std::floor(turns));
  const double r = std::sqrt(std::max(0.0, 1.0 - z * z));
  return glm::vec3(float(r * std::cos(phi)), float(r * std::sin(phi)), float(z));
}

// The number of the layout's cones (local frame) containing w.
int cones_containing(const ConeLayout& layout, glm::vec3 w) {
  int count = 0;
  for (const glm::vec3& a : layout.axes) count += cone_contains(layout.half_angle, a, w) ? 1 : 0;
  return count;
}

// The two critical points of the covering (cones.h): P, equidistant from a_0, a_1, a_2, and E, on the horizon
// halfway between a_1 and a_2, both on the meridian at azimuth pi/5.
glm::vec3 point_p(float psi) {
  const double rho = std::atan(std::tan(0.5 * psi) / std::cos(kPi / 5.0));
  return glm::vec3(float(std::sin(rho) * std::cos(kPi / 5.0)), float(std::sin(rho) * std::sin(kPi / 5.0)),
                   float(std::cos(rho)));
}
glm::vec3 point_e() { return glm::vec3(float(std::cos(kPi / 5.0)), float(std::sin(kPi / 5.0)), 0.0f); }

// The largest angle from a direction of the hemisphere to the nearest axis of a layout whose ring lies at polar
// angle psi, by brute force over an n x n solid-angle grid plus the horizon.
double brute_force_covering_radius(float psi, int n) {
  ConeLayout layout = make_cone_layout(kConeCoveringHalfAngle);
  for (int k = 1; k < kConeCount; ++k) {
    const double azimuth = 2.0 * kPi * (k - 1) / 5.0;
    layout.axes[size_t(k)] = glm::vec3(float(std::sin(psi) * std::cos(azimuth)),
                                       float(std::sin(psi) * std::sin(azimuth)), float(std::cos(psi)));
  }
  auto distance_to_nearest = [&](glm::vec3 w) {
    float best = -1.0f;
    for (const glm::vec3& a : layout.axes) best = std::max(best, glm::dot(a, w));
    return std::acos(std::clamp(double(best), -1.0, 1.0));
  };
  double worst = 0.0;
  const glm::vec3 z(0.0f, 0.0f, 1.0f), x(1.0f, 0.0f, 0.0f), y(0.0f, 1.0f, 0.0f);
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j) worst = std::max(worst, distance_to_nearest(hemisphere_cell(z, x, y, n, i, j, 0.0)));
  for (int j = 0; j < 8 * n; ++j) {  // the horizon itself, where E lies
    const double phi = 2.0 * kPi * (j + 0.5) / (8.0 * n);
    worst = std::max(worst, distance_to_nearest(glm::vec3(float(std::cos(phi)), float(std::sin(phi)), 0.0f)));
  }
  return worst;
}

// Monte Carlo estimate of the overlap of two cones of half-angle theta, axes a apart: directions uniform in the
// first cap (z = cos uniform in [cos theta, 1]), the fraction f inside the second, Omega = cap f.
struct Estimate {
  double mean, standard_error;
};
Estimate overlap_monte_carlo(double theta, double a, int samples, uint64_t seed) {
  std::mt19937_64 rng(seed);
  const glm::dvec3 axis2(std::sin(a), 0.0, std::cos(a));
  const double cos_theta = std::cos(theta);
  int64_t hits = 0;
  for (int s = 0; s < samples; ++s) {
    const double z = cos_theta + (1.0 - cos_theta) * uniform01(rng), phi = 2.0 * kPi * uniform01(rng);
    const double r = std::sqrt(std::max(0.0, 1.0 - z * z));
    hits += glm::dot(glm::dvec3(r * std::cos(phi), r * std::sin(phi), z), axis2) >= cos_theta ? 1 : 0;
  }
  const double cap = 2.0 * kPi * (1.0 - cos_theta), f = double(hits) / samples;
  return {cap * f, cap * std::sqrt(f * (1.0 - f) / samples)};
}

}  // namespace

TEST_CASE("Eq. 9-10 against Monte Carlo (10^6 directions each, 3 standard errors): pi/6 at a = 0.2, 0.4, 0.6, 0.9 gives 0.6428, 0.4501, 0.2711, 0.0551") {
  const double expected[] = {0.6428, 0.4501, 0.2711, 0.0551};
  const double separations[] = {0.2, 0.4, 0.6, 0.9};
  for (int i = 0; i < 4; ++i) {
    const float omega = cone_overlap_solid_angle(kConePaperHalfAngle, float(separations[i]));
    const Estimate mc = overlap_monte_carlo(kConePaperHalfAngle, separations[i], 1000000, 11 + i);
    std::printf("Eq. 9-10, theta_c = pi/6, a = %.2f: Omega = %.5f, Monte Carlo %.5f +- %.5f\n", separations[i], omega,
                mc.mean, mc.standard_error);
    INFO("a = " << separations[i] << ": Omega " << omega << ", Monte Carlo " << mc.mean << " +- " << mc.standard_error);
    CHECK(std::abs(omega - expected[i]) < 1e-4);
    CHECK(std::abs(omega - mc.mean) < 3.0 * mc.standard_error);
  }
  // The covering half-angle, at separations that matter for the layout: the ring's neighbours (66.87 degrees)
  // and a ring cone against the normal's (psi* = 69.62 degrees).
  for (const double a : {0.3, 0.8, 1.1671294, double(kConeRingPolarAngle), 1.4}) {
    const float omega = cone_overlap_solid_angle(kConeCoveringHalfAngle, float(a));
    const Estimate mc = overlap_monte_carlo(kConeCoveringHalfAngle, a, 1000000, 97 + uint64_t(a * 1000));
    std::printf("Eq. 9-10, theta_c = %.4f, a = %.4f: Omega = %.5f, Monte Carlo %.5f +- %.5f\n",
                double(kConeCoveringHalfAngle), a, omega, mc.mean, mc.standard_error);
    INFO("a = " << a << ": Omega " << omega << ", Monte Carlo " << mc.mean << " +- " << mc.standard_error);
    CHECK(std::abs(omega - mc.mean) < 3.0 * mc.standard_error);
  }
}

TEST_CASE("Eq. 9-10 at the ends: the whole cap at a = 0 with slope -2 sin theta_c, 0 from a = 2 theta_c on, symmetric and decreasing") {
  for (const float theta : {kConePaperHalfAngle, kConeCoveringHalfAngle, 0.2f, 1.2f}) {
    INFO("theta_c = " << theta);
    const float cap = cone_solid_angle(theta);
    CHECK(cap == Approx(2.0 * kPi * (1.0 - std::cos(double(theta)))).epsilon(1e-6));
    CHECK(cone_overlap_solid_angle(theta, 0.0f) == cap);
    // Continuous at a = 0: Omega(a) = cap - 2 sin(theta_c) a + O(a^2) (the boundary sweeps out 2 a sin theta_c).
    const float a = 1e-4f;
    const float omega_a = cone_overlap_solid_angle(theta, a);
    CHECK(std::abs(omega_a - (cap - 2.0f * std::sin(theta) * a)) < 1e-6f);
    CHECK(std::abs(omega_a - cap) <= 2.0f * std::sin(theta) * a + 1e-6f);
    CHECK(std::abs(cone_overlap_solid_angle(theta, 1e-6f) - cap) < 1e-5f);
    // Continuous at a = 2 theta_c, and exactly 0 from there on.
    CHECK(cone_overlap_solid_angle(theta, 2.0f * theta - 1e-4f) > 0.0f);
    CHECK(cone_overlap_solid_angle(theta, 2.0f * theta - 1e-4f) < 1e-5f);
    CHECK(cone_overlap_solid_angle(theta, 2.0f * theta) == 0.0f);
    CHECK(cone_overlap_solid_angle(theta, 2.0f * theta + 1e-3f) == 0.0f);
    CHECK(cone_overlap_solid_angle(theta, glm::pi<float>()) == 0.0f);
    // Symmetric: Eq. 10's gamma is a/2, the plane halfway between the axes, so the lens is two equal halves.
    for (float s = 0.05f; s < 2.0f * theta; s += 0.05f) {
      const double b = std::acos(std::sin(s / 2.0) / std::sin(double(theta)));
      const double f = std::acos(std::tan(s / 2.0) / std::tan(double(theta)));
      CHECK(cone_overlap_solid_angle(theta, s) == Approx(4.0 * (b - f * std::cos(double(theta)))).margin(1e-6));
    }
    // Decreasing in a over the whole range.
    float previous = cap;
    for (int i = 1; i <= 1000; ++i) {
      const float omega = cone_overlap_solid_angle(theta, 2.0f * theta * float(i) / 1000.0f);
      CHECK(omega <= previous);
      previous = omega;
    }
  }
}

TEST_CASE("a cone's solid angle above the horizon: closed form against Monte Carlo, half the cap with the axis on the horizon") {
  const float theta = kConeCoveringHalfAngle;
  CHECK(cone_solid_angle_above_horizon(theta, 0.0f) == Approx(cone_solid_angle(theta)).epsilon(1e-6));
  CHECK(cone_solid_angle_above_horizon(theta, glm::half_pi<float>()) ==
        Approx(0.5 * cone_solid_angle(theta)).epsilon(1e-5));
  CHECK(cone_solid_angle_above_horizon(theta, glm::half_pi<float>() + theta + 1e-3f) == 0.0f);
  for (const double psi : {double(kConeRingPolarAngle), 1.0, 1.8}) {
    std::mt19937_64 rng(5 + uint64_t(psi * 100));
    const double cos_theta = std::cos(double(theta));
    const glm::dvec3 axis(std::sin(psi), 0.0, std::cos(psi)), t(std::cos(psi), 0.0, -std::sin(psi)), b(0.0, 1.0, 0.0);
    const int samples = 1000000;
    int64_t above = 0;
    for (int s = 0; s < samples; ++s) {  // uniform in the cap around `axis`
      const double z = cos_theta + (1.0 - cos_theta) * uniform01(rng), phi = 2.0 * kPi * uniform01(rng);
      const double r = std::sqrt(std::max(0.0, 1.0 - z * z));
      above += (r * std::cos(phi) * t + r * std::sin(phi) * b + z * axis).z > 0.0 ? 1 : 0;
    }
    const double cap = cone_solid_angle(theta), f = double(above) / samples;
    const double mc = cap * f, se = cap * std::sqrt(f * (1.0 - f) / samples);
    const float omega = cone_solid_angle_above_horizon(theta, float(psi));
    std::printf("Omega^+(theta_c = %.4f, psi = %.4f) = %.5f, Monte Carlo %.5f +- %.5f\n", double(theta), psi, omega,
                mc, se);
    CHECK(std::abs(omega - mc) < 3.0 * se);
  }
}

TEST_CASE("the covering layout: psi* and theta* re-derived by brute force, every direction of a 10^6 grid covered, neighbours overlap") {
  // R(psi) closed form against brute force: a 1000 x 1000 grid of the hemisphere plus its horizon finds the
  // farthest direction to within its cell size (about 2.5e-3 rad), and never beyond the true one.
  for (const float psi : {kConeRingPolarAngle, 1.1f, 1.3f}) {
    const double brute = brute_force_covering_radius(psi, 1000);
    std::printf("covering radius at psi = %.4f: closed form %.6f, brute force %.6f\n", double(psi),
                double(cone_covering_radius(psi)), brute);
    CHECK(brute <= cone_covering_radius(psi) + 1e-5);
    CHECK(brute >= cone_covering_radius(psi) - 3e-3);
  }
  // psi* minimises R(psi): a scan in steps of 1e-5 rad over [pi/4, pi/2] finds it, and R(psi*) = theta*.
  float best_psi = 0.0f, best_r = 10.0f;
  for (float psi = 0.25f * glm::pi<float>(); psi <= glm::half_pi<float>(); psi += 1e-5f)
    if (cone_covering_radius(psi) < best_r) best_r = cone_covering_radius(psi), best_psi = psi;
  std::printf("scan: psi* = %.6f rad (%.4f deg), theta* = %.6f rad (%.4f deg)\n", double(best_psi),
              double(glm::degrees(best_psi)), double(best_r), double(glm::degrees(best_r)));
  CHECK(std::abs(best_psi - kConeRingPolarAngle) < 2e-5f);
  CHECK(std::abs(best_r - kConeMinimalCoveringHalfAngle) < 1e-5f);  // R has a kink of slopes ~ +-0.5 there
  CHECK(cone_covering_radius(kConeRingPolarAngle) == Approx(kConeMinimalCoveringHalfAngle).margin(1e-6));
  CHECK(kConeCoveringHalfAngle >= kConeMinimalCoveringHalfAngle);

  // Every direction of a 1000 x 1000 solid-angle grid, of the horizon, and the critical points P and E lie in
  // at least one cone of the covering layout.
  const ConeLayout layout = make_cone_layout();
  const glm::vec3 z(0.0f, 0.0f, 1.0f), x(1.0f, 0.0f, 0.0f), y(0.0f, 1.0f, 0.0f);
  int64_t uncovered = 0, most = 0;
  for (int i = 0; i < 1000; ++i)
    for (int j = 0; j < 1000; ++j) {
      const int count = cones_containing(layout, hemisphere_cell(z, x, y, 1000, i, j, 0.0));
      uncovered += count == 0 ? 1 : 0;
      most = std::max<int64_t>(most, count);
    }
  for (int j = 0; j < 100000; ++j) {
    const double phi = 2.0 * kPi * (j + 0.5) / 100000.0;
    uncovered += cones_containing(layout, glm::vec3(float(std::cos(phi)), float(std::sin(phi)), 0.0f)) == 0 ? 1 : 0;
  }
  std::printf("covering layout: %lld of 1.1e6 directions uncovered, at most %lld cones overlap\n",
              (long long)uncovered, (long long)most);
  CHECK(uncovered == 0);
  CHECK(cones_containing(layout, point_p(kConeRingPolarAngle)) == 3);
  CHECK(cones_containing(layout, point_e()) == 2);
  // theta* is the least that covers: 0.002 rad less and P and E fall outside every cone.
  const ConeLayout short_of = make_cone_layout(kConeMinimalCoveringHalfAngle - 0.002f);
  CHECK(cones_containing(short_of, point_p(kConeRingPolarAngle)) == 0);
  CHECK(cones_containing(short_of, point_e()) == 0);

  // Neighbours overlap: a_0 with each ring cone, and each ring cone with the next.
  for (int k = 1; k < kConeCount; ++k) {
    const int next = k % 5 + 1;
    const float to_normal = std::acos(glm::dot(layout.axes[0], layout.axes[size_t(k)]));
    const float to_next = std::acos(glm::dot(layout.axes[size_t(k)], layout.axes[size_t(next)]));
    CHECK(cone_overlap_solid_angle(layout.half_angle, to_normal) > 0.0f);
    CHECK(cone_overlap_solid_angle(layout.half_angle, to_next) > 0.0f);
    if (k == 1)
      std::printf("covering layout: Omega(a_0, a_1) = %.5f sr, Omega(a_1, a_2) = %.5f sr, each cone %.5f sr\n",
                  double(cone_overlap_solid_angle(layout.half_angle, to_normal)),
                  double(cone_overlap_solid_angle(layout.half_angle, to_next)),
                  double(cone_solid_angle(layout.half_angle)));
  }
}

TEST_CASE("the paper-literal layout (half-angle pi/6) leaves part of the hemisphere uncovered and its neighbours disjoint") {
  const ConeLayout paper = make_cone_layout(kConePaperHalfAngle);
  const glm::vec3 z(0.0f, 0.0f, 1.0f), x(1.0f, 0.0f, 0.0f), y(0.0f, 1.0f, 0.0f);
  int64_t uncovered = 0;
  const int n = 1000;
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j)
      uncovered += cones_containing(paper, hemisphere_cell(z, x, y, n, i, j, 0.0)) == 0 ? 1 : 0;
  const double fraction = double(uncovered) / (double(n) * n);
  double sum_c = 0.0;
  for (const float c : paper.cosine_weight) sum_c += c;
  std::printf("pi/6 layout: %.4f of the hemisphere's solid angle in no cone; sum c_k = %.5f (pi = %.5f)\n", fraction,
              sum_c, kPi);
  CHECK(fraction > 0.01);
  CHECK(sum_c < kPi - 0.01);
  CHECK(cone_overlap_solid_angle(kConePaperHalfAngle, std::acos(glm::dot(paper.axes[1], paper.axes[2]))) == 0.0f);
  CHECK(cone_overlap_solid_angle(kConePaperHalfAngle, std::acos(glm::dot(paper.axes[0], paper.axes[1]))) == 0.0f);
  // Eq. 9-10's transfer weights are the paper's own there: theta_T = pi/6.
  CHECK(paper.transfer_half_angle == kConePaperHalfAngle);
}

TEST_CASE("c_k: sum pi within 1e-4, the five ring cones equal, converged on the 1024 grid to 1e-6 of a 4096 grid") {
  const ConeLayout layout = make_cone_layout();
  std::array<float, kConeCount> fine = cone_cosine_weights(layout.axes, layout.half_angle, 4096);
  // The raw grid's ring values differ a little (cones.h); make_cone_layout takes their mean, and so does this.
  float ring_low = fine[1], ring_high = fine[1], fine_ring = 0.0f;
  for (int k = 1; k < kConeCount; ++k) {
    ring_low = std::min(ring_low, fine[size_t(k)]);
    ring_high = std::max(ring_high, fine[size_t(k)]);
    fine_ring += fine[size_t(k)] / 5.0f;
  }
  std::printf("4096 grid: the five ring c_k span %.2e before their mean is taken\n", double(ring_high - ring_low));
  for (int k = 1; k < kConeCount; ++k) fine[size_t(k)] = fine_ring;
  double sum_c = 0.0, largest_change = 0.0;
  for (int k = 0; k < kConeCount; ++k) {
    sum_c += layout.cosine_weight[size_t(k)];
    largest_change = std::max(largest_change, std::abs(double(layout.cosine_weight[size_t(k)]) - fine[size_t(k)]));
    std::printf("c_%d = %.6f (4096 grid %.6f), Omega_%d^+ = %.6f sr\n", k, double(layout.cosine_weight[size_t(k)]),
                double(fine[size_t(k)]), k, double(layout.solid_angle[size_t(k)]));
  }
  std::printf("sum c_k = %.7f, largest change to the 4096 grid %.2e, transfer half-angle %.5f rad\n", sum_c,
              largest_change, double(layout.transfer_half_angle));
  CHECK(std::abs(sum_c - kPi) < 1e-4);
  CHECK(largest_change < 1e-6);
  for (int k = 2; k < kConeCount; ++k) CHECK(layout.cosine_weight[size_t(k)] == layout.cosine_weight[1]);
  // The cone around the normal lies wholly above the horizon; a ring cone reaches 110 degrees, so part of it is
  // below and its Omega^+ is less than the cap.
  CHECK(layout.solid_angle[0] == Approx(cone_solid_angle(layout.half_angle)).epsilon(1e-6));
  CHECK(layout.solid_angle[1] < cone_solid_angle(layout.half_angle));
}

TEST_CASE("cones furnace: uniform radiance through the per-cone estimates re-shades to L within 1e-4 for any normal, the literal Eq. 11 to 2 L") {
  const ConeLayout layout = make_cone_layout();
  const glm::vec3 L(0.3f, 0.7f, 1.2f);
  // The normals: the poles (n = -z is where Frisvad's basis divides by zero), beside -z (the Duff basis' worst
  // rounding), on Duff's seam n.z = +-0, and two generic ones.
  const std::vector<glm::vec3> normals = {
      glm::vec3(0.0f, 0.0f, 1.0f),     glm::vec3(0.0f, 0.0f, -1.0f),
      glm::normalize(glm::vec3(1e-4f, 0.0f, -1.0f)), glm::normalize(glm::vec3(0.0f, 1e-7f, -1.0f)),
      glm::vec3(1.0f, 0.0f, -0.0f),    glm::vec3(0.0f, 1.0f, 0.0f),
      glm::normalize(glm::vec3(0.3f, -0.5f, 0.8f)), glm::normalize(glm::vec3(-0.7f, 0.2f, -0.3f))};
  for (const glm::vec3& n : normals) {
    INFO("n = (" << n.x << ", " << n.y << ", " << n.z << ")");
    // The world axes are orthonormally placed around n: a_0 = n, the ring at psi* from it.
    const ConeAxes axes = cone_axes(layout, n);
    CHECK(glm::length(axes[0] - n) < 1e-6f);
    for (int k = 1; k < kConeCount; ++k) {
      CHECK(glm::length(axes[size_t(k)]) == Approx(1.0f).epsilon(1e-5));
      CHECK(glm::dot(axes[size_t(k)], n) == Approx(std::cos(kConeRingPolarAngle)).margin(1e-5));
    }
    // The estimates: every direction of a 2 10^6-point spherical Fibonacci set as a sample of pdf 1/(4 pi); the
    // estimator drops the half below the horizon. Summed in double (a float sum of 10^6 terms drifts by 1e-3).
    const int64_t points = 2000000;
    std::array<glm::dvec3, kConeCount> sum{};
    for (int64_t i = 0; i < points; ++i) {
      ConeValues Lhat{};
      add_cone_sample(layout, axes, fibonacci_direction(i, points), L, float(1.0 / (4.0 * kPi)), Lhat);
      for (int k = 0; k < kConeCount; ++k) sum[size_t(k)] += glm::dvec3(Lhat[size_t(k)]);
    }
    ConeValues Lbar{};
    for (int k = 0; k < kConeCount; ++k) Lbar[size_t(k)] = glm::vec3(sum[size_t(k)] / double(points));
    const glm::vec3 L_o = reshade_cones(layout, Lbar);
    std::printf("furnace n = (%+.4f, %+.4f, %+.4f): Lbar_1 = %.6f (L 0.3), L_o = (%.6f, %.6f, %.6f)\n", n.x, n.y, n.z,
                double(Lbar[1].x), double(L_o.x), double(L_o.y), double(L_o.z));
    for (int k = 0; k < kConeCount; ++k) CHECK(glm::length(Lbar[size_t(k)] - L) < 2e-4f * glm::length(L));
    CHECK(std::abs(L_o.x - L.x) < 1e-4f);
    CHECK(std::abs(L_o.y - L.y) < 1e-4f);
    CHECK(std::abs(L_o.z - L.z) < 1e-4f);
  }
  // The paper's Eq. 11 on the same uniform field: 2 L (no cosine; cones.h).
  ConeValues uniform{};
  uniform.fill(L);
  const glm::vec3 literal = reshade_cones_literal(uniform);
  std::printf("literal Eq. 11 on L = (0.3, 0.7, 1.2): (%.6f, %.6f, %.6f)\n", double(literal.x), double(literal.y),
              double(literal.z));
  CHECK(std::abs(literal.x - 2.0f * L.x) < 1e-4f);
  CHECK(std::abs(literal.y - 2.0f * L.y) < 1e-4f);
  CHECK(std::abs(literal.z - 2.0f * L.z) < 1e-4f);
  CHECK(glm::length(reshade_cones(layout, uniform) - L) < 1e-4f);
}

TEST_CASE("per-cone estimator: 10^5 cosine-weighted samples of L = 1 + w.x average to each cone's mean of L within 3 standard errors") {
  const ConeLayout layout = make_cone_layout();
  const glm::vec3 n = glm::normalize(glm::vec3(0.6f, -0.3f, 0.5f));
  const ConeAxes axes = cone_axes(layout, n);
  glm::vec3 t, b;
  test_frame(n, t, b);
  auto radiance = [](glm::vec3 w) { return 1.0 + double(w.x); };
  // The cone means by quadrature: L averaged over the points of a 4 10^6-point spherical Fibonacci set that lie
  // in cone k above the horizon.
  const int64_t points = 4000000;
  std::array<double, kConeCount> sum_L{}, count{};
  for (int64_t i = 0; i < points; ++i) {
    const glm::vec3 w = fibonacci_direction(i, points);
    if (glm::dot(w, n) <= 0.0f) continue;
    for (int k = 0; k < kConeCount; ++k)
      if (cone_contains(layout.half_angle, axes[size_t(k)], w)) {
        sum_L[size_t(k)] += radiance(w);
        count[size_t(k)] += 1.0;
      }
  }
  // The estimates: one sample per draw, w cosine-weighted (pdf cos theta / pi), each single-sample Lhat_k kept
  // for its mean and standard error.
  std::mt19937_64 rng(2021);
  const int samples = 100000;
  std::array<double, kConeCount> sum{}, sum2{};
  for (int s = 0; s < samples; ++s) {
    const double u1 = uniform01(rng), u2 = uniform01(rng);
    const double r = std::sqrt(u1), phi = 2.0 * kPi * u2, cos_theta = std::sqrt(1.0 - u1);
    const glm::vec3 w = float(r * std::cos(phi)) * t + float(r * std::sin(phi)) * b + float(cos_theta) * n;
    ConeValues Lhat{};
    add_cone_sample(layout, axes, w, glm::vec3(float(radiance(w))), float(cos_theta / kPi), Lhat);
    for (int k = 0; k < kConeCount; ++k) {
      const double lhat_k = Lhat[size_t(k)].x;
      sum[size_t(k)] += lhat_k;
      sum2[size_t(k)] += lhat_k * lhat_k;
    }
  }
  for (int k = 0; k < kConeCount; ++k) {
    const double quadrature = sum_L[size_t(k)] / count[size_t(k)];
    const double mean = sum[size_t(k)] / samples;
    const double se = std::sqrt((sum2[size_t(k)] / samples - mean * mean) / (samples - 1));
    std::printf("cone %d: mean of L by quadrature %.5f, estimator %.5f +- %.5f\n", k, quadrature, mean, se);
    INFO("cone " << k << ": quadrature " << quadrature << ", estimate " << mean << " +- " << se);
    CHECK(std::abs(mean - quadrature) < 3.0 * se);
    CHECK(se < 0.02 * quadrature);  // the bound is tight enough to mean something
  }
  // The point set's solid angle of each cone agrees with Omega_k^+, the estimator's normalisation.
  for (int k = 0; k < kConeCount; ++k) {
    const double omega = count[size_t(k)] * 4.0 * kPi / double(points);
    std::printf("cone %d: Omega^+ closed form %.6f, Fibonacci count %.6f\n", k, double(layout.solid_angle[size_t(k)]),
                omega);
    CHECK(omega == Approx(layout.solid_angle[size_t(k)]).epsilon(1e-4));
  }
}

TEST_CASE("transfer between two normals: the identity for equal normals, with share 1, and a uniform field stays uniform") {
  const ConeLayout layout = make_cone_layout();
  std::mt19937_64 rng(7);
  auto random_cones = [&]() {
    ConeValues L{};
    for (glm::vec3& v : L) v = glm::vec3(float(uniform01(rng)), float(uniform01(rng)), float(uniform01(rng)));
    return L;
  };
  auto random_normal = [&]() {
    const double z = 2.0 * uniform01(rng) - 1.0, phi = 2.0 * kPi * uniform01(rng), r = std::sqrt(1.0 - z * z);
    return glm::vec3(float(r * std::cos(phi)), float(r * std::sin(phi)), float(z));
  };
  std::vector<glm::vec3> normals = {glm::vec3(0.0f, 0.0f, 1.0f), glm::vec3(0.0f, 0.0f, -1.0f),
                                    glm::normalize(glm::vec3(1e-4f, 0.0f, -1.0f)), glm::vec3(1.0f, 0.0f, -0.0f)};
  for (int i = 0; i < 20; ++i) normals.push_back(random_normal());
  for (const ConeLayout& l : {layout, make_cone_layout(kConePaperHalfAngle)})
    for (const glm::vec3& n : normals) {
      const ConeValues source = random_cones();
      const ConeTransfer same = transfer_cones(l, n, n, source);
      for (int k = 0; k < kConeCount; ++k) {
        CHECK(glm::length(same.values[size_t(k)] - source[size_t(k)]) < 1e-6f);
        CHECK(same.share[size_t(k)] == 1.0f);  // the source's hemisphere is the target's: all of each cone
      }
      // Blending with this frame's cones then changes nothing.
      const ConeValues blended = blend_transferred(same, random_cones());
      for (int k = 0; k < kConeCount; ++k) CHECK(glm::length(blended[size_t(k)] - source[size_t(k)]) < 1e-6f);
    }
  // A uniform field, between every pair of normals: each cone's carried value is the field where any source cone
  // overlaps it; blended with this frame's field, the same, it stays uniform whatever the shares. (The former full
  // transfer, `full`, answered opposite normals with the source mean; its values stay uniform too.)
  const glm::vec3 L(0.3f, 0.7f, 1.2f);
  ConeValues uniform{};
  uniform.fill(L);
  float worst = 0.0f;
  for (const glm::vec3& p : normals)
    for (const glm::vec3& q : normals) {
      const ConeTransfer moved = transfer_cones(layout, p, q, uniform);
      for (const glm::vec3& v : blend_transferred(moved, uniform)) worst = std::max(worst, glm::length(v - L));
      for (const glm::vec3& v : transfer_cones(layout, p, q, uniform, true).values)
        worst = std::max(worst, glm::length(v - L));
    }
  const glm::vec3 up(0.0f, 0.0f, 1.0f), down(0.0f, 0.0f, -1.0f);
  for (const glm::vec3& v : transfer_cones(layout, up, down, uniform, true).values)
    worst = std::max(worst, glm::length(v - L));
  std::printf("transfer of a uniform field: largest deviation %.2e over %zu normal pairs\n", double(worst),
              normals.size() * normals.size());
  CHECK(worst < 1e-6f);
  // Between opposite normals the target's axes are the source's mirrored: a_0 = -b_0 and no pair is closer than
  // 180 - 2 psi* = 40.8 degrees, so some target cones get no overlap: the former transfer gave them the source
  // mean; now they have no share, and frame i's cone stands [TRMV21 Sec. 4.3, Fig. 7]. The source's hemisphere is
  // the target's lower one: every share is 0.
  ConeValues ramp{};
  for (int m = 0; m < kConeCount; ++m) ramp[size_t(m)] = glm::vec3(float(m));
  CHECK(transfer_cones(layout, up, down, ramp, true).values[0].x == Approx(2.5f));  // the mean of 0..5
  const ConeTransfer flipped = transfer_cones(layout, up, down, ramp);
  for (float f : flipped.share) CHECK(f == 0.0f);
  ConeValues own{};
  own.fill(glm::vec3(9.0f));
  for (const glm::vec3& v : blend_transferred(flipped, own)) CHECK(v == glm::vec3(9.0f));
}

TEST_CASE("the transfer's share: f_k against Monte Carlo (10^6 directions) within 0.02, 1 and 0 at the ends") {
  // f_k = Omega(C_k, H_t, H_s) / Omega(C_k, H_t) [TRMV21 Sec. 4.3, Fig. 7], counted on a 16x16 grid of the cap
  // (cones.h); here against a Fibonacci set of the sphere, for target +z and sources tilted by 0.3, 0.8 and 1.4 rad.
  const ConeLayout layout = make_cone_layout();
  const glm::vec3 n_t(0.0f, 0.0f, 1.0f);
  const ConeAxes a = cone_axes(layout, n_t);
  float worst = 0.0f;
  for (double tilt : {0.3, 0.8, 1.4}) {
    const glm::vec3 n_s(float(std::sin(tilt)), 0.0f, float(std::cos(tilt)));
    std::array<double, kConeCount> above_t{}, above_both{};
    const int64_t points = 1000000;
    for (int64_t i = 0; i < points; ++i) {
      const glm::vec3 w = fibonacci_direction(i, points);
      if (!(glm::dot(w, n_t) > 0.0f)) continue;
      for (int k = 0; k < kConeCount; ++k)
        if (cone_contains(layout.half_angle, a[size_t(k)], w)) {
          above_t[size_t(k)] += 1.0;
          above_both[size_t(k)] += glm::dot(w, n_s) > 0.0f ? 1.0 : 0.0;
        }
    }
    for (int k = 0; k < kConeCount; ++k) {
      const float expected = float(above_both[size_t(k)] / above_t[size_t(k)]);
      const float f = cone_share_in_hemisphere(layout.half_angle, a[size_t(k)], n_t, n_s);
      worst = std::max(worst, std::abs(f - expected));
    }
  }
  std::printf("transfer share: largest |grid - Monte Carlo| %.4f\n", double(worst));
  CHECK(worst < 0.02f);
  CHECK(cone_share_in_hemisphere(layout.half_angle, a[0], n_t, n_t) == 1.0f);
  CHECK(cone_share_in_hemisphere(layout.half_angle, a[0], n_t, -n_t) == 0.0f);
}

TEST_CASE("transfer of a smooth field to a tilted normal: closer to the target's own cone means than copying the cones") {
  // L(w) = 1 + w.x, the cones' means over their parts above each normal's horizon by a 10^6-point Fibonacci set;
  // the source around n_q = +z, the target around n_p tilted by 0.3 rad towards +x. Copying the source's cones
  // (reusing colour, in effect) ignores the tilt; the transfer looks up the directions each target cone covers.
  const ConeLayout layout = make_cone_layout();
  auto cone_means = [&](glm::vec3 n) {
    const ConeAxes axes = cone_axes(layout, n);
    std::array<double, kConeCount> sum{}, count{};
    const int64_t points = 1000000;
    for (int64_t i = 0; i < points; ++i) {
      const glm::vec3 w = fibonacci_direction(i, points);
      if (glm::dot(w, n) <= 0.0f) continue;
      for (int k = 0; k < kConeCount; ++k)
        if (cone_contains(layout.half_angle, axes[size_t(k)], w)) {
          sum[size_t(k)] += 1.0 + double(w.x);
          count[size_t(k)] += 1.0;
        }
    }
    ConeValues L{};
    for (int k = 0; k < kConeCount; ++k) L[size_t(k)] = glm::vec3(float(sum[size_t(k)] / count[size_t(k)]));
    return L;
  };
  const glm::vec3 n_q(0.0f, 0.0f, 1.0f), n_p(float(std::sin(0.3)), 0.0f, float(std::cos(0.3)));
  const ConeValues source = cone_means(n_q), truth = cone_means(n_p);
  const ConeValues moved = transfer_cones(layout, n_p, n_q, source).values;
  double error_transfer = 0.0, error_copy = 0.0;
  for (int k = 0; k < kConeCount; ++k) {
    error_transfer += std::abs(double(moved[size_t(k)].x - truth[size_t(k)].x));
    error_copy += std::abs(double(source[size_t(k)].x - truth[size_t(k)].x));
  }
  std::printf("tilt 0.3 rad: mean |error| of the transferred cones %.4f, of the copied cones %.4f\n",
              error_transfer / kConeCount, error_copy / kConeCount);
  CHECK(error_transfer < error_copy);
}
