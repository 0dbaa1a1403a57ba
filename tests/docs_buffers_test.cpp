// docs/buffers.md is our contract with users: the layer names an engine must write to run a pass on its own
// frames, and the names `rtdr filter` writes. Its "Filter passes" tables must list exactly the layers the passes
// declare (filters/passes.h), with the same type and the same writing passes. This test reads those tables and
// compares them with the declarations, both ways.
#include "filters/passes.h"

#include <catch2/catch.hpp>

#include <filesystem>
#include <fstream>
#include <map>
#include <regex>
#include <set>
#include <sstream>
#include <string>
#include <vector>

namespace fs = std::filesystem;
using namespace rtdr;

namespace {

// The lines of docs/buffers.md's "Filter passes" section, up to the next heading.
std::vector<std::string> filter_passes_section() {
  std::ifstream in(fs::path(RTDR_SOURCE_DIR) / "docs" / "buffers.md");
  REQUIRE(in);
  std::vector<std::string> lines;
  bool inside = false;
  for (std::string line; std::getline(in, line);) {
    if (line.rfind("## ", 0) == 0 || line.rfind("# ", 0) == 0) inside = line == "## Filter passes";
    else if (inside) lines.push_back(line);
  }
  return lines;
}

std::vector<std::string> split_row(const std::string& line) {
  std::vector<std::string> cells;
  std::stringstream ss(line.substr(1));  // drop the leading '|'
  for (std::string cell; std::getline(ss, cell, '|');) {
    const size_t a = cell.find_first_not_of(' '), b = cell.find_last_not_of(' ');
    cells.push_back(a == std::string::npos ? "" : cell.substr(a, b - a + 1));
  }
  return cells;
}

// A documented layer: "`filter.<s>.temporal.R/G/B`" is the RGB layer filter.<s>.temporal, "`filter.<s>.variance`"
// the scalar layer of that name.
struct Documented {
  LayerType type;
  std::set<std::string> passes;  // the third column, split at ", "
};

std::map<std::string, Documented> documented_layers() {
  std::map<std::string, Documented> layers;
  for (const std::string& line : filter_passes_section()) {
    if (line.rfind("| `", 0) != 0) continue;  // table rows that name channels
    const std::vector<std::string> cells = split_row(line);
    REQUIRE(cells.size() >= 3);
    Documented doc{LayerType::Scalar, {}};
    std::stringstream passes(cells[2]);
    for (std::string pass; std::getline(passes, pass, ',');)
      doc.passes.insert(pass.substr(pass.find_first_not_of(' ')));
    const std::regex span("`([^`]+)`");
    for (auto it = std::sregex_iterator(cells[0].begin(), cells[0].end(), span); it != std::sregex_iterator(); ++it) {
      std::string name = (*it)[1].str();
      Documented layer = doc;
      if (name.size() > 6 && name.compare(name.size() - 6, 6, ".R/G/B") == 0) {
        name.resize(name.size() - 6);
        layer.type = LayerType::Rgb;
      }
      INFO(line);
      CHECK(layers.count(name) == 0);  // each layer documented once
      layers[name] = layer;
    }
  }
  return layers;
}

// Every declared layer, with the passes that declare it.
std::map<std::string, Documented> declared_layers() {
  std::map<std::string, Documented> layers;
  for (const PassDecl& pass : filter_passes())
    for (const LayerDecl* layer : pass.writes) {
      Documented& d = layers[std::string(layer->pattern)];
      d.type = layer->type;
      d.passes.insert(std::string(pass.name));
    }
  return layers;
}

}  // namespace

TEST_CASE("docs/buffers.md documents exactly the layers the passes declare, with their types and passes") {
  const std::map<std::string, Documented> documented = documented_layers();
  const std::map<std::string, Documented> declared = declared_layers();
  // The section exists and has its rows: 2 outputs and 10 dump layers (moments are two).
  CHECK(documented.size() == 12);
  for (const auto& [name, d] : declared) {
    INFO("declared layer " << name);
    const auto it = documented.find(name);
    REQUIRE(it != documented.end());
    CHECK((it->second.type == LayerType::Rgb) == (d.type == LayerType::Rgb));
    CHECK(it->second.passes == d.passes);
  }
  for (const auto& [name, d] : documented) {
    INFO("documented layer " << name);
    CHECK(declared.count(name) == 1);
  }
}

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
