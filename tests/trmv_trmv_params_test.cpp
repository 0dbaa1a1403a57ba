// Tests of TRMV's parameter table (filters/trmv/trmv_params.h): its defaults are the paper's, set_param checks
// range and type, validate names the parameter and rejects windows without a centre.
#include "filters/trmv/trmv_params.h"

#include "core/error.h"

#include <catch2/catch.hpp>

TEST_CASE("trmv parameters: the paper's defaults, checked ranges, whole numbers, an odd clean-up window") {
  rtdr::TrmvParams p;
  CHECK(p.alpha == 0.1f);             // [TRMV21 Sec. 5]
  CHECK(p.falloff_sigma == 0.1f);     // [TRMV21 Eq. 4], radians
  CHECK(p.clamp_gamma == 3.0f);       // mu +- 3 sigma [TRMV21 Sec. 5]
  CHECK(p.clamp_radius == 1);         // 3x3
  CHECK(p.spatial_radius == 15);      // 31x31 [TRMV21 Sec. 5]
  CHECK(p.spatial_sigma == 5.0f);     // radius / 3
  CHECK(p.cleanup_size == 9);         // 9x9 [TRMV21 Sec. 5]
  CHECK(p.cleanup_sigma_max == 5.0f); // min(w_A + w_C, 5) [TRMV21 Sec. 5]
  CHECK(p.cleanup_eps == 0.001f);     // [TRMV21 Eq. 8]
  CHECK(p.motion == 4);               // each component its own vector [TRMV21 Sec. 4]
  CHECK(p.cones == 1);                // the disoccluded history re-shaded from cones [TRMV21 Sec. 4.3]
  CHECK(p.cone_half_angle == 0.71f);  // covers the hemisphere (filters/trmv/cones.h)
  CHECK(p.history_after_cleanup == 0);
  CHECK(rtdr::trmv_param_table().size() == 13);
  CHECK(rtdr::trmv_motion_from_name("traditional") == 0);
  CHECK(rtdr::trmv_motion_from_name("all") == 4);
  CHECK(rtdr::trmv_motion_from_name("shadows") == -1);
  CHECK(rtdr::param_values(p).size() == rtdr::trmv_param_table().size());
  CHECK_NOTHROW(rtdr::validate(p));

  CHECK(rtdr::set_param(p, "clamp_gamma", 1.0));  // Salvi's mu +- sigma
  CHECK(p.clamp_gamma == 1.0f);
  CHECK(rtdr::set_param(p, "clamp_gamma", 0.0));  // no clamp
  CHECK_FALSE(rtdr::set_param(p, "sigma_l", 4.0));  // SVGF's row, not this table's
  CHECK_THROWS_AS(rtdr::set_param(p, "cleanup_size", 8.5), rtdr::Error);
  CHECK_THROWS_AS(rtdr::set_param(p, "alpha", 1.5), rtdr::Error);
  CHECK_THROWS_AS(rtdr::set_param(p, "falloff_sigma", 0.0), rtdr::Error);  // G would divide by 0

  rtdr::TrmvParams even;
  even.cleanup_size = 8;
  CHECK_THROWS_WITH(rtdr::validate(even), Catch::Contains("cleanup_size"));
  rtdr::TrmvParams other_motion;
  other_motion.motion = 5;  // 0 traditional, 1 shadow, 2 dual, 3 glossy, 4 all
  CHECK_THROWS_WITH(rtdr::validate(other_motion), Catch::Contains("motion"));
  rtdr::TrmvParams out_of_range;
  out_of_range.spatial_radius = 65;
  CHECK_THROWS_WITH(rtdr::validate(out_of_range), Catch::Contains("spatial_radius"));
}
