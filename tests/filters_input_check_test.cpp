// Tests of filters/input_check.cpp, the one list of what a method requires of an input frame (rtdr check prints
// it, rtdr filter refuses its first line): the strata rule by hand on small planes, partial strata included; each
// rule on a real frame; and, for asvgf, that a frame passes the list exactly when the method filters it.
#include "filters/input_check.h"

#include "core/error.h"
#include "scenes/gltf_loader.h"
#include "trace/gradients.h"

#include <catch2/catch.hpp>

#include <random>

using namespace rtdr;

TEST_CASE("input check: at most one gradient sample per stratum, partial strata at the edges included") {
  UIntPlane source(7, 5, kInvalidId);  // strata of 3: 3 x 2, the last column and row partial
  CHECK(gradient_strata_problems(source, 3).empty());
  for (int sy = 0; sy < 2; ++sy)
    for (int sx = 0; sx < 3; ++sx) source.at(3 * sx, 3 * sy) = uint32_t(sx + 10 * sy);  // one in each
  CHECK(gradient_strata_problems(source, 3).empty());
  source.at(6, 4) = 99;  // a second one in the partial stratum (2, 1)
  CHECK(gradient_strata_problems(source, 3) ==
        std::vector<std::string>{"stratum (2, 1) of 3x3 pixels holds two gradient samples, at (6, 3) and (6, 4); a "
                                 "stratum holds at most one (trace/gradients.h)"});
  source.at(1, 1) = 5;  // and a second one in (0, 0) and in (1, 1): three crowded strata, (0, 0) first
  source.at(5, 3) = 6;
  const std::vector<std::string> three = gradient_strata_problems(source, 3);
  REQUIRE(three.size() == 1);
  CHECK_THAT(three[0], Catch::StartsWith("stratum (0, 0) of 3x3 pixels holds two gradient samples, at (0, 0) and (1, 1)"));
  CHECK_THAT(three[0], Catch::EndsWith("; 2 more strata hold more than one"));
  CHECK(gradient_strata_problems(source, 8).size() == 1);  // one 7x5 stratum holding them all
}

TEST_CASE("input check: each rule on a rendered frame, one line each, without the file's name") {
  const Scene scene = load_scene("cornell");
  const Frame good = render_frame_with_gradients(scene, 0, 16, 9, {}, {}, nullptr);
  const InputChannels asvgf = make_method("asvgf")->inputs();
  CHECK(input_problems(good, asvgf).empty());
  Frame bad = good;
  bad.attributes["rtdr.gradient.stratum_size"] = "65";
  bad.float_channel("normal.Y").data[17] = -INFINITY;
  std::vector<uint32_t> ids = bad.uint_channel("id.mesh").data;
  Frame no_ids(16, 9);
  for (const auto& [name, plane] : bad.float_channels()) no_ids.add_float(name) = plane;
  for (const auto& [name, plane] : bad.uint_channels())
    if (name != "id.mesh" && name != "gradient.source") no_ids.add_uint(name) = plane;
  no_ids.attributes = bad.attributes;
  for (size_t k = 0; k < ids.size(); ++k) no_ids.add_float("id.mesh").data[k] = float(ids[k]);
  CHECK(input_problems(no_ids, asvgf) ==
        std::vector<std::string>{"channel 'normal.Y' holds NaN or infinity at 1 pixels, the first at (1, 1): -Inf",
                                 "channel 'id.mesh' is stored as float, but the method reads it as uint",
                                 "layer 'gradient' lacks gradient.source: render the frames with `rtdr render --gradients` "
                                 "(A-SVGF's gradient samples)",
                                 "rtdr.gradient.stratum_size '65' is not a stratum size (1 to 64)"});
  // svgf reads none of the gradient samples: their header is none of its business.
  CHECK(input_problems(bad, make_method("svgf")->inputs()).size() == 1);
}

TEST_CASE("input check: asvgf filters a frame exactly when its input check passes (random extra samples)") {
  const Scene scene = load_scene("cornell");
  const Frame first = render_frame_with_gradients(scene, 0, 16, 9, {}, {}, nullptr);
  const Frame second = render_frame_with_gradients(scene, 1, 16, 9, {}, {}, &first);
  std::mt19937 rng(7);
  int refused = 0;
  for (int trial = 0; trial < 24; ++trial) {
    Frame frame = second;
    UIntPlane& source = frame.uint_channel("gradient.source");
    for (int extra = trial % 3; extra > 0; --extra) source.data[rng() % source.data.size()] = rng() % 144;
    const bool passes = input_problems(frame, make_method("asvgf")->inputs()).empty();
    bool filtered = true;
    try {
      const std::unique_ptr<Method> asvgf = make_method("asvgf");
      asvgf->filter(first);
      asvgf->filter(frame);
    } catch (const Error&) {
      filtered = false;
    }
    INFO("trial " << trial);
    CHECK(passes == filtered);
    refused += !passes;
  }
  CHECK(refused > 0);  // some trials did crowd a stratum
}
