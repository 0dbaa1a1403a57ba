// Tests of TRMV's clean-up filter [TRMV21 Sec. 5, Eq. 7-8] (filters/trmv/cleanup.cpp): w_A, w_C and the std by
// hand, the identity where nothing was clamped and alpha^V = alpha, constants kept, and the separable filter at a
// lone pixel with a std, by hand.
#include "filters/trmv/cleanup.h"

#include "filters/trmv/falloff.h"
#include "filters/trmv/spatial.h"

#include "svgf_fixtures.h"

#include "trmv_fixtures.h"

#include <catch2/catch.hpp>

#include <glm/gtc/constants.hpp>

#include <cmath>

using namespace rtdr;

namespace {

// A temporal output whose history was not clamped anywhere: fetched = clamped.
TrmvTemporalOutput unclamped(const RgbPlane& color) {
  const RgbPlane h = noise_rgb(color.width, color.height, 99);
  return {color, h, h, FloatPlane(color.width, color.height, 0.1f)};
}

}  // namespace

TEST_CASE("Eq. 7 by hand: w_A = 0.12540, 0.60559, 0.01118 for theta - pi/2 = 0.1, 0.2, 0.05 rad") {
  const float half_pi = glm::half_pi<float>();
  CHECK(trmv_weight_alpha(trmv_falloff_alpha(half_pi + 0.1f, 0.1f, 0.1f), 0.1f) == Approx(0.12540).margin(1e-5));
  CHECK(trmv_weight_alpha(trmv_falloff_alpha(half_pi + 0.2f, 0.1f, 0.1f), 0.1f) == Approx(0.60559).margin(1e-5));
  CHECK(trmv_weight_alpha(trmv_falloff_alpha(half_pi + 0.05f, 0.1f, 0.1f), 0.1f) == Approx(0.01118).margin(1e-5));
  CHECK(trmv_weight_alpha(0.1f, 0.1f) == 0.0f);                        // planar receiver
  CHECK(trmv_weight_alpha(1.0f, 0.1f) == Approx(0.81f).epsilon(1e-6));  // the largest, (1 - alpha)^2
}

TEST_CASE("Eq. 8 by hand: cbar = 1 clamped to 0.6 gives w_C = 0.4 / 1.001 = 0.39960, std min(w_A + w_C, 5)") {
  CHECK(trmv_weight_clamp(glm::vec3(0.6f), glm::vec3(1.0f), 0.001f) == Approx(0.39960).margin(1e-5));
  CHECK(trmv_weight_clamp(glm::vec3(0.5f), glm::vec3(0.5f), 0.001f) == 0.0f);  // nothing clamped
  CHECK(trmv_weight_clamp(glm::vec3(0.0f), glm::vec3(0.0f), 0.001f) == 0.0f);  // no history
  // On RGB: Y of the per-channel |difference|, so channels clamped in opposite directions do not cancel.
  // Y(0.1, 0, 0.1) = 0.1 (0.2126 + 0.0722) = 0.02848 over Y(1, 1, 1) + 0.001.
  CHECK(trmv_weight_clamp(glm::vec3(1.1f, 1.0f, 0.9f), glm::vec3(1.0f), 0.001f) == Approx(0.02848 / 1.001).epsilon(1e-4));
  CHECK(trmv_cleanup_sigma(0.12540f, 0.39960f, 5.0f) == Approx(0.525).epsilon(1e-6));
  CHECK(trmv_cleanup_sigma(0.81f, 30.0f, 5.0f) == 5.0f);  // capped
  // Through the per-pixel function: w_A from alpha^V = 0.45412, w_C from the histories.
  TrmvTemporalOutput t{RgbPlane(1, 1), RgbPlane(1, 1, glm::vec3(1.0f)), RgbPlane(1, 1, glm::vec3(0.6f)), FloatPlane(1, 1)};
  const TrmvCleanupWeights w = trmv_cleanup_weights_pixel(t, FloatPlane(1, 1, 0.45412f), TrmvParams{}, 0, 0);
  CHECK(w.w_a == Approx(0.12540).margin(1e-5));
  CHECK(w.w_c == Approx(0.39960).margin(1e-5));
  CHECK(w.sigma == Approx(0.12540 + 0.39960).margin(2e-5));
}

