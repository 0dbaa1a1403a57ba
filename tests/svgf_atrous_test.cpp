// Tests of filters/svgf/atrous.cpp: one a-trous level [SVGF17 Sec. 4.3, Eq. 1, 2 and the variance equation]
// with the B3 kernel [SVGF17 Eq. 1] and the 3x3 box [ASVGF18 Sec. 4]. Closed forms (constant in, constant out;
// a spike spreads with exactly the kernel's footprint; edges stop the filter), properties read off the probe,
// and the propagated variance against a Monte Carlo estimate.
#include "filters/svgf/atrous.h"

#include "core/color.h"
#include "core/error.h"
#include "filters/svgf/edge_stopping.h"
#include "filters/svgf/prefilter.h"

#include "svgf_fixtures.h"

#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <random>
#include <string>

using namespace rtdr;

namespace {


// A G-buffer where the weights differ from tap to tap: depth tilted along x, normals bending along y, a second
// mesh, and a few pixels without a surface.
SurfacePlanes varied_surface(int w, int h) {
  SurfacePlanes s = flat_surface(w, h);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      s.depth.at(x, y) = 2.0f + 0.02f * float(x) + 0.3f * float((x * 7 + y * 3) % 5 == 0);
      s.depth_grad.at(x, y) = {0.02f, 0.0f};
      s.normal.at(x, y) = glm::normalize(glm::vec3(0.0f, 0.04f * float(y - h / 2), 1.0f));
      s.mesh.at(x, y) = x < w / 3 ? 1u : 0u;
      if ((x * 5 + y * 11) % 23 == 0) s.mesh.at(x, y) = kInvalidId;
    }
  return s;
}

// A smooth G-buffer with unequal weights: a curved depth ramp along x (taps off p's column get w_z near
// exp(-1)), normals bending along y (taps off p's row get w_n < 1), one mesh, every pixel covered.
SurfacePlanes curved_surface(int w, int h) {
  SurfacePlanes s = flat_surface(w, h);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      s.depth.at(x, y) = 2.0f + 0.02f * float(x) + 0.001f * float(x * x);
      s.depth_grad.at(x, y) = {0.02f + 0.002f * float(x), 0.0f};  // d depth / dx, analytic
      s.normal.at(x, y) = glm::normalize(glm::vec3(0.0f, 0.04f * float(y - h / 2), 1.0f));
    }
  return s;
}

SvgfParams params(int kernel_size) {
  SvgfParams p;
  p.kernel_size = kernel_size;
  return p;
}

// The 1D kernel value of tap index k (-radius..radius), as the paper writes it (not read from atrous.cpp).
double h1(int kernel_size, int k) {
  const double b3[5] = {1.0 / 16, 1.0 / 4, 3.0 / 8, 1.0 / 4, 1.0 / 16};
  return kernel_size == 5 ? b3[k + 2] : 1.0 / 3.0;
}

std::string tap(int dx, int dy) { return "tap (" + std::to_string(dx) + ", " + std::to_string(dy) + ")"; }

}  // namespace

TEST_CASE("the kernels are B3 (1/16, 1/4, 3/8, 1/4, 1/16) and the 3x3 box, other sizes throw", "[svgf][atrous]") {
  const AtrousKernel b3 = atrous_kernel(5);
  CHECK(b3.radius == 2);
  for (int k = -2; k <= 2; ++k) CHECK(b3.h[k + 2] == float(h1(5, k)));
  const AtrousKernel box = atrous_kernel(3);
  CHECK(box.radius == 1);
  for (int k = -1; k <= 1; ++k) CHECK(box.h[k + 1] == float(1.0 / 3.0));
  CHECK_THROWS_AS(atrous_kernel(4), Error);
}

TEST_CASE("a constant image passes every level and both kernels unchanged", "[svgf][atrous]") {
  // Eq. 1 divides by the sum of its own weights, so a constant c gives c whatever the weights are.
  const int w = 40, h = 36;
  const SurfacePlanes s = varied_surface(w, h);
  const glm::vec3 c(0.8f, 2.5f, 0.05f);
  FloatPlane var(w, h);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) var.at(x, y) = 0.01f + 0.05f * float((x + 3 * y) % 7);
  for (int kernel_size : {3, 5})
    for (int level = 0; level < 5; ++level) {
      const AtrousOutput out = atrous_level(RgbPlane(w, h, c), var, s, level, params(kernel_size));
      for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
          INFO("kernel " << kernel_size << " level " << level << " pixel (" << x << ", " << y << ")");
          CHECK(out.color.at(x, y).r == Approx(c.r).epsilon(1e-6));
          CHECK(out.color.at(x, y).g == Approx(c.g).epsilon(1e-6));
          CHECK(out.color.at(x, y).b == Approx(c.b).epsilon(1e-6));
        }
    }
}

