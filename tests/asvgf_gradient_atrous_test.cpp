// Tests of the reconstruction of the sparse gradient on the stratum grid [ASVGF18 Sec. 3.4, Eq. 7-12]: constant
// values stay constant, a spike spreads over exactly the 3x3 taps 2^k strata apart, and hole filling, where the
// density of gradient samples cancels in lambda's quotient [ASVGF18 Eq. 14].
#include "filters/asvgf/gradient_atrous.h"

#include "filters/asvgf/adaptive_alpha.h"
#include "filters/asvgf/asvgf.h"

#include "asvgf_fixtures.h"

#include <catch2/catch.hpp>

#include <cmath>
#include <cstdlib>

using namespace rtdr;
using rtdr::test::flat_grid;
using rtdr::test::reconstruct;

TEST_CASE("hole filling: one gradient sample on a plane gives lambda = abs(d) / D over the 63x63 footprint, 0 beyond") {
  // 81 x 81 strata, the sample at (40, 40): five iterations reach 1 + 2 + 4 + 8 + 16 = 31 strata each way.
  GradientImage g = flat_grid(81, 81);
  const float d = -0.3f, D = 1.2f;
  g.values.delta.at(40, 40) = d;
  g.values.norm.at(40, 40) = D;
  const GradientValues v = reconstruct(g);
  int reached = 0;
  for (int y = 0; y < 81; ++y)
    for (int x = 0; x < 81; ++x) {
      const bool inside_footprint = std::abs(x - 40) <= 31 && std::abs(y - 40) <= 31;
      const float lambda = gradient_lambda(v.delta.at(x, y), v.norm.at(x, y));
      INFO("stratum " << x << ", " << y);
      if (inside_footprint) {
        // The sample's weight cancels in the quotient [ASVGF18 Eq. 14]: the same ratio everywhere it reaches.
        CHECK(lambda == Approx(std::abs(d) / D).epsilon(1e-5));
        reached += 1;
      } else {
        CHECK(v.norm.at(x, y) == 0.0f);  // Delta^ = 0 beyond the footprint: lambda = 0, the stated rule
        CHECK(lambda == 0.0f);
      }
    }
  CHECK(reached == 63 * 63);

  // Strata without a surface are skipped; the density of empty strata cancels too: lambda is unchanged.
  GradientImage holes = g;
  for (int y = 0; y < 81; y += 2)
    for (int x = 2; x < 81; x += 3) holes.surface.mesh.at(x, y) = kInvalidId;  // not (40, 40)
  const GradientValues h = reconstruct(holes);
  int compared = 0;
  for (int y = 0; y < 81; ++y)
    for (int x = 0; x < 81; ++x)
      if (holes.surface.covered(x, y) && h.norm.at(x, y) > 0.0f) {
        CHECK(gradient_lambda(h.delta.at(x, y), h.norm.at(x, y)) == Approx(std::abs(d) / D).epsilon(1e-5));
        ++compared;
      }
  INFO(compared << " strata compared");
  CHECK(compared > 2000);
}

TEST_CASE("reconstruction: constant values on a plane stay constant, and a spike spreads over 3x3 taps 2^k apart") {
  GradientImage g = flat_grid(40, 30);
  for (float& v : g.values.delta.data) v = 0.25f;
  for (float& v : g.values.norm.data) v = 0.75f;
  for (float& v : g.values.variance.data) v = 0.5f;
  const GradientValues once = gradient_atrous_level(g.values, g, 2, SvgfParams{});
  for (size_t i = 0; i < once.delta.data.size(); ++i) {
    CHECK(once.delta.data[i] == Approx(0.25f).epsilon(1e-6));
    CHECK(once.norm.data[i] == Approx(0.75f).epsilon(1e-6));
    CHECK(once.luminance.data[i] == Approx(1.0f).epsilon(1e-6));
  }
  // One spike of delta at (20, 15); iteration k = 2 puts taps 4 strata apart: exactly the 3x3 strata
  // (20 + 4i, 15 + 4j) receive it, each with the box weight 1/9 of an interior stratum.
  GradientImage spike = flat_grid(40, 30);
  spike.values.delta.at(20, 15) = 9.0f;
  const GradientValues spread = gradient_atrous_level(spike.values, spike, 2, SvgfParams{});
  int nonzero = 0;
  for (int y = 0; y < 30; ++y)
    for (int x = 0; x < 40; ++x)
      if (spread.delta.at(x, y) != 0.0f) {
        ++nonzero;
        CHECK((std::abs(x - 20) % 4 == 0 && std::abs(x - 20) <= 4 && std::abs(y - 15) % 4 == 0 && std::abs(y - 15) <= 4));
        CHECK(spread.delta.at(x, y) == Approx(1.0f).epsilon(1e-6));
      }
  CHECK(nonzero == 9);
}


