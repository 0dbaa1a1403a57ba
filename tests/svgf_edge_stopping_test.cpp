// Tests of filters/svgf/edge_stopping.cpp: the weights w_z, w_n, w_l [SVGF17 Eq. 3-5] against values worked out
// by hand (the arithmetic is in the comments; the digits are from double-precision evaluation).
#include "filters/svgf/edge_stopping.h"

#include <catch2/catch.hpp>

#include <cmath>

using namespace rtdr;

TEST_CASE("w_z [SVGF17 Eq. 3] matches hand-computed values", "[svgf][edge_stopping]") {
  const float eps = 1e-4f;
  // z(p) = 2, z(q) = 2.5, grad z(p) = (0.1, 0.05) per pixel, p - q = (2, 0), sigma_z = 1:
  //   grad . (p - q) = 0.1 * 2 + 0.05 * 0 = 0.2;  denominator 1 * 0.2 + 1e-4 = 0.2001
  //   |z(p) - z(q)| / 0.2001 = 0.5 / 0.2001 = 2.49875062;  exp(-2.49875062) = 0.0821876177
  CHECK(weight_depth(2.0f, 2.5f, {0.1f, 0.05f}, {2.0f, 0.0f}, 1.0f, eps) == Approx(0.0821876177).epsilon(1e-6));
  // The same tap one level up is twice as far, p - q = (4, 0): the plane predicts twice the change.
  //   grad . (p - q) = 0.4;  0.5 / 0.4001 = 1.24968758;  exp(-1.24968758) = 0.286594321
  CHECK(weight_depth(2.0f, 2.5f, {0.1f, 0.05f}, {4.0f, 0.0f}, 1.0f, eps) == Approx(0.286594321).epsilon(1e-6));
  // sigma_z = 2 at p - q = (2, 0) gives the same denominator 2 * 0.2 + 1e-4 = 0.4001, hence the same weight.
  CHECK(weight_depth(2.0f, 2.5f, {0.1f, 0.05f}, {2.0f, 0.0f}, 2.0f, eps) == Approx(0.286594321).epsilon(1e-6));
  // The sign of p - q does not matter: |grad . (q - p)| = |grad . (p - q)|.
  CHECK(weight_depth(2.0f, 2.5f, {0.1f, 0.05f}, {-2.0f, 0.0f}, 1.0f, eps) ==
        weight_depth(2.0f, 2.5f, {0.1f, 0.05f}, {2.0f, 0.0f}, 1.0f, eps));
  // The gradient is projected on the offset: grad = (0.1, 0.05), p - q = (1, -2) gives 0.1 - 0.1 = 0, so the
  // plane predicts no change and any depth difference is an edge: exp(-0.5 / 1e-4) = exp(-5000) = 0.
  CHECK(weight_depth(2.0f, 2.5f, {0.1f, 0.05f}, {1.0f, -2.0f}, 1.0f, eps) == 0.0f);
}

TEST_CASE("w_z is exactly 1 where the depth matches, including q = p and a flat G-buffer", "[svgf][edge_stopping]") {
  // q = p: |z(p) - z(q)| = 0 and grad . 0 = 0, so 0 / (0 + epsilon) = 0 and exp(-0) = 1.
  CHECK(weight_depth(3.7f, 3.7f, {0.3f, -0.2f}, {0.0f, 0.0f}, 1.0f, 1e-4f) == 1.0f);
  // A plane facing the camera: grad = 0, equal depths, any offset: 0 / epsilon = 0, exp(-0) = 1.
  CHECK(weight_depth(1.0f, 1.0f, {0.0f, 0.0f}, {16.0f, -32.0f}, 1.0f, 1e-4f) == 1.0f);
  // The same plane with a depth step of 0.01: exp(-0.01 / 1e-4) = exp(-100) = 3.7e-44 (a float denormal).
  CHECK(weight_depth(1.0f, 1.01f, {0.0f, 0.0f}, {1.0f, 0.0f}, 1.0f, 1e-4f) < 1e-40f);
}