TEST_CASE("the probe's weights normalise and rebuild the output", "[svgf][atrous]") {
  const int w = 24, h = 20;
  const SurfacePlanes s = varied_surface(w, h);
  RgbPlane color(w, h);
  FloatPlane var(w, h);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      color.at(x, y) = glm::vec3(0.5f + 0.1f * float((x * y) % 9), 0.3f * float(x % 4), 1.0f);
      var.at(x, y) = 0.2f + 0.1f * float((x + y) % 3);
    }
  const FloatPlane var_g3x3 = prefilter_variance(var);
  for (int kernel_size : {3, 5})
    for (int level : {0, 1, 2}) {
      const SvgfParams p = params(kernel_size);
      const int x = 12, y = 9, step = 1 << level, r = kernel_size / 2;
      Probe probe;
      const AtrousPixel out = atrous_pixel(color, var, var_g3x3, s, level, p, x, y, &probe);
      const float sum_hw = probe.find("sum h w", "sum").value[0];
      double weights = 0.0, var_sum = 0.0;
      glm::dvec3 c_sum(0.0);
      for (int j = -r; j <= r; ++j)
        for (int k = -r; k <= r; ++k) {
          const std::string g = tap(k * step, j * step);
          const int qx = x + k * step, qy = y + j * step;
          if (!s.covered(qx, qy)) {
            CHECK(probe.find("skipped: no surface", g).value[0] == 1.0f);
            continue;
          }
          const double hw = probe.find("h w", g).value[0];
          CHECK(probe.find("h(q)", g).value[0] == Approx(h1(kernel_size, k) * h1(kernel_size, j)).epsilon(1e-6));
          // w = w_z w_n w_l [SVGF17 Eq. 2], exactly: the filter multiplies the weights edge_stopping.h
          // computes, the same values the probe reports.
          const float w_z = probe.find("w_z", g).value[0], w_n = probe.find("w_n", g).value[0];
          const float w_l = probe.find("w_l", g).value[0];
          CHECK(probe.find("w", g).value[0] == w_z * w_n * w_l);
          if (k != 0 || j != 0) {
            CHECK(w_z == weight_depth(s.depth.at(x, y), s.depth.at(qx, qy), s.depth_grad.at(x, y),
                                      glm::vec2(float(-k * step), float(-j * step)), p.sigma_z, p.epsilon));
            CHECK(w_n == weight_normal(s.normal.at(x, y), s.normal.at(qx, qy), p.sigma_n));
            CHECK(w_l == weight_luminance(luminance(color.at(x, y)), luminance(color.at(qx, qy)),
                                          var_g3x3.at(x, y), p.sigma_l, p.epsilon));
          }
          weights += hw / sum_hw;  // the normalised weight of tap q
          c_sum += hw / sum_hw * glm::dvec3(color.at(qx, qy));
          var_sum += hw * hw / (double(sum_hw) * sum_hw) * var.at(qx, qy);
        }
      INFO("kernel " << kernel_size << " level " << level);
      CHECK(weights == Approx(1.0).epsilon(1e-6));
      CHECK(probe.find("w", tap(0, 0)).value[0] == 1.0f);  // the centre tap [SVGF17 Eq. 3-5 at q = p]
      CHECK(out.color.r == Approx(c_sum.r).epsilon(1e-5));
      CHECK(out.color.g == Approx(c_sum.g).epsilon(1e-5));
      CHECK(out.variance == Approx(var_sum).epsilon(1e-5));
      CHECK(probe.find("Var(c_{i+1}(p))", "sum").value[0] == out.variance);
    }
}

