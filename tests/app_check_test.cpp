// rtdr check (app/cmd_check.cpp): a good sequence passes; with each layer a method reads removed in turn, exactly
// that layer is named, in the frame that lacks it, or noted where it has a default (emission, indirect: filtered
// as zeros, to the bit); NaN, a frame of another size and a file that is no EXR are
// each named too, and every problem of every frame is reported, not only the first.
#include "core/exr_io.h"
#include "filters/method.h"

#include "cli_fixtures.h"

#include <catch2/catch.hpp>

#include <cmath>
#include <fstream>
#include <set>

namespace fs = std::filesystem;
using rtdr::cli::run_rtdr;

namespace {

// `frame` without the channels of `layer` (every "layer.*").
rtdr::Frame without_layer(const rtdr::Frame& frame, const std::string& layer) {
  rtdr::Frame out(frame.width(), frame.height());
  out.attributes = frame.attributes;
  for (const auto& [name, plane] : frame.float_channels())
    if (name.rfind(layer + ".", 0) != 0) out.add_float(name) = plane;
  for (const auto& [name, plane] : frame.uint_channels())
    if (name.rfind(layer + ".", 0) != 0) out.add_uint(name) = plane;
  return out;
}

// How many lines of `text` contain `part`.
int lines_with(const std::string& text, const std::string& part) {
  int n = 0;
  for (size_t at = text.find(part); at != std::string::npos; at = text.find(part, at + 1)) ++n;
  return n;
}

}  // namespace

TEST_CASE("rtdr check: each missing layer named exactly, in its frame, and every problem of every frame") {
  const fs::path dir = rtdr::cli::scratch("rtdr_check_test", "frames");
  const fs::path good = dir / "good";
  REQUIRE(run_rtdr("render --scene cornell --frames 0-1 --size 24x16 --out " + good.string(), dir).exit_code == 0);
  const rtdr::cli::RunResult ok = run_rtdr("check --in " + good.string(), dir);
  CHECK(ok.exit_code == 0);
  CHECK_THAT(ok.out, Catch::Contains("ok: 2 frames of 24x16"));

  // The layers svgf reads, from its declared input channels: depth, normal, motion, albedo, emission, direct,
  // indirect and id.
  const rtdr::InputChannels channels = rtdr::make_method("svgf")->inputs();
  std::set<std::string> layers;
  for (const auto* names : {&channels.floats, &channels.uints})
    for (const std::string& n : *names) layers.insert(n.substr(0, n.rfind('.')));
  CHECK(layers.size() == 8);
  const rtdr::Frame frame1 = rtdr::read_exr((good / "frame_0001.exr").string());
  for (const std::string& layer : layers) {
    INFO("without layer " << layer);
    const fs::path bad = dir / ("no_" + layer);
    fs::create_directories(bad);
    fs::copy_file(good / "frame_0000.exr", bad / "frame_0000.exr");
    rtdr::write_exr((bad / "frame_0001.exr").string(), without_layer(frame1, layer));
    const rtdr::cli::RunResult r = run_rtdr("check --in " + bad.string(), dir);
    if (layer == "emission" || layer == "indirect") {  // these may be left out: they default to 0
      CHECK(r.exit_code == 0);
      CHECK_THAT(r.out, Catch::Contains("note: some frames leave out " + layer + ".R, which then holds 0"));
      continue;
    }
    CHECK(r.exit_code == 1);
    CHECK(lines_with(r.out, "\n") == 1);  // one problem: this layer, in frame 1
    CHECK_THAT(r.out, Catch::StartsWith((bad / "frame_0001.exr").string() + ": missing layer '" + layer + "'"));
    CHECK_THAT(r.err, Catch::Contains("1 problem(s) in 1 of 2 frames"));
  }

  // A frame that leaves out emission is filtered as one whose emission is 0 everywhere, to the bit.
  const fs::path zero = dir / "zero_emission";
  fs::create_directories(zero);
  fs::copy_file(good / "frame_0000.exr", zero / "frame_0000.exr");
  rtdr::Frame zeroed = without_layer(frame1, "emission");
  for (const char* c : {"emission.R", "emission.G", "emission.B"}) zeroed.add_float(c, 0.0f);
  rtdr::write_exr((zero / "frame_0001.exr").string(), zeroed);
  for (const fs::path& in : {dir / "no_emission", zero})
    REQUIRE(run_rtdr("filter --method svgf --in " + in.string() + " --out " + in.string() + "_svgf", dir).exit_code == 0);
  const rtdr::Frame left_out = rtdr::read_exr((dir / "no_emission_svgf" / "frame_0001.exr").string());
  const rtdr::Frame written = rtdr::read_exr((dir / "zero_emission_svgf" / "frame_0001.exr").string());
  CHECK(left_out.float_channel("color.G").data == written.float_channel("color.G").data);

  // Everything at once: one channel of a layer gone, NaN, another size, not an EXR; and gradient samples for asvgf.
  const fs::path mixed = dir / "mixed";
  fs::create_directories(mixed);
  rtdr::Frame partial = frame1;
  partial = without_layer(partial, "normal");
  partial.add_float("normal.X") = frame1.float_channel("normal.X");
  partial.float_channel("direct.G").at(3, 2) = std::nanf("");
  rtdr::write_exr((mixed / "frame_0000.exr").string(), partial);
  REQUIRE(run_rtdr("render --scene cornell --frames 1 --size 20x16 --out " + (dir / "small").string(), dir).exit_code == 0);
  fs::copy_file(dir / "small" / "frame_0001.exr", mixed / "frame_0001.exr");
  std::ofstream(mixed / "frame_0002.exr") << "not an exr";
  const rtdr::cli::RunResult r = run_rtdr("check --in " + mixed.string(), dir);
  CHECK(r.exit_code == 1);
  CHECK(lines_with(r.out, "\n") == 4);
  CHECK_THAT(r.out, Catch::Contains("frame_0000.exr: layer 'normal' lacks normal.Y, normal.Z"));
  CHECK_THAT(r.out, Catch::Contains("frame_0000.exr: channel 'direct.G' holds NaN or infinity at 1 pixels, the first at (3, 2)"));
  CHECK_THAT(r.out, Catch::Contains("frame_0001.exr: size 20x16, but") && Catch::Contains("is 24x16"));
  CHECK_THAT(r.out, Catch::Contains("frame_0002.exr: cannot read EXR file"));
  CHECK_THAT(r.err, Catch::Contains("4 problem(s) in 3 of 3 frames"));

  const rtdr::cli::RunResult gradients = run_rtdr("check --method asvgf --in " + good.string(), dir);
  CHECK(gradients.exit_code == 1);
  CHECK(lines_with(gradients.out, "missing layer 'gradient' (gradient.prev_direct, gradient.prev_indirect, gradient.source)") == 2);
  CHECK(lines_with(gradients.out, "no header attribute rtdr.gradient.stratum_size") == 2);
  CHECK(run_rtdr("check --method nothing --in " + good.string(), dir).exit_code == 1);
}

