// docs/buffers.md is our contract with users: the layer names an engine must write to run a pass on its own
// frames, and the names `rtdr filter` writes. Its "Filter passes" tables must list exactly the layers the passes
// declare (filters/passes.h), with the same type and the same writing passes. This test reads those tables and
// compares them with the declarations, both ways.
#include "filters/passes.h"

#include "markdown_fixtures.h"

#include <catch2/catch.hpp>

#include <filesystem>
#include <fstream>
#include <map>
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
    const std::vector<std::string> cells = test::split_row(line);
    REQUIRE(cells.size() >= 3);
    Documented doc{LayerType::Scalar, {}};
    std::stringstream passes(cells[2]);
    for (std::string pass; std::getline(passes, pass, ',');)
      doc.passes.insert(pass.substr(pass.find_first_not_of(' ')));
    for (std::string name : test::code_spans(cells[0])) {
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
  // The section exists and has its rows: 2 outputs, SVGF's 11 dump layers (moments are two), A-SVGF's 11 and
  // TRMV's 25.
  CHECK(documented.size() == 49);
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
