// Tests of the reconstruction of the sparse gradient on the stratum grid [ASVGF18 Sec. 3.4, Eq. 7-12]: constant
// values stay constant, a spike spreads over exactly the 3x3 taps 2^k strata apart, and hole filling, where the
// density of gradient samples cancels in lambda's quotient [ASVGF18 Eq. 14].
#include "filters/asvgf/gradient_atrous.h"

#include "filters/asvgf/adaptive_alpha.h"

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

