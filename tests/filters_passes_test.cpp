// Tests of filters/passes.cpp: the layer patterns expand to the names the dumps write and match them back, the
// pass that writes a channel is found for error messages, dump_layer refuses a plane of the wrong kind, and every
// declared pass names an existing golden file, what it writes and what its probe prints. (That docs/buffers.md
// documents exactly these layers is tests/docs_buffers_test.cpp.)
#include "filters/passes.h"

#include <catch2/catch.hpp>

#include <filesystem>
#include <string>
#include <vector>

namespace fs = std::filesystem;
using namespace rtdr;

TEST_CASE("layer patterns expand to names and match channels back") {
  // By hand: the level layer for stream indirect and level 3, and its channels.
  CHECK(layer_name(layers::kLevel, "indirect", 3) == "filter.indirect.level3");
  CHECK(layer_channels(layers::kLevelVariance, "direct", 12) ==
        std::vector<std::string>{"filter.direct.level12.variance"});
  CHECK(layer_channels(layers::kTonemapped) ==
        std::vector<std::string>{"filter.tonemapped.R", "filter.tonemapped.G", "filter.tonemapped.B"});
  CHECK(expand_layer(layers::kLevelPrefiltered, 2) ==
        std::vector<std::string>{
            "filter.direct.level0.prefiltered_variance", "filter.direct.level1.prefiltered_variance",
            "filter.indirect.level0.prefiltered_variance", "filter.indirect.level1.prefiltered_variance"});
  CHECK(expand_layer(layers::kColor, 5).size() == 3);

  // Every expanded channel matches its own layer, and no other layer of the same pass.
  for (const PassDecl& pass : filter_passes())
    for (const LayerDecl* layer : pass.writes)
      for (const std::string& channel : expand_layer(*layer, 3)) {
        INFO(channel);
        CHECK(layer_has_channel(*layer, channel));
        for (const LayerDecl* other : pass.writes)
          if (other != layer) CHECK_FALSE(layer_has_channel(*other, channel));
      }
  CHECK_FALSE(layer_has_channel(layers::kLevel, "filter.direct.levelX.R"));
  CHECK_FALSE(layer_has_channel(layers::kLevel, "filter.specular.level0.R"));
  CHECK_FALSE(layer_has_channel(layers::kVariance, "filter.direct.variance.R"));

  // The pass that writes a channel, for error messages.
  CHECK(pass_writing("color.G") == "modulate");
  CHECK(pass_writing("display.B") == "tonemap, taa");
  CHECK(pass_writing("filter.direct.level2.R") == "atrous, eaw");
  CHECK(pass_writing("filter.indirect.level0.prefiltered_variance") == "prefilter");
  CHECK(pass_writing("filter.direct.moments.mu2") == "temporal");
  CHECK(pass_writing("albedo.R") == "?");
}

TEST_CASE("dump_layer refuses a plane of the wrong kind, and every pass declares its parameters and probe") {
  Frame dump(2, 2);
  CHECK_THROWS(dump_layer(&dump, layers::kVariance, "direct", -1, RgbPlane(2, 2)));
  CHECK_THROWS(dump_layer(&dump, layers::kTemporal, "direct", -1, FloatPlane(2, 2)));
  dump_layer(&dump, layers::kTemporal, "direct", -1, RgbPlane(2, 2));
  CHECK(dump.has("filter.direct.temporal.G"));
  CHECK_THROWS(find_pass("specular"));
  for (const PassDecl& pass : filter_passes()) {
    INFO(pass.name);
    CHECK(find_pass(pass.name).golden == pass.golden);
    CHECK(fs::exists(fs::path(RTDR_SOURCE_DIR) / pass.golden));
    CHECK_FALSE(pass.probe.empty());
    CHECK_FALSE(pass.writes.empty());
  }
}
