// The registry of methods (filters/method.h): every name makes a method, the SVGF pipelines and the classes of their
// own are told apart by the registry alone, and a parameter goes to the method's own table first.
#include "filters/method.h"
#include "filters/svgf/svgf.h"

#include "core/error.h"

#include <catch2/catch.hpp>

using namespace rtdr;

TEST_CASE("registry: every method is made under its own name, and exactly the SVGF pipelines have stages") {
  const std::vector<std::string> names = method_names();
  CHECK(names == std::vector<std::string>{"svgf", "asvgf", "a-eaw", "accum", "eaw", "eaw-accum", "none", "trmv"});
  for (const std::string& name : names) {
    INFO("method " << name);
    CHECK(make_method(name)->name() == name);
    if (is_svgf_pipeline(name))
      CHECK(method_options(name).name == name);
    else
      CHECK_THROWS_WITH(method_options(name), Catch::Contains("not one of SVGF's pipelines"));
  }
  CHECK_FALSE(is_svgf_pipeline("trmv"));
  CHECK_THROWS_WITH(is_svgf_pipeline("svfg"), Catch::Contains("is not one of: svgf, asvgf"));
  CHECK_THROWS_WITH(make_method("svfg"), Catch::Contains("is not one of: svgf, asvgf"));
}

TEST_CASE("registry: a key both tables have goes to the method's own table, any other to the table that has it") {
  // alpha is SVGF's (its EMA weight, [SVGF17 Sec. 4.1]) and TRMV's (Eq. 2's blend weight, [TRMV21 Sec. 5]): trmv's
  // own table first.
  MethodParams trmv = method_defaults("trmv");
  const float svgf_alpha = trmv.svgf.alpha;
  REQUIRE(set_method_param("trmv", trmv, "alpha", 0.3));
  CHECK(trmv.trmv.alpha == 0.3f);
  CHECK(trmv.svgf.alpha == svgf_alpha);
  MethodParams svgf = method_defaults("svgf");
  const float trmv_alpha = svgf.trmv.alpha;
  REQUIRE(set_method_param("svgf", svgf, "alpha", 0.3));
  CHECK(svgf.svgf.alpha == 0.3f);
  CHECK(svgf.trmv.alpha == trmv_alpha);
  // A key of one table alone reaches it from any method; an unknown key reaches none, and a value out of the range
  // of the key's table is refused with the range.
  REQUIRE(set_method_param("svgf", svgf, "falloff_sigma", 2.0));
  CHECK(svgf.trmv.falloff_sigma == 2.0f);
  REQUIRE(set_method_param("trmv", trmv, "gradient_levels", 3));
  CHECK(trmv.asvgf.gradient_levels == 3);
  CHECK_FALSE(set_method_param("svgf", svgf, "alpah", 0.3));
  CHECK_THROWS_WITH(set_method_param("svgf", svgf, "alpha", 7.0), Catch::Contains("alpha = 7 is not a number in [0, 1]"));
}

TEST_CASE("registry: rtdr filter prints the tables a method reads, and no other") {
  const auto has = [](const std::string& text, const std::string& name) {
    return text.find("\n" + name + " =") != std::string::npos || text.rfind(name + " =", 0) == 0;
  };
  const std::string none = describe_method_params("none", method_defaults("none"));
  CHECK(none.empty());
  const std::string svgf = describe_method_params("svgf", method_defaults("svgf"));
  CHECK(has(svgf, "atrous_levels"));
  CHECK_FALSE(has(svgf, "gradient_levels"));
  const std::string asvgf = describe_method_params("asvgf", method_defaults("asvgf"));
  CHECK(has(asvgf, "atrous_levels"));
  CHECK(has(asvgf, "gradient_levels"));
  const std::string trmv = describe_method_params("trmv", method_defaults("trmv"));
  CHECK(has(trmv, "falloff_sigma"));
  // TRMV's own a-trous (4 levels of a 3x3, filters/trmv/atrous.h), not SVGF's 5 levels: trmv prints no SVGF row.
  CHECK(trmv.find("\natrous_levels = 4 ") != std::string::npos);
  CHECK_FALSE(has(trmv, "history_level"));
  CHECK_FALSE(has(trmv, "variance_min_history"));
}