namespace {

// One reconstruction iteration (k = 0) and lambda per stratum for a 9x9-stratum plane whose strata hold the
// gradient samples `samples` ((stratum, f_now, f_before) each; the others none), made into values by the asvgf
// parameters' GradientForm, and lambda formed as the adaptive_alpha pass forms it (asvgf.h).
struct Sample {
  glm::ivec2 stratum;
  float f_now, f_before;
};
FloatPlane variant_lambda(const std::vector<Sample>& samples, const AsvgfParams& asvgf) {
  GradientImage g = flat_grid(9, 9);
  for (const Sample& s : samples) {
    const glm::vec2 v = gradient_sample_values(s.f_now, s.f_before, gradient_form(asvgf));
    g.values.delta.at(s.stratum.x, s.stratum.y) = v.x;
    g.values.norm.at(s.stratum.x, s.stratum.y) = v.y;
  }
  const GradientValues once = reconstruct(g, 1);
  return adaptive_alpha_pass(once, 3, 27, 27, adaptive_alpha_params(SvgfParams{}, asvgf)).lambda;
}

AsvgfParams variant(int normalize, int exponent = 1, float scale = 1.0f, int absolute = 0) {
  AsvgfParams p;
  p.gradient_normalize = normalize;
  p.gradient_exponent = exponent;
  p.gradient_scale = scale;
  p.gradient_abs = absolute;
  return p;
}

}  // namespace

