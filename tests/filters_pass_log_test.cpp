// The pass log (filters/pass_log.h) by itself, on planes made by hand: what its dump writes under each declared
// layer, and which run its probe picks or why it refuses. The methods' tests check it on real frames.
#include "filters/pass_log.h"

#include <catch2/catch.hpp>

using namespace rtdr;

namespace {

// A plane whose value at (x, y) is base + 10 x + y, so every pixel says where it came from.
FloatPlane ramp(int width, int height, float base) {
  FloatPlane p(width, height);
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x) p.at(x, y) = base + 10.0f * float(x) + float(y);
  return p;
}

// A pixel function that records which run it is and the pixel it was asked for.
PassRun::Pixel recorder(float run) {
  return [run](int x, int y, Probe* probe) {
    note(probe, "run", run);
    note(probe, "pixel", glm::vec3(float(x), float(y), 0.0f));
  };
}

}  // namespace

TEST_CASE("pass log: the dump holds each logged plane under its declared layer, stream and level") {
  const FloatPlane direct = ramp(4, 3, 0.0f), indirect = ramp(4, 3, 100.0f);
  const RgbPlane level1(4, 3, glm::vec3(1.0f, 2.0f, 3.0f));
  PassLog log;
  log.begin(4, 3);
  log.add(find_pass("variance"), "direct").writes(layers::kVariance, direct);
  log.add(find_pass("variance"), "indirect").writes(layers::kVariance, indirect);
  log.add(find_pass("atrous"), "direct", 1).writes(layers::kLevel, level1);
  log.add(find_pass("tonemap")).writes(layers::kTonemapped, RgbPlane(4, 3, glm::vec3(0.5f)));  // moved in, kept
  Frame dump(1, 1);  // of another size: made the frame's
  log.dump(dump);
  REQUIRE(dump.width() == 4);
  CHECK(dump.float_channel("filter.direct.variance").data == direct.data);
  CHECK(dump.float_channel("filter.indirect.variance").data == indirect.data);
  CHECK(dump.float_channel("filter.direct.level1.G").data == std::vector<float>(12, 2.0f));
  CHECK(dump.float_channel("filter.tonemapped.B").data == std::vector<float>(12, 0.5f));
  CHECK(dump.float_channels().size() == 2 + 3 + 3);
  CHECK(log.passes() == std::vector<std::string>{"variance", "atrous", "tonemap"});
}

TEST_CASE("pass log: a plane of strata is dumped with each value repeated over its stratum, partial ones included") {
  // 5 x 4 pixels in strata of 3: a 2 x 2 grid, the right column and bottom row of strata partial.
  const FloatPlane strata = ramp(2, 2, 0.0f);
  PassLog log;
  log.begin(5, 4);
  log.add(find_pass("adaptive_alpha"), "direct").writes(layers::kLambda, strata, 3);
  Frame dump(5, 4);
  log.dump(dump);
  const std::vector<float>& lambda = dump.float_channel("filter.direct.lambda").data;
  for (int y = 0; y < 4; ++y)
    for (int x = 0; x < 5; ++x) {
      INFO("pixel " << x << ", " << y);
      CHECK(lambda[size_t(y * 5 + x)] == strata.at(x / 3, y / 3));
    }
}

TEST_CASE("pass log: the probe runs the pixel function of the run asked for, on the pixel asked for") {
  PassLog log;
  log.begin(4, 3);
  log.add(find_pass("variance"), "direct").pixel(recorder(1.0f));
  log.add(find_pass("variance"), "indirect").pixel(recorder(2.0f));
  for (int level = 0; level < 3; ++level) log.add(find_pass("atrous"), "indirect", level).pixel(recorder(10.0f + level));
  log.add(find_pass("tonemap")).pixel(recorder(3.0f));
  CHECK(log.probe("variance", "indirect", -1, 3, 2).find("run").value == std::vector<float>{2.0f});
  CHECK(log.probe("variance", "indirect", -1, 3, 2).find("pixel").value == std::vector<float>{3.0f, 2.0f, 0.0f});
  CHECK(log.probe("atrous", "indirect", 2, 0, 0).find("run").value == std::vector<float>{12.0f});
  // A pass over the whole frame answers for any stream.
  CHECK(log.probe("tonemap", "direct", 0, 1, 1).find("run").value == std::vector<float>{3.0f});
}

TEST_CASE("pass log: the probe refuses, naming what did run, a pixel, pass, stream or level the frame has not") {
  PassLog log;
  CHECK_THROWS_WITH(log.probe("variance", "direct", -1, 0, 0), "probe: no frame has been filtered yet");
  log.begin(4, 3);
  log.add(find_pass("variance"), "direct").pixel(recorder(1.0f));
  for (int level = 0; level < 2; ++level) log.add(find_pass("atrous"), "direct", level).pixel(recorder(float(level)));
  log.add(find_pass("modulate"));  // logged without a pixel function: not probed
  CHECK_THROWS_WITH(log.probe("variance", "direct", -1, 4, 0), "--pixel 4,0 is outside the 4x3 frame");
  CHECK_THROWS_WITH(log.probe("variance", "direct", -1, 0, -1), "--pixel 0,-1 is outside the 4x3 frame");
  CHECK_THROWS_WITH(log.probe("taa", "direct", -1, 0, 0),
                    "--pass 'taa' did not run on this frame (passes that ran: variance, atrous, modulate)");
  CHECK_THROWS_WITH(log.probe("modulate", "direct", -1, 0, 0), Catch::Contains("--pass 'modulate' did not run"));
  CHECK_THROWS_WITH(log.probe("variance", "indirect", -1, 0, 0), "--stream 'indirect': pass variance ran on direct");
  CHECK_THROWS_WITH(log.probe("atrous", "direct", 2, 0, 0), "--level 2 is not one of the 2 levels run");
  // A new frame forgets the last one's runs.
  log.begin(4, 3);
  CHECK_THROWS_WITH(log.probe("variance", "direct", -1, 0, 0), Catch::Contains("did not run on this frame"));
}