TEST_CASE("on a flat G-buffer a spike spreads with exactly the kernel's footprint at the level's step",
          "[svgf][atrous]") {
  // Flat G-buffer: w_z = w_n = 1 exactly; sigma_l = 1e9 makes w_l = exp(-|dl| / (1e9 + 1e-4)) = 1 in float.
  // A spike of 1 at c: pixel p = c + 2^i (a, b) gathers it through the tap q = c with weight h(-a) h(-b), and
  // its kernel weights sum to 1 (all taps inside), so c_{i+1}(p) = h(a) h(b); every other pixel stays 0.
  const int n = 131, c = 65;  // level 4: |p - c| <= 2 * 16 and p's taps reach 2 * 16 further, inside [0, 130]
  const SurfacePlanes s = flat_surface(n, n);
  RgbPlane color(n, n, glm::vec3(0.0f));
  color.at(c, c) = glm::vec3(1.0f);
  const FloatPlane var(n, n, 1.0f);
  for (int kernel_size : {5, 3})
    for (int level = 0; level < 5; ++level) {
      SvgfParams p = params(kernel_size);
      p.sigma_l = 1e9f;
      const int step = 1 << level, r = kernel_size / 2;
      const AtrousOutput out = atrous_level(color, var, s, level, p);
      int nonzero = 0;
      for (int y = 0; y < n; ++y)
        for (int x = 0; x < n; ++x) {
          const int dx = x - c, dy = y - c;
          const bool on_grid = dx % step == 0 && dy % step == 0 && std::abs(dx) <= r * step && std::abs(dy) <= r * step;
          const double expected = on_grid ? h1(kernel_size, dx / step) * h1(kernel_size, dy / step) : 0.0;
          INFO("kernel " << kernel_size << " level " << level << " pixel (" << x << ", " << y << ")");
          REQUIRE(out.color.at(x, y).g == Approx(expected).margin(1e-6));
          nonzero += out.color.at(x, y).g != 0.0f;
        }
      CHECK(nonzero == (2 * r + 1) * (2 * r + 1));
      // Var = 1 everywhere, weights h: Var(c_{i+1}) = sum h^2 / (sum h)^2 = (sum_k h_k^2)^2, for B3
      // (2/256 + 2/16 + 9/64)^2 = 0.2734375^2 = 0.0747680664, for the box (3/9)^2 = 1/9.
      const double var_expected = kernel_size == 5 ? 0.2734375 * 0.2734375 : 1.0 / 9.0;
      CHECK(out.variance.at(c + 7, c - 3) == Approx(var_expected).epsilon(1e-6));
    }
}

TEST_CASE("the propagated variance matches a Monte Carlo estimate", "[svgf][atrous]") {
  // Weights fixed (sigma_l = 1e9 makes w_l = 1; w_z, w_n vary with a tilted, bending G-buffer and do not depend
  // on the noise). Inputs: grey colours (v, v, v), v = 1 + sqrt(Var(q)) N(0, 1), independent per pixel and
  // draw, so luminance l = v has variance Var(q). The output's luminance variance over 20000 draws must match
  // sum h^2 w^2 Var / (sum h w)^2 [SVGF17 Sec. 4.3]; its standard error is sqrt(2 / 20000) = 1%, we allow 4%.
  const int w = 21, h = 21, draws = 20000;
  const SurfacePlanes s = curved_surface(w, h);
  FloatPlane var(w, h);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) var.at(x, y) = 0.5f + 0.1f * float((3 * x + 5 * y) % 17);
  const FloatPlane var_g3x3 = prefilter_variance(var);
  SvgfParams p = params(5);
  p.sigma_l = 1e9f;
  const int pixels[3][2] = {{10, 10}, {0, 3}, {6, 17}};  // centre, border (taps skipped), off-centre
  for (int level : {0, 1}) {
    double sum[3] = {}, sum2[3] = {};
    float predicted[3] = {};
    std::mt19937 rng(1234u + unsigned(level));
    std::normal_distribution<float> normal(0.0f, 1.0f);
    RgbPlane color(w, h);
    for (int d = 0; d < draws; ++d) {
      for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) color.at(x, y) = glm::vec3(1.0f + std::sqrt(var.at(x, y)) * normal(rng));
      for (int i = 0; i < 3; ++i) {
        const AtrousPixel out = atrous_pixel(color, var, var_g3x3, s, level, p, pixels[i][0], pixels[i][1]);
        const double l = luminance(out.color);
        sum[i] += l;
        sum2[i] += l * l;
        predicted[i] = out.variance;  // the same every draw: the weights do not see the noise
      }
    }
    for (int i = 0; i < 3; ++i) {
      const double mean = sum[i] / draws;
      const double empirical = (sum2[i] - draws * mean * mean) / (draws - 1);
      INFO("level " << level << " pixel (" << pixels[i][0] << ", " << pixels[i][1] << ") empirical " << empirical
                    << " propagated " << predicted[i]);
      CHECK(empirical == Approx(predicted[i]).epsilon(0.04));
    }
  }
  // The weights really are unequal here, so the test covers the w^2 in the formula, not just h^2.
  Probe probe;
  atrous_pixel(RgbPlane(w, h, glm::vec3(1.0f)), var, var_g3x3, s, 0, p, 10, 10, &probe);
  CHECK(probe.find("w", tap(1, 0)).value[0] < 0.5f);
  CHECK(probe.find("w", tap(0, 1)).value[0] > 0.5f);
}

namespace {

// Filters a spike at (13, 8), left of an edge at x = 16, at levels 0..3; returns the largest output right of
// the edge (x >= 16). sigma_l = 1e9 so that only the G-buffer can stop the filter.
float leak_across(const SurfacePlanes& s, const RgbPlane& color) {
  SvgfParams p = params(5);
  p.sigma_l = 1e9f;
  float leak = 0.0f;
  for (int level = 0; level < 4; ++level) {
    const AtrousOutput out = atrous_level(color, FloatPlane(s.width(), s.height(), 1.0f), s, level, p);
    for (int y = 0; y < s.height(); ++y)
      for (int x = 16; x < s.width(); ++x) leak = std::max(leak, out.color.at(x, y).r);
  }
  return leak;
}

}  // namespace

