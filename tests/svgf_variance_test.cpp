// Tests of filters/svgf/variance.cpp [SVGF17 Sec. 4.2]: the temporal estimate mu2' - mu1'^2, the 7x7 spatial
// fallback against hand-computed weighted variances, and the synthetic test of SVGF17 Eq. 6 / Fig. 9.
#include "filters/svgf/variance.h"

#include "core/error.h"
#include "filters/svgf/temporal.h"

#include "svgf_fixtures.h"

#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <random>

using namespace rtdr;

namespace {


// A temporal output with the given moments and history length everywhere.
TemporalOutput moments(int w, int h, float mu1, float mu2, float n) {
  return {RgbPlane(w, h, glm::vec3(mu1)), FloatPlane(w, h, mu1), FloatPlane(w, h, mu2), FloatPlane(w, h, n)};
}

}  // namespace

TEST_CASE("temporal estimate (n >= 4): sigma'^2 = mu2' - mu1'^2, never negative") {
  const SurfacePlanes s = flat_surface(3, 3);
  const SvgfParams params;  // variance_min_history = 4
  // Exact in float: 0.75 - 0.5^2 = 0.5.
  CHECK(variance_pixel(moments(3, 3, 0.5f, 0.75f, 4.0f), s, params, 1, 1) == 0.5f);
  // Rounding can put mu2' a hair below mu1'^2 where the variance is 0: clamped to 0.
  CHECK(variance_pixel(moments(3, 3, 0.1f, 0.00999f, 9.0f), s, params, 1, 1) == 0.0f);

  std::mt19937 rng(4);
  std::uniform_real_distribution<float> u(0.0f, 2.0f);
  for (int i = 0; i < 1000; ++i) {
    const float mu1 = u(rng), mu2 = mu1 * mu1 + u(rng) - 0.2f;  // sometimes below mu1^2
    const float sigma2 = variance_pixel(moments(3, 3, mu1, mu2, 4.0f + float(i % 3)), s, params, 1, 1);
    CHECK(sigma2 == std::max(0.0f, mu2 - mu1 * mu1));
    CHECK(sigma2 >= 0.0f);
  }
}

TEST_CASE("n < 4 switches to the spatial estimate, no surface gives 0") {
  SurfacePlanes s = flat_surface(9, 9);
  TemporalOutput t = moments(9, 9, 0.5f, 0.75f, 3.0f);
  t.moment1.at(5, 4) = 1.0f;  // a neighbour that differs: the spatial estimate sees it, the temporal one not
  const SvgfParams params;
  Probe probe;
  CHECK(variance_pixel(t, s, params, 4, 4, &probe) != 0.5f);
  CHECK(probe.find("temporal estimate (n >= variance_min_history)", "variance").value[0] == 0.0f);
  t.length.at(4, 4) = 4.0f;
  CHECK(variance_pixel(t, s, params, 4, 4) == 0.5f);
  s.mesh.at(4, 4) = kInvalidId;
  CHECK(variance_pixel(t, s, params, 4, 4) == 0.0f);
}

