// Tests of A-SVGF's adaptive temporal weight [ASVGF18 Sec. 3.5, Eq. 14-15]: lambda and alpha_i, and the maximum
// over exactly 3x3 strata. The pipeline's oracles on rendered scenes are in asvgf_asvgf_test.cpp.
#include "filters/asvgf/adaptive_alpha.h"

#include "asvgf_fixtures.h"

#include <catch2/catch.hpp>

#include <cmath>
#include <cstdlib>

using namespace rtdr;
using rtdr::test::flat_grid;

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

TEST_CASE("Sec. 3.5: the maximum over 3x3 strata gives alpha = 1 on exactly 9x9 pixels around a dropped stratum") {
  GradientValues v = flat_grid(10, 8).values;
  v.delta.at(4, 3) = 2.0f;  // lambda = 1 in stratum (4, 3), 0 elsewhere
  v.norm.at(4, 3) = 2.0f;
  const AdaptiveAlpha a = adaptive_alpha_pass(v, 3, 30, 24, {0.1f, 0.2f, 1});
  CHECK(a.lambda.at(4, 3) == 1.0f);
  int dropped = 0;
  for (int y = 0; y < 24; ++y)
    for (int x = 0; x < 30; ++x) {
      const bool near = std::abs(x / 3 - 4) <= 1 && std::abs(y / 3 - 3) <= 1;
      CHECK(a.alpha.at(x, y) == (near ? 1.0f : 0.1f));
      CHECK(a.alpha_moments.at(x, y) == (near ? 1.0f : 0.2f));  // the same lambda, the moments' base weight
      dropped += a.alpha.at(x, y) == 1.0f;
    }
  CHECK(dropped == 9 * 9);
  // Radius 0: the stratum alone, 3x3 pixels.
  const AdaptiveAlpha alone = adaptive_alpha_pass(v, 3, 30, 24, {0.1f, 0.2f, 0});
  int alone_dropped = 0;
  for (float alpha : alone.alpha.data) alone_dropped += alpha == 1.0f;
  CHECK(alone_dropped == 3 * 3);
}
