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
  CHECK(p.footprint_height == 1080);  // the paper's 1920x1080 [TRMV21 Sec. 6]
  CHECK(p.shadow_filter == 0);        // the fixed 31x31, chosen by measurement (filters/trmv/README.md)
  CHECK(p.splat_size == 0);           // the shadow filter's window [TRMV21 Sec. 4.1]
  CHECK(p.diffuse_filter == 1);       // the 4-level a-trous [TRMV21 Sec. 5]
  CHECK(p.atrous_levels == 4);        // "essentially 32x32"
  CHECK(p.glossy_filter == 1);        // the lobe's footprint [LLK*19]
  CHECK(p.glossy_radius == 15);
  CHECK(p.history_test == 1);
  CHECK(p.shadow_receiver_test == 0);
  CHECK(p.falloff_carry == 1);
  CHECK(p.glossy_draw == 1);          // Eq. 5's stochastic vector
  CHECK(p.cone_transfer == 1);        // the share of each cone [TRMV21 Fig. 7]
  CHECK(rtdr::trmv_param_table().size() == 25);
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
  rtdr::TrmvParams even_splat;
  even_splat.splat_size = 10;
  CHECK_THROWS_WITH(rtdr::validate(even_splat), Catch::Contains("splat_size"));
  rtdr::TrmvParams other_motion;
  other_motion.motion = 5;  // 0 traditional, 1 shadow, 2 dual, 3 glossy, 4 all
  CHECK_THROWS_WITH(rtdr::validate(other_motion), Catch::Contains("motion"));
  rtdr::TrmvParams out_of_range;
  out_of_range.spatial_radius = 65;
  CHECK_THROWS_WITH(rtdr::validate(out_of_range), Catch::Contains("spatial_radius"));
}