TEST_CASE("spatial 7x7 estimate equals the hand-computed weighted variance") {
  const int w = 9, h = 9;
  SvgfParams params;
  SECTION("by hand: box weights, one pixel without surface, one off the plane, one tilted normal") {
    params.sigma_n = 1.0f;  // w_n = n(p) . n(q): a tilted normal of cosine 0.5 weighs 0.5
    SurfacePlanes s = flat_surface(w, h);
    // Columns 0..2 hold mu1' = mu2' = 1 (a sample of luminance 1), the rest 0; n = 1 (just disoccluded).
    TemporalOutput t = moments(w, h, 0.0f, 0.0f, 1.0f);
    for (int y = 0; y < h; ++y)
      for (int x = 0; x <= 2; ++x) t.moment1.at(x, y) = t.moment2.at(x, y) = 1.0f;
    // The 7x7 around (4, 4) spans x, y in 1..7: 14 ones (columns 1, 2) and 35 zeros, each of weight 1, but
    // (1, 1) sees no surface (a one dropped), (7, 7) lies at depth 5 (w_z = exp(-4 / 1e-4) = 0, a zero
    // dropped) and (6, 4) has a normal at 60 degrees (w_n = 0.5, a zero at half weight).
    s.mesh.at(1, 1) = kInvalidId;
    s.depth.at(7, 7) = 5.0f;
    s.normal.at(6, 4) = glm::vec3(std::sqrt(0.75f), 0.0f, 0.5f);
    // sum w = 49 - 2 - 0.5 = 46.5; sum w mu1' = sum w mu2' = 13.
    const double mu1 = 13.0 / 46.5, mu2 = 13.0 / 46.5;
    Probe probe;
    const float sigma2 = variance_pixel(t, s, params, 4, 4, &probe);
    CHECK(probe.find("sum w", "spatial estimate").value[0] == Approx(46.5).epsilon(1e-6));
    CHECK(sigma2 == Approx(mu2 - mu1 * mu1).epsilon(1e-6));  // 0.2013...
    CHECK(probe.find("w_n", "7x7 tap (2, 0)").value[0] == Approx(0.5).epsilon(1e-6));
  }
  SECTION("a tilted plane with random moments, against the sum written out in double") {
    SurfacePlanes s = flat_surface(w, h);
    TemporalOutput t = moments(w, h, 0.0f, 0.0f, 2.0f);
    std::mt19937 rng(8);
    std::uniform_real_distribution<float> u(0.0f, 1.0f);
    for (int y = 0; y < h; ++y)
      for (int x = 0; x < w; ++x) {
        s.depth.at(x, y) = 2.0f + 0.1f * float(x) + 0.05f * float(y);  // depth gradient (0.1, 0.05)
        s.depth_grad.at(x, y) = glm::vec2(0.1f, 0.05f);
        const float tilt = 0.3f * u(rng);  // normals up to ~17 degrees off
        s.normal.at(x, y) = glm::vec3(std::sin(tilt), 0.0f, std::cos(tilt));
        t.moment1.at(x, y) = u(rng);
        t.moment2.at(x, y) = t.moment1.at(x, y) * t.moment1.at(x, y) + 0.5f * u(rng);
      }
    s.depth.at(3, 5) += 0.3f;  // a step off the plane
    s.mesh.at(5, 2) = kInvalidId;
    for (const glm::ivec2 p : {glm::ivec2(4, 4), glm::ivec2(1, 2), glm::ivec2(8, 8)}) {  // centre, near edges
      double sum_w = 0.0, m1 = 0.0, m2 = 0.0;
      for (int y = p.y - 3; y <= p.y + 3; ++y)
        for (int x = p.x - 3; x <= p.x + 3; ++x) {
          if (x < 0 || y < 0 || x >= w || y >= h || s.mesh.at(x, y) == kInvalidId) continue;
          // w_z [SVGF17 Eq. 3] and w_n [SVGF17 Eq. 4] in double.
          const double dz = std::abs(double(s.depth.at(p.x, p.y)) - double(s.depth.at(x, y)));
          const double predicted = 1.0 * std::abs(0.1 * (p.x - x) + 0.05 * (p.y - y)) + 1e-4;
          const glm::dvec3 np(s.normal.at(p.x, p.y)), nq(s.normal.at(x, y));
          const double wgt = std::exp(-dz / predicted) * std::pow(std::max(0.0, glm::dot(np, nq)), 128.0);
          sum_w += wgt;
          m1 += wgt * t.moment1.at(x, y);
          m2 += wgt * t.moment2.at(x, y);
        }
      const double expected = m2 / sum_w - (m1 / sum_w) * (m1 / sum_w);
      INFO("pixel (" << p.x << ", " << p.y << ")");
      CHECK(variance_pixel(t, s, params, p.x, p.y) == Approx(expected).epsilon(1e-4).margin(1e-6));
    }
  }
}

