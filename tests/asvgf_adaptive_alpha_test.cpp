// Tests of A-SVGF's filter side on synthetic stratum grids [ASVGF18 Sec. 3.4, 3.5, Eq. 7-15]: lambda and alpha_i
// (Eq. 14-15), the reconstruction's hole filling, where the density of gradient samples cancels in lambda's
// quotient, and the maximum over exactly 3x3 strata. The pipeline's oracles on rendered scenes are in
// asvgf_asvgf_test.cpp.
#include "filters/asvgf/adaptive_alpha.h"
#include "filters/asvgf/gradient_atrous.h"

#include "core/frame.h"

#include <catch2/catch.hpp>

#include <cmath>
#include <cstdlib>

using namespace rtdr;

namespace {

// A w x h stratum grid on a plane facing the camera: every stratum covered, depth 1, constant luminance, no
// variance, and no gradient sample anywhere (delta = Delta = 0).
GradientImage flat_grid(int w, int h, int s = 3) {
  GradientImage g;
  g.stratum_size = s;
  g.values = {FloatPlane(w, h), FloatPlane(w, h), FloatPlane(w, h, 1.0f), FloatPlane(w, h)};
  g.surface.depth = FloatPlane(w, h, 1.0f);
  g.surface.depth_grad = Vec2Plane(w, h);
  g.surface.normal = RgbPlane(w, h, glm::vec3(0.0f, 0.0f, 1.0f));
  g.surface.mesh = UIntPlane(w, h, 0u);
  return g;
}

// Five reconstruction iterations, as A-SVGF runs them [ASVGF18 Sec. 3.4].
GradientValues reconstruct(const GradientImage& g, int iterations = 5) {
  GradientValues v = g.values;
  for (int k = 0; k < iterations; ++k) v = gradient_atrous_level(v, g, k, SvgfParams{});
  return v;
}

}  // namespace

TEST_CASE("Eq. 14-15: lambda = min(1, abs(delta) / Delta), alpha_i = (1 - lambda) alpha + lambda") {
  CHECK(gradient_lambda(1.0f, 2.0f) == 0.5f);
  CHECK(gradient_lambda(-1.0f, 2.0f) == 0.5f);  // the sign of the change does not matter
  CHECK(gradient_lambda(3.0f, 2.0f) == 1.0f);   // clamped
  CHECK(gradient_lambda(0.0f, 0.0f) == 0.0f);   // no sample within reach: the history is kept
  CHECK(adaptive_alpha(0.1f, 0.0f) == 0.1f);
  CHECK(adaptive_alpha(0.1f, 1.0f) == 1.0f);
  CHECK(adaptive_alpha(0.1f, 0.5f) == Approx(0.55f).epsilon(1e-6));
  float previous = 0.0f;
  for (float lambda = 0.0f; lambda <= 1.0f; lambda += 0.125f) {  // in [alpha, 1] and increasing in lambda
    const float a = adaptive_alpha(0.1f, lambda);
    CHECK(a >= 0.1f);
    CHECK(a <= 1.0f);
    CHECK(a >= previous);
    previous = a;
  }
}

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

TEST_CASE("Sec. 3.5: the maximum over 3x3 strata gives alpha = 1 on exactly 9x9 pixels around a dropped stratum") {
  GradientValues v = flat_grid(10, 8).values;
  v.delta.at(4, 3) = 2.0f;  // lambda = 1 in stratum (4, 3), 0 elsewhere
  v.norm.at(4, 3) = 2.0f;
  const AdaptiveAlpha a = adaptive_alpha_pass(v, 3, 30, 24, 0.1f, 1);
  CHECK(a.lambda.at(4, 3) == 1.0f);
  int dropped = 0;
  for (int y = 0; y < 24; ++y)
    for (int x = 0; x < 30; ++x) {
      const bool near = std::abs(x / 3 - 4) <= 1 && std::abs(y / 3 - 3) <= 1;
      CHECK(a.alpha.at(x, y) == (near ? 1.0f : 0.1f));
      dropped += a.alpha.at(x, y) == 1.0f;
    }
  CHECK(dropped == 9 * 9);
  // Radius 0: the stratum alone, 3x3 pixels.
  const AdaptiveAlpha alone = adaptive_alpha_pass(v, 3, 30, 24, 0.1f, 0);
  int alone_dropped = 0;
  for (float alpha : alone.alpha.data) alone_dropped += alpha == 1.0f;
  CHECK(alone_dropped == 3 * 3);
}
