// Tests of filters/svgf/svgf_params.cpp: the table's defaults, ranges and the text form of a configuration.
#include "filters/svgf/svgf_params.h"

#include "core/error.h"

#include <catch2/catch.hpp>

#include <cmath>

#include <sstream>
#include <string>

namespace {

// Reads "name=value:name=value" back with set_param, onto the defaults.
rtdr::SvgfParams read_changed(const std::string& text) {
  rtdr::SvgfParams params;
  std::stringstream parts(text);
  for (std::string part; std::getline(parts, part, ':');) {
    const size_t eq = part.find('=');
    REQUIRE(eq != std::string::npos);
    REQUIRE(rtdr::set_param(params, part.substr(0, eq), std::stod(part.substr(eq + 1))));
  }
  return params;
}

}  // namespace

TEST_CASE("changed_params names exactly the parameters off their defaults, in digits that read back exactly") {
  CHECK(rtdr::changed_params(rtdr::SvgfParams{}).empty());

  rtdr::SvgfParams p;
  p.alpha = 0.1f;
  p.atrous_levels = 4;
  p.kernel_size = 3;
  p.epsilon = 1e-5f;
  p.temporal_normal_cosine = -0.5f;
  p.sigma_l = 1.0f / 3.0f;  // needs 9 significant digits
  const std::string text = rtdr::changed_params(p);
  CHECK(text == "alpha=0.1:temporal_normal_cosine=-0.5:sigma_l=0.33333334:epsilon=1e-05:atrous_levels=4:kernel_size=3");
  CHECK(rtdr::param_values(read_changed(text)) == rtdr::param_values(p));
}

TEST_CASE("validate names the first parameter out of its range, and kernel sizes other than 3 and 5") {
  CHECK_NOTHROW(rtdr::validate(rtdr::SvgfParams{}));
  rtdr::SvgfParams p;
  p.alpha = 1.5f;
  CHECK_THROWS_WITH(rtdr::validate(p), Catch::Contains("alpha"));
  p = {};
  p.kernel_size = 4;
  CHECK_THROWS_WITH(rtdr::validate(p), Catch::Contains("kernel_size"));
  p = {};
  p.atrous_levels = 11;
  CHECK_THROWS_WITH(rtdr::validate(p), Catch::Contains("atrous_levels"));
}

TEST_CASE("set_param checks a value as a double before casting it: range, whole numbers for ints, NaN") {
  rtdr::SvgfParams params;
  CHECK(rtdr::set_param(params, "atrous_levels", 4.0));
  CHECK(params.atrous_levels == 4);
  CHECK(rtdr::set_param(params, "alpha", 0.05));
  CHECK(params.alpha == 0.05f);
  // 1e30 and NaN cast to int are undefined behaviour; 2.9 would silently become 2.
  for (const double bad : {2.9, 1e30, -1.0, 11.0, std::nan("")})
    CHECK_THROWS_WITH(rtdr::set_param(params, "atrous_levels", bad), Catch::Contains("atrous_levels"));
  for (const double bad : {1.5, -0.1, std::nan(""), double(INFINITY)})
    CHECK_THROWS_AS(rtdr::set_param(params, "alpha", bad), rtdr::Error);
  CHECK(params.atrous_levels == 4);  // a refused value changes nothing
  CHECK(params.alpha == 0.05f);
  CHECK_FALSE(rtdr::set_param(params, "no_such_parameter", 1.0));
}