TEST_CASE("variance_pass checks sizes and is never negative") {
  const SurfacePlanes s = flat_surface(6, 5);
  std::mt19937 rng(3);
  std::uniform_real_distribution<float> u(0.0f, 1.0f);
  TemporalOutput t = moments(6, 5, 0.0f, 0.0f, 1.0f);
  for (size_t i = 0; i < t.moment1.data.size(); ++i) {
    t.moment1.data[i] = u(rng);
    t.moment2.data[i] = t.moment1.data[i] * t.moment1.data[i] * (1.0f - 1e-6f);  // variance 0, rounded below
    t.length.data[i] = float(1 + i % 6);
  }
  for (float sigma2 : variance_pass(t, s, SvgfParams{}).data) CHECK(sigma2 >= 0.0f);
  t.length = FloatPlane(6, 6);
  CHECK_THROWS_AS(variance_pass(t, s, SvgfParams{}), Error);
}

// ---- The synthetic test of SVGF17 Sec. 5.2, Eq. 6 and Fig. 9 ---------------------------------------------
//
// Each pixel draws f(x, a) = 0 if x < a else 1 / (1 - a), x uniform in [0, 1): mean 1, and
//   Var(f) = E[f^2] - 1 = (1 - a) / (1 - a)^2 - 1 = a / (1 - a),
// with a swept across the columns from 0 to 0.95. "Structured" multiplies f by a pattern c(y) (bands of two
// rows at 0.5 and 1.5), as the paper's "structured noise" does: then the mean is c and Var = c^2 a / (1 - a).
//
// Which variance: SVGF's sigma'^2 = mu2' - mu1'^2 estimates the variance of ONE SAMPLE, Var(f), not the
// variance of the accumulated estimate C' (for the EMA that is alpha / (2 - alpha) Var(f) = Var(f) / 9), so
// both estimates are compared with Var(f). The temporal one is biased low by design: E[mu1'^2] = 1 +
// Var(mu1') makes E[sigma'^2] = (1 - alpha / (2 - alpha)) Var(f) = 0.889 Var(f).
//
// Temporal: the temporal pass on a static, flat G-buffer (colour history = the integrated colour), 40 frames
// of warm-up (n >= 4 long before), then 200 measured frames. Spatial-only: every frame a disocclusion (an
// empty history, n = 1), so the 7x7 spatial estimate of each frame's raw samples.
namespace {

struct Fig9Errors {
  double rmse_temporal = 0.0, rmse_spatial = 0.0;  // RMS of (estimate - Var(f)) over pixels and frames
  double mean_temporal = 0.0, mean_spatial = 0.0, mean_true = 0.0;
};

// Errors over the columns with a <= 0.95 / 4 (the low-variance quarter) and over all columns.
void run_fig9(bool structured, Fig9Errors& low, Fig9Errors& all) {
  const int w = 64, h = 16, warmup = 40, frames = 240;
  const SurfacePlanes s = flat_surface(w, h);
  const SvgfParams params;
  const auto a_of = [&](int x) { return 0.95f * float(x) / float(w - 1); };
  const auto c_of = [&](int y) { return structured ? ((y / 2) % 2 ? 1.5f : 0.5f) : 1.0f; };
  std::mt19937 rng(2017);
  std::uniform_real_distribution<float> u(0.0f, 1.0f);
  TemporalHistory prev;
  double n_low = 0.0, n_all = 0.0;
  for (int frame = 0; frame < frames; ++frame) {
    RgbPlane noisy(w, h);
    for (int y = 0; y < h; ++y)
      for (int x = 0; x < w; ++x) {
        const float a = a_of(x);
        const float f = u(rng) < a ? 0.0f : 1.0f / (1.0f - a);  // [SVGF17 Eq. 6]
        noisy.at(x, y) = glm::vec3(c_of(y) * f);                // grey: luminance c f
      }
    const TemporalOutput t = temporal_pass(noisy, s, prev, params);
    prev = {t.color, t.moment1, t.moment2, t.length, s};
    const FloatPlane var_temporal = variance_pass(t, s, params);
    const FloatPlane var_spatial = variance_pass(temporal_pass(noisy, s, TemporalHistory{}, params), s, params);
    if (frame < warmup) continue;
    REQUIRE(*std::min_element(t.length.data.begin(), t.length.data.end()) >= 4.0f);  // the temporal estimate
    for (int y = 0; y < h; ++y)
      for (int x = 0; x < w; ++x) {
        const double a = a_of(x), c = c_of(y), var_f = c * c * a / (1.0 - a);
        const double et = var_temporal.at(x, y) - var_f, es = var_spatial.at(x, y) - var_f;
        for (Fig9Errors* e : {&all, x < w / 4 ? &low : nullptr}) {
          if (!e) continue;
          e->rmse_temporal += et * et;
          e->rmse_spatial += es * es;
          e->mean_temporal += var_temporal.at(x, y);
          e->mean_spatial += var_spatial.at(x, y);
          e->mean_true += var_f;
          (e == &all ? n_all : n_low) += 1.0;
        }
      }
  }
  for (auto [e, n] : {std::pair{&low, n_low}, std::pair{&all, n_all}}) {
    e->rmse_temporal = std::sqrt(e->rmse_temporal / n);
    e->rmse_spatial = std::sqrt(e->rmse_spatial / n);
    e->mean_temporal /= n;
    e->mean_spatial /= n;
    e->mean_true /= n;
  }
}

std::string describe(const char* side, const Fig9Errors& e) {
  char line[256];
  std::snprintf(line, sizeof line,
                "%s: RMSE temporal %.4f, spatial %.4f; mean estimate temporal %.4f, spatial %.4f, true Var(f) %.4f\n",
                side, e.rmse_temporal, e.rmse_spatial, e.mean_temporal, e.mean_spatial, e.mean_true);
  return line;
}

}  // namespace