TEST_CASE("clean-up: the identity exactly where nothing was clamped and alpha^V = alpha (std 0)") {
  const RgbPlane c = noise_rgb(14, 11, 7);
  SurfacePlanes s = flat_surface(14, 11);
  const TrmvCleanupOutput out = trmv_cleanup_pass(unclamped(c), FloatPlane(14, 11, 0.1f), s, TrmvParams{}, SvgfParams{});
  const TrmvCleanupOutput no_falloff = trmv_cleanup_pass(unclamped(c), FloatPlane(), s, TrmvParams{}, SvgfParams{});
  for (size_t i = 0; i < c.data.size(); ++i) {
    CHECK(out.color.data[i] == c.data[i]);
    CHECK(no_falloff.color.data[i] == c.data[i]);
    CHECK(out.w_a.data[i] == 0.0f);
    CHECK(out.w_c.data[i] == 0.0f);
    CHECK(out.sigma.data[i] == 0.0f);
  }
}

TEST_CASE("clean-up: a constant image stays constant under the largest std (the weights normalise)") {
  const int w = 13, h = 10;
  TrmvTemporalOutput t{RgbPlane(w, h, glm::vec3(0.3f, 0.6f, 0.9f)), RgbPlane(w, h, glm::vec3(1.0f)),
                       RgbPlane(w, h, glm::vec3(0.0f)), FloatPlane(w, h, 0.1f)};  // w_C = 1 / 1.001
  const TrmvCleanupOutput out = trmv_cleanup_pass(t, FloatPlane(w, h, 1.0f), flat_surface(w, h), TrmvParams{},
                                                  SvgfParams{});
  for (size_t i = 0; i < out.color.data.size(); ++i) {
    CHECK(out.sigma.data[i] == Approx(0.81 + 1.0 / 1.001).epsilon(1e-5));
    CHECK(out.color.data[i].x == Approx(0.3f).epsilon(1e-6));
    CHECK(out.color.data[i].y == Approx(0.6f).epsilon(1e-6));
    CHECK(out.color.data[i].z == Approx(0.9f).epsilon(1e-6));
  }
}

TEST_CASE("clean-up: one clamped pixel is filtered 9x9 with its std, by hand, and every other pixel is unchanged") {
  const int w = 15, h = 15;
  const RgbPlane c = noise_rgb(w, h, 11);
  TrmvTemporalOutput t = unclamped(c);
  const int px = 7, py = 6;
  t.fetched.at(px, py) = glm::vec3(1.0f);
  t.clamped.at(px, py) = glm::vec3(0.6f);  // w_C = 0.39960: std 0.39960 px at (7, 6) only
  const TrmvCleanupOutput out = trmv_cleanup_pass(t, FloatPlane(), flat_surface(w, h), TrmvParams{}, SvgfParams{});
  // On the flat surface w_z = w_n = 1. The horizontal pass changes (7, 6) only; the vertical pass at (7, 6) reads
  // that and the unchanged pixels above and below, each with G(k; 0, std), k = -4 .. 4.
  const double sigma = 0.4 / 1.001;
  double sum_g = 0.0;
  glm::dvec3 row(0.0);
  for (int k = -4; k <= 4; ++k) {
    const double g = std::exp(-double(k * k) / (2.0 * sigma * sigma));
    sum_g += g;
    row += g * glm::dvec3(c.at(px + k, py));
  }
  row /= sum_g;
  glm::dvec3 col = row;  // k = 0, G = 1
  for (int k = -4; k <= 4; ++k)
    if (k != 0) col += std::exp(-double(k * k) / (2.0 * sigma * sigma)) * glm::dvec3(c.at(px, py + k));
  col /= sum_g;
  CHECK(out.sigma.at(px, py) == Approx(sigma).epsilon(1e-5));
  for (int i = 0; i < 3; ++i) CHECK(out.color.at(px, py)[i] == Approx(col[i]).epsilon(1e-5));
  CHECK(out.color.at(px, py) != c.at(px, py));
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x)
      if (x != px || y != py) CHECK(out.color.at(x, y) == c.at(x, y));
}
