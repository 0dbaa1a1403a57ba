// Tests of filters/trmv/reflection.cpp: TRMV's glossy filter, the BRDF lobe's footprint [TRMV21 Sec. 5, after
// LLK*19]: the Gaussian of Sigma_i + I / 12 by hand, its orientation, the round fallback, the window.
#include "filters/trmv/reflection.h"

#include "core/error.h"

#include <catch2/catch.hpp>

#include <cmath>
#include <cstdlib>

using namespace rtdr;

namespace {

SurfacePlanes flat(int w, int h) {
  return {FloatPlane(w, h, 3.0f), Vec2Plane(w, h, glm::vec2(0.0f)), RgbPlane(w, h, glm::vec3(0.0f, 0.0f, 1.0f)),
          UIntPlane(w, h, 0u), Vec2Plane(w, h, glm::vec2(0.0f))};
}

TrmvFootprint footprint(int w, int h, float xx, float xy, float yy, uint32_t valid = 1u) {
  return {FloatPlane(w, h, xx), FloatPlane(w, h, xy), FloatPlane(w, h, yy), UIntPlane(w, h, valid)};
}

// The filtered value at the centre of a (2r + 1)^2 image holding 1 at offset d and 0 elsewhere, by hand in double:
// g(d) / sum_q g(q) with g = exp(-q^T S^-1 q / 2), S = Sigma + I / 12 (w_z = w_n = 1 on the flat surface).
double expected(double xx, double xy, double yy, int r, glm::ivec2 d) {
  const double a = xx + 1.0 / 12.0, b = xy, c = yy + 1.0 / 12.0, det = a * c - b * b;
  const auto g = [&](int x, int y) { return std::exp(-0.5 * (c * x * x - 2.0 * b * x * y + a * y * y) / det); };
  double sum = 0.0;
  for (int y = -r; y <= r; ++y)
    for (int x = -r; x <= r; ++x) sum += g(x, y);
  return g(d.x, d.y) / sum;
}

}  // namespace

TEST_CASE("lobe filter: the footprint's Gaussian by hand, tilted along its ellipse, zero beyond the window") {
  const int r = 3, n = 2 * r + 1;
  const SvgfParams edges;
  // Sigma with stds 2 px along x, 1 px along y, correlated 0.6: the footprint of a lobe seen at a slant.
  const float xx = 4.0f, xy = 1.2f, yy = 1.0f;
  for (const glm::ivec2 d : {glm::ivec2(1, 0), glm::ivec2(0, 1), glm::ivec2(2, 1), glm::ivec2(2, -1), glm::ivec2(3, 3)}) {
    RgbPlane c(n, n, glm::vec3(0.0f));
    c.at(r + d.x, r + d.y) = glm::vec3(1.0f);
    const glm::vec3 out = trmv_reflection_pixel(c, flat(n, n), footprint(n, n, xx, xy, yy), r, edges, r, r);
    INFO("offset " << d.x << ", " << d.y);
    CHECK(out.x == Approx(expected(xx, xy, yy, r, d)).epsilon(1e-5));
  }
  // The ellipse leans along +x+y: a tap at (2, 1) weighs more than one at (2, -1).
  RgbPlane plus(n, n, glm::vec3(0.0f)), minus = plus;
  plus.at(r + 2, r + 1) = minus.at(r + 2, r - 1) = glm::vec3(1.0f);
  const TrmvFootprint f = footprint(n, n, xx, xy, yy);
  CHECK(trmv_reflection_pixel(plus, flat(n, n), f, r, edges, r, r).x >
        trmv_reflection_pixel(minus, flat(n, n), f, r, edges, r, r).x);
  // Beyond the window: nothing.
  RgbPlane far(11, 11, glm::vec3(0.0f));
  far.at(9, 5) = glm::vec3(1.0f);  // 4 from the centre (5, 5), the window reaches 3
  CHECK(trmv_reflection_pixel(far, flat(11, 11), footprint(11, 11, xx, xy, yy), r, edges, 5, 5).x == 0.0f);
}

TEST_CASE("lobe filter: a mirror's footprint keeps the pixel, no footprint is the window's round Gaussian") {
  const int r = 5, n = 2 * r + 1;
  const SvgfParams edges;
  RgbPlane c(n, n, glm::vec3(0.0f));
  c.at(r, r) = glm::vec3(1.0f);
  // A mirror (Sigma ~ 0): S = I / 12, a neighbour weighs exp(-6) = 0.0025 of the centre.
  const glm::vec3 mirror = trmv_reflection_pixel(c, flat(n, n), footprint(n, n, 0, 0, 0), r, edges, r, r);
  CHECK(mirror.x == Approx(expected(0, 0, 0, r, {0, 0})).epsilon(1e-5));
  CHECK(mirror.x > 0.98f);
  // No footprint (the lobe wider than any window): the round Gaussian of std r / 3.
  const double sigma = double(r) / 3.0, s2 = sigma * sigma;
  const glm::vec3 none = trmv_reflection_pixel(c, flat(n, n), footprint(n, n, 0, 0, 0, 0u), r, edges, r, r);
  CHECK(none.x == Approx(expected(s2 - 1.0 / 12.0, 0.0, s2 - 1.0 / 12.0, r, {0, 0})).epsilon(1e-5));
  // A constant stays constant through the pass, whatever the footprints.
  TrmvFootprint mixed = footprint(n, n, 3.0f, -0.5f, 0.7f);
  mixed.valid.at(2, 3) = 0u;
  const RgbPlane out = trmv_reflection_pass(RgbPlane(n, n, glm::vec3(0.3f)), flat(n, n), mixed, r, edges);
  for (const glm::vec3& v : out.data) CHECK(v.x == Approx(0.3f).epsilon(1e-6));
  CHECK_THROWS_AS(trmv_reflection_pass(c, flat(n, n), footprint(n, n + 1, 0, 0, 0), r, edges), Error);
}