TEST_CASE("SVGF17 Fig. 9 (Eq. 6 with structure): the temporal estimate beats the spatial one where noise is low") {
  Fig9Errors low, all;
  run_fig9(true, low, all);
  INFO(describe("a <= 0.23", low) << describe("all a", all));
  // Measured (seed 2017, 64x16, 200 frames):
  //   a <= 0.23: RMSE temporal 0.1426, spatial 0.3059; mean temporal 0.1482, spatial 0.4132, true 0.1682
  //   all a:     RMSE temporal 6.3351, spatial 5.9713; mean temporal 2.5364, spatial 2.9720, true 2.8449
  // The spatial estimate counts the bands' own contrast (a variance without noise, SVGF17 Sec. 4.2) as noise:
  // on the low side its mean is 0.25 too high, about 2.5x the true variance; the temporal one sees one
  // pixel's samples only. On the noisy side (a near 0.95, Var(f) up to 19) both are dominated by the rare
  // large samples and the 49-sample spatial estimate is the less noisy one (RMSE over all a).
  CHECK(low.rmse_temporal < 0.6 * low.rmse_spatial);
  CHECK(low.mean_temporal == Approx(0.889 * low.mean_true).epsilon(0.1));  // the EMA's bias (see above)
}

TEST_CASE("SVGF17 Eq. 6 without structure: the spatial estimate, 49 samples, is the less noisy one") {
  Fig9Errors low, all;
  run_fig9(false, low, all);
  INFO(describe("a <= 0.23", low) << describe("all a", all));
  // Measured (seed 2017, 64x16, 200 frames):
  //   a <= 0.23: RMSE temporal 0.0889, spatial 0.0459; mean temporal 0.1208, spatial 0.1370, true 0.1345
  //   all a:     RMSE temporal 3.9140, spatial 2.3372; mean temporal 2.0135, spatial 2.1764, true 2.2760
  // Where the mean is the same everywhere the 7x7 window is 49 samples of (nearly) one distribution, while the
  // EMA with alpha = 0.2 holds about (2 - alpha) / alpha = 9 samples' worth: the temporal estimate is noisier.
  // Its advantage in SVGF is not fewer samples but no structure counted as noise (the test above).
  CHECK(low.rmse_spatial < low.rmse_temporal);
}