TEST_CASE("variants: one bright changed sample among dim unchanged ones, normalised after (Eq. 14) or before") {
  // Stratum (4, 4) is a bright sample that halved, 2 -> 1: delta = -1, Delta = 2, its own ratio r = 1/2. Its eight
  // neighbours are dim and unchanged, 0.1 -> 0.1: delta = 0, Delta = 0.1, r = 0. One iteration on a plane of
  // constant luminance weights each of the 3x3 taps with h w = 1/9 (w_z = w_n = w_l = 1), so at (4, 4):
  const glm::ivec2 c(4, 4);
  std::vector<Sample> samples{{c, 1.0f, 2.0f}};
  for (int dy = -1; dy <= 1; ++dy)
    for (int dx = -1; dx <= 1; ++dx)
      if (dx != 0 || dy != 0) samples.push_back({c + glm::ivec2(dx, dy), 0.1f, 0.1f});
  // after (the paper): delta^ = -1/9, Delta^ = (2 + 8 0.1) / 9, lambda = 1 / 2.8: delta_b / (Delta_b + sum of the
  // dim Delta). The dim samples dilute the change by their brightness.
  CHECK(variant_lambda(samples, variant(0)).at(c.x, c.y) == Approx(1.0 / 2.8).epsilon(1e-6));
  // ... with Q2RTX's square after: (1 / 2.8)^2; with RTGL1's k = 0.1: 0.1 / 2.8.
  CHECK(variant_lambda(samples, variant(0, 2)).at(c.x, c.y) == Approx(1.0 / (2.8 * 2.8)).epsilon(1e-6));
  CHECK(variant_lambda(samples, variant(0, 1, 0.1f)).at(c.x, c.y) == Approx(0.1 / 2.8).epsilon(1e-6));
  // before: delta^ = r_b / 9 = 0.5 / 9 and the present weights' Delta^ = 9 / 9, so lambda = (1/9) 0.5: the bright
  // sample's share of the filter weight (1 of 9 samples in reach) times its own ratio.
  CHECK(variant_lambda(samples, variant(1)).at(c.x, c.y) == Approx(0.5 / 9.0).epsilon(1e-6));
  // ... squared per sample (Q2RTX): (1/9) 0.25; scaled per sample (RTGL1): (1/9) 0.1 0.5. p and k are not applied
  // a second time after the reconstruction.
  CHECK(variant_lambda(samples, variant(1, 2)).at(c.x, c.y) == Approx(0.25 / 9.0).epsilon(1e-6));
  CHECK(variant_lambda(samples, variant(1, 1, 0.1f)).at(c.x, c.y) == Approx(0.05 / 9.0).epsilon(1e-6));

  // Without the dim samples (empty strata, 0 and 0) the density cancels in both quotients [ASVGF18 Sec. 3.5]: the
  // bright sample is all there is in reach, and lambda is its own ratio, 1/2, either way. (Q2RTX filters no
  // sample-present weight: its lambda would stay at 0.5 / 9, diluted by the empty strata.)
  const std::vector<Sample> alone{samples.front()};
  CHECK(variant_lambda(alone, variant(0)).at(c.x, c.y) == Approx(0.5).epsilon(1e-6));
  CHECK(variant_lambda(alone, variant(1)).at(c.x, c.y) == Approx(0.5).epsilon(1e-6));
  // Three of the nine strata with samples (the bright one and two dim): before gives 0.5 / 3.
  const std::vector<Sample> three{samples[0], samples[1], samples[2]};
  CHECK(variant_lambda(three, variant(1)).at(c.x, c.y) == Approx(0.5 / 3.0).epsilon(1e-6));
  // Beyond every sample's reach lambda is 0 in all forms (stratum (0, 8) is 4 strata from (4, 4)).
  for (const AsvgfParams& p : {variant(0), variant(1), variant(0, 2), variant(0, 1, 1.0f, 1)})
    CHECK(variant_lambda(samples, p).at(0, 8) == 0.0f);
}

TEST_CASE("variants: opposite changes cancel in the signed reconstruction, not in the unsigned one") {
  // A shadow edge moving right: stratum (4, 4) darkens 2 -> 1 (delta = -1, Delta = 2), (5, 4) brightens 1 -> 2
  // (delta = +1, Delta = 2); the seven other strata of (4, 4)'s 3x3 are dim and unchanged (Delta = 0.1).
  const glm::ivec2 c(4, 4);
  std::vector<Sample> samples{{c, 1.0f, 2.0f}, {c + glm::ivec2(1, 0), 2.0f, 1.0f}};
  for (int dy = -1; dy <= 1; ++dy)
    for (int dx = -1; dx <= 0; ++dx)
      if (dx != 0 || dy != 0) samples.push_back({c + glm::ivec2(dx, dy), 0.1f, 0.1f});
  for (int dy : {-1, 1}) samples.push_back({c + glm::ivec2(1, dy), 0.1f, 0.1f});
  REQUIRE(samples.size() == 9);
  // Signed (Eq. 12): delta^ = (-1 + 1) / 9 = 0, lambda = 0 although half the light moved.
  CHECK(variant_lambda(samples, variant(0)).at(c.x, c.y) == 0.0f);
  // abs(delta): delta^ = (1 + 1) / 9, Delta^ = (2 + 2 + 7 0.1) / 9, lambda = 2 / 4.7.
  CHECK(variant_lambda(samples, variant(0, 1, 1.0f, 1)).at(c.x, c.y) == Approx(2.0 / 4.7).epsilon(1e-6));
  // Per sample (before) the ratios are unsigned as well: (0.5 + 0.5) / 9.
  CHECK(variant_lambda(samples, variant(1)).at(c.x, c.y) == Approx(1.0 / 9.0).epsilon(1e-6));
}
