// Tests of filters/trmv/footprint.cpp: the paper's 1080p windows [TRMV21 Sec. 5, 6] at the heights this project
// renders, by hand from footprint.h's rules.
#include "filters/trmv/footprint.h"

#include <catch2/catch.hpp>

using namespace rtdr;

TEST_CASE("a window of side S at 1080 rows has side S H / 1080 at H rows, the nearest odd one, at least 3x3") {
  // 31x31 [TRMV21 Sec. 5]: 1080 -> 31; 720 -> 20.7 -> 21; 360 -> 10.3 -> 11; 180 -> 5.17 -> 5; 90 -> 2.58 -> 3.
  CHECK(trmv_scaled_radius(15, 1080, 1080) == 15);
  CHECK(trmv_scaled_radius(15, 720, 1080) == 10);
  CHECK(trmv_scaled_radius(15, 360, 1080) == 5);
  CHECK(trmv_scaled_radius(15, 180, 1080) == 2);
  CHECK(trmv_scaled_radius(15, 90, 1080) == 1);
  // 9x9, the clean-up: 1080 -> 9; 720 -> 6 -> 7; 360 -> 3; 180 -> 1.5 -> the 3x3 floor.
  CHECK(trmv_scaled_side(9, 1080, 1080) == 9);
  CHECK(trmv_scaled_side(9, 720, 1080) == 7);
  CHECK(trmv_scaled_side(9, 360, 1080) == 3);
  CHECK(trmv_scaled_side(9, 180, 1080) == 3);
  // The identity stays the identity, and footprint_height = H leaves every window as it is.
  CHECK(trmv_scaled_radius(0, 360, 1080) == 0);
  CHECK(trmv_scaled_radius(15, 360, 360) == 15);
  // The std keeps +-3 std on the window: 5 at r = 15, 5 x 5 / 15 at r = 5.
  CHECK(trmv_scaled_sigma(5.0f, 15, 1080, 1080) == 5.0f);
  CHECK(trmv_scaled_sigma(5.0f, 15, 360, 1080) == Approx(5.0f / 3.0f));
}

TEST_CASE("four 3x3 a-trous levels reach 31 pixels at 1080 rows, and elsewhere the level count nearest in the log") {
  // Side 2^(L+1) - 1 scaled: 720 -> 20.7, log2(21.7) - 1 = 3.44 -> 3; 360 -> 10.3, 2.50 -> 3; 180 -> 5.17, 1.62 -> 2;
  // 90 -> 2.58, 0.84 -> 1.
  CHECK(trmv_scaled_levels(4, 1080, 1080) == 4);
  CHECK(trmv_scaled_levels(4, 720, 1080) == 3);
  CHECK(trmv_scaled_levels(4, 360, 1080) == 3);
  CHECK(trmv_scaled_levels(4, 180, 1080) == 2);
  CHECK(trmv_scaled_levels(4, 90, 1080) == 1);
  CHECK(trmv_scaled_levels(5, 1080, 1080) == 5);
}

TEST_CASE("the method's windows at 640x360: shadow 11x11 (std 5/3), splat 11x11, a-trous 3 levels, clean-up 3x3") {
  const TrmvWindows w = trmv_windows(TrmvParams{}, 360);
  CHECK(w.shadow_radius == 5);
  CHECK(w.shadow_sigma == Approx(5.0f / 3.0f));
  CHECK(w.splat_size == 11);  // the shadow filter's window [TRMV21 Sec. 4.1]
  CHECK(w.atrous_levels == 3);
  CHECK(w.glossy_radius == 5);
  CHECK(w.cleanup_radius == 1);
  // The former fixed 9x9 splat at 360 rows is splat_size 27 at 1080.
  TrmvParams nine;
  nine.splat_size = 27;
  CHECK(trmv_windows(nine, 360).splat_size == 9);
  // At 1080 rows, the paper's sizes.
  const TrmvWindows paper = trmv_windows(TrmvParams{}, 1080);
  CHECK(paper.shadow_radius == 15);
  CHECK(paper.splat_size == 31);
  CHECK(paper.atrous_levels == 4);
  CHECK(paper.cleanup_radius == 4);
}