TEST_CASE("docs/buffers.md's table of the channels each method reads is what each method reads") {
  std::ifstream doc(RTDR_SOURCE_DIR "/docs/buffers.md");
  REQUIRE(doc.good());
  // The backticked names of a table cell.
  const auto names = [](const std::string& cell) {
    std::vector<std::string> out;
    for (size_t open = cell.find('`'); open != std::string::npos; open = cell.find('`', open + 1)) {
      const size_t close = cell.find('`', open + 1);
      out.push_back(cell.substr(open + 1, close - open - 1));
      open = close;
    }
    return out;
  };
  bool in_section = false;
  std::set<std::string> common, documented;
  for (std::string line; std::getline(doc, line);) {
    if (line.rfind("## ", 0) == 0) in_section = line == "## Feeding your engine's frames";
    if (!in_section || line.rfind("| `", 0) != 0) continue;
    const size_t split = line.find(" | ");
    const std::vector<std::string> methods = names(line.substr(0, split));
    std::set<std::string> channels;
    for (const std::string& n : names(line.substr(split))) channels.insert(n);
    channels.erase("rtdr.gradient.stratum_size");  // a header attribute, not a channel
    if (line.find("(the common set)") != std::string::npos) common = channels;
    if (line.find("the common set and") != std::string::npos || line.find("the common set,") != std::string::npos)
      channels.insert(common.begin(), common.end());
    for (const std::string& m : methods) {
      INFO("method " << m);
      const rtdr::InputChannels in = rtdr::make_method(m)->inputs();
      std::set<std::string> reads(in.floats.begin(), in.floats.end());
      reads.insert(in.uints.begin(), in.uints.end());
      CHECK(channels == reads);
      documented.insert(m);
    }
  }
  const std::vector<std::string> all = rtdr::method_names();
  CHECK(documented == std::set<std::string>(all.begin(), all.end()));
}