TEST_CASE("w_z on a tilted plane is about exp(-1 / sigma_z)", "[svgf][edge_stopping]") {
  // Linear depth along a tilted line, z = 2 + 0.01 x: the first-order model is exact for it, so
  // |dz| / (sigma_z |grad . d|) = 0.03 / 0.03 = 1 (epsilon aside): w_z = exp(-0.03 / 0.0301) = 0.368493.
  CHECK(weight_depth(2.0f, 2.03f, {0.01f, 0.0f}, {-3.0f, 0.0f}, 1.0f, 1e-4f) ==
        Approx(std::exp(-0.03 / 0.0301)).epsilon(1e-5));
}

TEST_CASE("w_n [SVGF17 Eq. 4] matches hand-computed values", "[svgf][edge_stopping]") {
  const glm::vec3 n_p(0.0f, 0.0f, 1.0f);
  // Identical normals: max(0, 1)^128 = 1.
  CHECK(weight_normal(n_p, n_p, 128.0f) == 1.0f);
  // n(p) . n(q) = 0.99 (n(q) = (0, sqrt(1 - 0.99^2), 0.99)): 0.99^128 = exp(128 ln 0.99) = exp(-1.28644299)
  //   = 0.276251668.
  const glm::vec3 n_q(0.0f, std::sqrt(1.0f - 0.99f * 0.99f), 0.99f);
  CHECK(weight_normal(n_p, n_q, 128.0f) == Approx(0.276251668).epsilon(1e-5));
  // sigma_n = 4 at cos = 0.8: 0.8^4 = 0.4096.
  CHECK(weight_normal(n_p, {0.0f, 0.6f, 0.8f}, 4.0f) == Approx(0.4096f).epsilon(1e-6));
  // Perpendicular (cos 0) and opposite (cos -1, clamped by max(0, .)) normals both give 0.
  CHECK(weight_normal(n_p, {1.0f, 0.0f, 0.0f}, 128.0f) == 0.0f);
  CHECK(weight_normal(n_p, {0.0f, 0.0f, -1.0f}, 128.0f) == 0.0f);
}

TEST_CASE("w_l [SVGF17 Eq. 5] matches hand-computed values", "[svgf][edge_stopping]") {
  // l(p) = 1, l(q) = 1.5, g3x3(Var)(p) = 0.04 (standard deviation 0.2), sigma_l = 4, epsilon = 1e-4:
  //   denominator 4 * 0.2 + 1e-4 = 0.8001;  0.5 / 0.8001 = 0.624921885;  exp(-0.624921885) = 0.535303242
  CHECK(weight_luminance(1.0f, 1.5f, 0.04f, 4.0f, 1e-4f) == Approx(0.535303242).epsilon(1e-6));
  // Symmetric in l(p) - l(q).
  CHECK(weight_luminance(1.5f, 1.0f, 0.04f, 4.0f, 1e-4f) == weight_luminance(1.0f, 1.5f, 0.04f, 4.0f, 1e-4f));
  // sigma_l = 1, Var = 0.0025 (sd 0.05), epsilon = 0.01, difference 0.3:
  //   0.3 / (1 * 0.05 + 0.01) = 5;  exp(-5) = 0.006737947
  CHECK(weight_luminance(2.0f, 2.3f, 0.0025f, 1.0f, 0.01f) == Approx(0.006737947).epsilon(1e-5));
  // q = p: 0 / (sigma_l sd + epsilon) = 0, exp(-0) = 1 exactly, even with zero variance.
  CHECK(weight_luminance(0.7f, 0.7f, 0.0f, 4.0f, 1e-4f) == 1.0f);
  // A variance rounded below 0 counts as 0: 0.001 / (4 * 0 + 1e-4) = 10, exp(-10) = 4.53999298e-5.
  CHECK(weight_luminance(1.0f, 1.001f, -1e-9f, 4.0f, 1e-4f) == Approx(4.53999298e-5).epsilon(1e-3));
}