TEST_CASE("depth, normal and no-surface steps stop the filter: no energy crosses", "[svgf][atrous]") {
  const int w = 32, h = 16;
  RgbPlane spike(w, h, glm::vec3(0.0f));
  spike.at(13, 8) = glm::vec3(1.0f);
  // Without an edge the spike does reach the right half (the control).
  CHECK(leak_across(flat_surface(w, h), spike) > 0.01f);

  SECTION("a depth step: exp(-|1 - 2| / (0 + 1e-4)) = exp(-10000) = 0") {
    SurfacePlanes s = flat_surface(w, h);
    for (int y = 0; y < h; ++y)
      for (int x = 16; x < w; ++x) s.depth.at(x, y) = 2.0f;
    CHECK(leak_across(s, spike) == 0.0f);
  }
  SECTION("a normal step: max(0, (0,0,1) . (1,0,0))^128 = 0") {
    SurfacePlanes s = flat_surface(w, h);
    for (int y = 0; y < h; ++y)
      for (int x = 16; x < w; ++x) s.normal.at(x, y) = {1.0f, 0.0f, 0.0f};
    CHECK(leak_across(s, spike) == 0.0f);
  }
  SECTION("a step to no surface: those taps are skipped, those pixels pass through") {
    SurfacePlanes s = flat_surface(w, h);
    RgbPlane color = spike;
    for (int y = 0; y < h; ++y)
      for (int x = 16; x < w; ++x) {
        s.mesh.at(x, y) = kInvalidId;
        color.at(x, y) = glm::vec3(5.0f);  // background colour that must not leak left
      }
    SvgfParams p = params(5);
    p.sigma_l = 1e9f;
    const FloatPlane var(w, h, 0.25f);
    for (int level = 0; level < 4; ++level) {
      const AtrousOutput with_bg = atrous_level(color, var, s, level, p);
      const AtrousOutput without_bg = atrous_level(spike, var, s, level, p);
      for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
          if (x < 16) CHECK(with_bg.color.at(x, y) == without_bg.color.at(x, y));  // the 5s were never read
          if (x >= 16) CHECK(with_bg.color.at(x, y) == glm::vec3(5.0f));        // passed through
          if (x >= 16) CHECK(with_bg.variance.at(x, y) == 0.25f);
        }
    }
  }
  SECTION("two meshes meeting in one plane are filtered across: SVGF's a-trous has no mesh-id weight") {
    SurfacePlanes s = flat_surface(w, h);
    for (int y = 0; y < h; ++y)
      for (int x = 16; x < w; ++x) s.mesh.at(x, y) = 7u;
    CHECK(leak_across(s, spike) == leak_across(flat_surface(w, h), spike));
  }
}

TEST_CASE("a luminance step far above the noise stops the filter", "[svgf][atrous]") {
  // Var = 0.01 (sd 0.1), sigma_l = 4: across a step of 10, w_l = exp(-10 / (4 * 0.1 + 1e-4)) = exp(-24.99)
  // = 1.4e-11, so each side keeps its value to 1e-9.
  const int w = 32, h = 12;
  RgbPlane color(w, h, glm::vec3(0.0f));
  for (int y = 0; y < h; ++y)
    for (int x = 16; x < w; ++x) color.at(x, y) = glm::vec3(10.0f);
  const AtrousOutput out = atrous_level(color, FloatPlane(w, h, 0.01f), flat_surface(w, h), 1, params(5));
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) CHECK(out.color.at(x, y).g == Approx(x < 16 ? 0.0f : 10.0f).margin(1e-6));
}

TEST_CASE("atrous_level is atrous_pixel on every pixel and keeps g3x3(Var)", "[svgf][atrous]") {
  const int w = 17, h = 13;
  const SurfacePlanes s = varied_surface(w, h);
  RgbPlane color(w, h);
  FloatPlane var(w, h);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      color.at(x, y) = glm::vec3(float((x * 3 + y) % 5), 1.0f, 0.5f * float(y % 3));
      var.at(x, y) = 0.1f * float((x + y) % 4);
    }
  const AtrousOutput out = atrous_level(color, var, s, 2, params(3));
  const FloatPlane var_g3x3 = prefilter_variance(var);
  CHECK(out.prefiltered_variance.data == var_g3x3.data);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      const AtrousPixel px = atrous_pixel(color, var, var_g3x3, s, 2, params(3), x, y);
      CHECK(out.color.at(x, y) == px.color);
      CHECK(out.variance.at(x, y) == px.variance);
    }
  CHECK_THROWS_AS(atrous_level(color, var, s, 0, params(4)), Error);
}
