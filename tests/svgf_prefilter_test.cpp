// Tests of filters/svgf/prefilter.cpp: the 3x3 Gaussian g3x3 of the variance [SVGF17 Sec. 4.4, Eq. 5].
#include "filters/svgf/prefilter.h"

#include <catch2/catch.hpp>

using namespace rtdr;

TEST_CASE("g3x3 of a constant variance is the constant, borders included", "[svgf][prefilter]") {
  // The nine weights sum to (1/4 + 1/2 + 1/4)^2 = 1, and clamped borders keep all nine, so c -> c.
  const FloatPlane var(9, 7, 0.37f);
  const FloatPlane out = prefilter_variance(var);
  for (int y = 0; y < var.height; ++y)
    for (int x = 0; x < var.width; ++x) CHECK(out.at(x, y) == Approx(0.37f).epsilon(1e-6));
}

TEST_CASE("g3x3 of a single spike is the 3x3 kernel", "[svgf][prefilter]") {
  // Var = 1 at (5, 4), 0 elsewhere: the output at (5 + dx, 4 + dy) is the weight g(-dx) g(-dy) with which that
  // pixel reads the spike, g = (1/4, 1/2, 1/4): 1/4 at the spike, 1/8 beside it, 1/16 at the corners, 0 beyond.
  FloatPlane var(11, 9, 0.0f);
  var.at(5, 4) = 1.0f;
  const FloatPlane out = prefilter_variance(var);
  const float g[3] = {0.25f, 0.5f, 0.25f};
  for (int y = 0; y < var.height; ++y)
    for (int x = 0; x < var.width; ++x) {
      const int dx = x - 5, dy = y - 4;
      const bool near = dx >= -1 && dx <= 1 && dy >= -1 && dy <= 1;
      const float expected = near ? g[dx + 1] * g[dy + 1] : 0.0f;
      INFO("pixel (" << x << ", " << y << ")");
      CHECK(out.at(x, y) == expected);  // powers of two: exact
    }
  CHECK(out.at(5, 4) == 0.25f);
  CHECK(out.at(6, 4) == 0.125f);
  CHECK(out.at(4, 3) == 0.0625f);
}

TEST_CASE("g3x3 clamps at the border: a corner spike is read by four taps", "[svgf][prefilter]") {
  // Var = 1 at (0, 0) only. At (0, 0) the taps (-1, -1), (0, -1), (-1, 0), (0, 0) all clamp to (0, 0):
  // (1/4 + 1/2) * (1/4 + 1/2) = 9/16. At (1, 0): taps (0, -1) and (0, 0) read it, 1/4 * (1/4 + 1/2) = 3/16.
  FloatPlane var(5, 5, 0.0f);
  var.at(0, 0) = 1.0f;
  CHECK(prefilter_variance_pixel(var, 0, 0) == 0.5625f);
  CHECK(prefilter_variance_pixel(var, 1, 0) == 0.1875f);
  CHECK(prefilter_variance_pixel(var, 1, 1) == 0.0625f);
  CHECK(prefilter_variance_pixel(var, 2, 0) == 0.0f);
}

TEST_CASE("g3x3 probe records every tap and the sum, the plane equals the per-pixel function", "[svgf][prefilter]") {
  FloatPlane var(6, 5);
  for (int y = 0; y < var.height; ++y)
    for (int x = 0; x < var.width; ++x) var.at(x, y) = 0.1f * float(x) + 0.03f * float(y * y);
  Probe probe;
  const float v = prefilter_variance_pixel(var, 2, 3, &probe);
  float sum = 0.0f, weights = 0.0f;
  for (int dy = -1; dy <= 1; ++dy)
    for (int dx = -1; dx <= 1; ++dx) {
      const std::string group = "g3x3 tap (" + std::to_string(dx) + ", " + std::to_string(dy) + ")";
      const float g = probe.find("g", group).value[0];
      CHECK(probe.find("Var(q)", group).value[0] == var.at(2 + dx, 3 + dy));
      sum += g * probe.find("Var(q)", group).value[0];
      weights += g;
    }
  CHECK(weights == 1.0f);
  CHECK(probe.find("g3x3(Var)(p)", "g3x3").value[0] == v);
  CHECK(sum == Approx(v).epsilon(1e-6));
  const FloatPlane out = prefilter_variance(var);
  for (int y = 0; y < var.height; ++y)
    for (int x = 0; x < var.width; ++x) CHECK(out.at(x, y) == prefilter_variance_pixel(var, x, y));
}
