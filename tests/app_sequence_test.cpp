// A frame that lacks a layer `rtdr render` writes only when asked (filters/input_check.cpp missing_layers, filters/method.h
// missing_layer_fix): the error of every command that reads it names the layer and the flag that writes it, the same
// words in rtdr filter, probe and check. Runs the real binary (RTDR_EXE) on 2 frames rendered at 24x14 without the
// gradient samples and without the shading term; the control renders them with the flags the errors name.
#include "filters/method.h"

#include "cli_fixtures.h"

#include <catch2/catch.hpp>

#include <algorithm>
#include <filesystem>
#include <string>

namespace fs = std::filesystem;
using namespace rtdr::cli;

namespace {

fs::path scratch(const std::string& name) { return rtdr::cli::scratch("rtdr_sequence_test", name); }

size_t lines_with(const std::string& text, const std::string& part) {
  size_t n = 0, at = 0;
  while ((at = text.find(part, at)) != std::string::npos) ++n, at += part.size();
  return n;
}

}  // namespace

TEST_CASE("a missing gradient or shading layer names the rtdr render flag that writes it, in filter, probe and check") {
  const fs::path dir = scratch("hints");
  const std::string in = (dir / "plain").string();
  REQUIRE(run_rtdr("render --scene pillars --frames 0-1 --size 24x14 --out " + in, dir).exit_code == 0);
  const std::string gradients = "render the frames with `rtdr render --gradients`";
  const std::string shading = "render the frames with `rtdr render --shading-samples N`";
  for (const auto& [method, layer, fix] : {std::tuple{"asvgf", "gradient", gradients},
                                          std::tuple{"a-eaw", "gradient", gradients},
                                          std::tuple{"trmv", "direct.shading", shading}}) {
    INFO(method);
    const std::string missing = "missing layer '" + std::string(layer) + "' (";
    const RunResult filter = run_rtdr("filter --method " + std::string(method) + " --in " + in + " --out " +
                                          (dir / "out").string(), dir);
    CHECK(filter.exit_code == 1);
    CHECK_THAT(filter.err, Catch::StartsWith("rtdr: error: " + in + "/frame_0000.exr: " + missing) &&
                               Catch::EndsWith(fix + " (" + (layer == std::string("gradient")
                                                                  ? "A-SVGF's gradient samples)\n"
                                                                  : "TRMV's shading term; rtdr eval uses 64)\n")));
    CHECK_FALSE(fs::exists(dir / "out"));
    const RunResult probe = run_rtdr("probe --method " + std::string(method) + " --in " + in +
                                         " --frame 1 --pixel 3,3 --pass " + rtdr::make_method(method)->probe_passes()[0],
                                     dir);
    CHECK(probe.exit_code == 1);
    CHECK_THAT(probe.err, Catch::Contains(missing) && Catch::Contains(fix));
    // rtdr check: the same line for each frame, then its summary.
    const RunResult check = run_rtdr("check --method " + std::string(method) + " --in " + in, dir);
    CHECK(check.exit_code == 1);
    CHECK(lines_with(check.out, missing) == 2);
    CHECK(lines_with(check.out, fix) == 2);
  }
  // A layer every render writes has no such fix: the message stays as it was.
  CHECK(rtdr::missing_layer_fix("normal").empty());
  CHECK(rtdr::missing_layer_fix("id").empty());

  // The control: frames rendered as the errors say are accepted by every method.
  const std::string full = (dir / "full").string();
  REQUIRE(run_rtdr("render --scene pillars --frames 0-1 --size 24x14 --gradients --shading-samples 2 --out " + full,
                   dir).exit_code == 0);
  for (const std::string& method : rtdr::method_names()) {
    INFO(method);
    const RunResult check = run_rtdr("check --method " + method + " --in " + full, dir);
    CHECK(check.exit_code == 0);
    CHECK_THAT(check.out, Catch::StartsWith("ok: 2 frames"));
  }
}
