// Tests of A-SVGF's parameter table (filters/asvgf/asvgf_params.h): its defaults are the paper's, set_param checks
// range and type, validate names the parameter.
#include "filters/asvgf/asvgf_params.h"

#include "core/error.h"

#include <catch2/catch.hpp>

TEST_CASE("asvgf parameters: the paper's defaults, checked ranges, whole numbers") {
  rtdr::AsvgfParams p;
  CHECK(p.gradient_levels == 5);   // five iterations [ASVGF18 Sec. 3.4]
  CHECK(p.alpha_max_radius == 1);  // 3x3 strata [ASVGF18 Sec. 3.5]
  CHECK(p.history_rule == 0);
  CHECK(rtdr::asvgf_param_table().size() == 7);
  CHECK(p.gradient_normalize == 0);  // after the reconstruction, Eq. 14 as printed
  CHECK(p.gradient_exponent == 1);
  CHECK(p.gradient_scale == 1.0f);
  CHECK(p.gradient_abs == 0);  // signed delta, Eq. 12
  CHECK(rtdr::set_param(p, "gradient_levels", 3.0));
  CHECK(p.gradient_levels == 3);
  CHECK_FALSE(rtdr::set_param(p, "alpha", 0.5));  // SVGF's row, not this table's
  CHECK_THROWS_AS(rtdr::set_param(p, "gradient_levels", 2.5), rtdr::Error);
  CHECK_THROWS_AS(rtdr::set_param(p, "alpha_max_radius", 5.0), rtdr::Error);
  p.history_rule = 2;
  CHECK_THROWS_WITH(rtdr::validate(p), Catch::Contains("history_rule"));
}
