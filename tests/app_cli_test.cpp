// The `rtdr` command as a user meets it: bad input gives one line on stderr, a non-zero exit and no
// files; a good run writes exactly the layers docs/buffers.md lists. Runs the real binary (RTDR_EXE).
#include "app/commands.h"
#include "core/error.h"
#include "core/exr_io.h"
#include "gpu/vulkan_context.h"

#include "cli_fixtures.h"

#include <catch2/catch.hpp>

#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <regex>
#include <set>
#include <sstream>

namespace fs = std::filesystem;

namespace {

using namespace rtdr::cli;

fs::path scratch(const std::string& name) { return rtdr::cli::scratch("rtdr_cli_test", name); }
std::string read_file(const fs::path& p) { return read_text(p); }
size_t count_files(const fs::path& dir) { return files_in(dir).size(); }

// The channel names in the first column of the tables of docs/buffers.md that describe rendered frames
// (everything before "## Filter passes"): each `name` in the cell, where
// the last part may list alternatives, `path.light.X/Y/Z` meaning path.light.X, path.light.Y, path.light.Z.
// The channels that the tables of docs/buffers.md's sections whose headings start with one of `sections` name.
std::set<std::string> documented_channels(const std::vector<std::string>& sections) {
  std::set<std::string> names;
  std::istringstream doc(read_file(fs::path(RTDR_SOURCE_DIR) / "docs/buffers.md"));
  const std::regex row("^\\| (`[^|]+) \\|");
  const std::regex name("`([a-z_.]+)\\.([A-Za-z_/]+)`");
  bool inside = false;
  for (std::string line; std::getline(doc, line);) {
    if (line.starts_with("## "))
      inside = std::any_of(sections.begin(), sections.end(),
                           [&](const std::string& s) { return line.starts_with("## " + s); });
    std::smatch cell;
    if (!inside || !std::regex_search(line, cell, row)) continue;
    const std::string text = cell[1].str();
    for (auto it = std::sregex_iterator(text.begin(), text.end(), name); it != std::sregex_iterator(); ++it) {
      std::stringstream suffixes((*it)[2].str());
      for (std::string s; std::getline(suffixes, s, '/');) names.insert((*it)[1].str() + "." + s);
    }
  }
  return names;
}

// What rtdr render writes.
std::set<std::string> documented_channels() {
  return documented_channels({"G-buffer and visibility buffer", "Path-traced radiance"});
}

}  // namespace

TEST_CASE("bad input gives one error line, a non-zero exit and no output") {
  const fs::path dir = scratch("bad");
  const fs::path malformed = dir / "malformed.gltf";
  std::ofstream(malformed) << "{ \"asset\": { \"version\": \"2.0\" }, \"nodes\": [ {";
  const fs::path truncated = dir / "truncated.gltf";
  const std::string cornell = read_file(fs::path(RTDR_SOURCE_DIR) / "scenes/cornell.gltf");
  std::ofstream(truncated) << cornell.substr(0, cornell.size() / 2);
  const fs::path not_a_dir = dir / "file.txt";
  std::ofstream(not_a_dir) << "x";

  const std::string out = (dir / "out").string();
  const std::vector<std::string> bad_args = {
      "render --scene no_such_scene --frames 0 --size 8x8 --out " + out,
      "render --scene /no/such/file.gltf --frames 0 --size 8x8 --out " + out,
      "render --scene " + malformed.string() + " --frames 0 --size 8x8 --out " + out,
      "render --scene " + truncated.string() + " --frames 0 --size 8x8 --out " + out,
      "render --scene cornell --frames 0 --size 0x8 --out " + out,
      "render --scene cornell --frames 0 --size 8x --out " + out,
      "render --scene cornell --frames 0 --size -8x8 --out " + out,
      "render --scene cornell --frames 0 --size 99999x8 --out " + out,
      "render --scene cornell --frames 5-2 --size 8x8 --out " + out,
      "render --scene cornell --frames a-b --size 8x8 --out " + out,
      "render --scene cornell --frames 0 --size 8x8 --out " + not_a_dir.string(),
      "render --no-such-flag",
      "bench --stage nothing --runs 1",
      "",
  };
  for (const std::string& args : bad_args) {
    INFO("rtdr " << args);
    const RunResult r = run_rtdr(args, dir);
    CHECK(r.exit_code != 0);
    CHECK(r.err.rfind("rtdr: error: ", 0) == 0);
    CHECK(std::count(r.err.begin(), r.err.end(), '\n') == 1);
    CHECK(count_files(dir / "out") == 0);
  }
}

TEST_CASE("a render at an odd size writes every documented layer and no temporary files") {
  const fs::path dir = scratch("good");
  const RunResult r = run_rtdr("render --scene cornell --frames 0-1 --size 33x17 --out " + (dir / "out").string(), dir);
  REQUIRE(r.exit_code == 0);
  CHECK(r.err.empty());
  std::set<std::string> files;
  for (const auto& e : fs::directory_iterator(dir / "out")) files.insert(e.path().filename().string());
  CHECK(files == std::set<std::string>{"frame_0000.exr", "frame_0000.png", "frame_0001.exr", "frame_0001.png"});

  const rtdr::Frame frame = rtdr::read_exr((dir / "out/frame_0001.exr").string());
  CHECK(frame.width() == 33);
  CHECK(frame.height() == 17);
  std::set<std::string> written;
  for (const auto& [name, plane] : frame.float_channels()) written.insert(name);
  for (const auto& [name, plane] : frame.uint_channels()) written.insert(name);
  const std::set<std::string> documented = documented_channels();
  CHECK(documented.size() >= 60);
  CHECK(written == documented);
}

TEST_CASE("render --gradients adds the documented gradient layers, continues a sequence, and says how") {
  const fs::path dir = scratch("gradients");
  const std::string out = (dir / "out").string();
  const RunResult first = run_rtdr("render --scene pillars --frames 0-2 --size 33x17 --gradients --out " + out, dir);
  REQUIRE(first.exit_code == 0);
  // Frames 3-4 continue from frame 2 in --out; frame 7 renders frames 0-6 first, unwritten.
  const RunResult next = run_rtdr("render --scene pillars --frames 3-4 --size 33x17 --gradients --out " + out, dir);
  REQUIRE(next.exit_code == 0);
  CHECK_THAT(next.out, Catch::Contains("continuing from frame 2"));
  const RunResult later = run_rtdr("render --scene pillars --frames 7 --size 33x17 --gradients --out " + out, dir);
  REQUIRE(later.exit_code == 0);
  CHECK_THAT(later.out, Catch::Contains("rendering frames 0-6 first (not written)"));
  CHECK(count_files(dir / "out") == 2 * 6);

  // Every plain layer and the gradient section's layers of docs/buffers.md.
  const rtdr::Frame frame = rtdr::read_exr((dir / "out/frame_0004.exr").string());
  std::set<std::string> written;
  for (const auto& [name, plane] : frame.float_channels()) written.insert(name);
  for (const auto& [name, plane] : frame.uint_channels()) written.insert(name);
  const std::set<std::string> expected =
      documented_channels({"G-buffer and visibility buffer", "Path-traced radiance", "Gradient samples"});
  CHECK(expected.size() == documented_channels().size() + 4);  // gradient.source, .prev_direct/indirect, rng.seed_frame
  CHECK(written == expected);
  size_t gradient_pixels = 0;
  for (const uint32_t s : frame.uint_channel("gradient.source").data) gradient_pixels += s != rtdr::kInvalidId;
  CHECK(gradient_pixels > 0);
  CHECK(gradient_pixels <= size_t((33 + 2) / 3) * size_t((17 + 2) / 3));  // one per 3x3 stratum at most

  // Continuing a render of another size, other gradient parameters, or of frames without gradients, is one line
  // of error and no output.
  const RunResult restrided =
      run_rtdr("render --scene pillars --frames 5 --size 33x17 --gradients --gradient-stratum-size 2 --out " + out, dir);
  CHECK(restrided.exit_code != 0);
  CHECK_THAT(restrided.err, Catch::Contains("rtdr.gradient.stratum_size is 3, not 2"));
  CHECK(std::count(restrided.err.begin(), restrided.err.end(), '\n') == 1);
  const RunResult resized = run_rtdr("render --scene pillars --frames 3 --size 32x17 --gradients --out " + out, dir);
  CHECK(resized.exit_code != 0);
  CHECK_THAT(resized.err, Catch::Contains("is 33x17, not 32x17"));
  const std::string plain = (dir / "plain").string();
  REQUIRE(run_rtdr("render --scene pillars --frames 0 --size 33x17 --out " + plain, dir).exit_code == 0);
  const RunResult mixed = run_rtdr("render --scene pillars --frames 1 --size 33x17 --gradients --out " + plain, dir);
  CHECK(mixed.exit_code != 0);
  CHECK_THAT(mixed.err, Catch::Contains("was not rendered with --gradients"));
  CHECK(count_files(dir / "plain") == 2);
  CHECK(run_rtdr("render --frames 0 --size 33x17 --gradients --spp 4 --out " + plain, dir).exit_code != 0);
}

TEST_CASE("option parsers accept what they document and reject the rest") {
  CHECK(rtdr::parse_size("1280x720").width == 1280);
  CHECK(rtdr::parse_size("641x481").height == 481);
  for (const char* bad : {"", "x", "12x", "x12", "0x5", "5x0", "12X7", "1.5x2", "16385x2", " 3x3", "3x3 "})
    CHECK_THROWS_AS(rtdr::parse_size(bad), rtdr::Error);
  CHECK(rtdr::parse_frames("7").first == 7);
  CHECK(rtdr::parse_frames("7").last == 7);
  CHECK(rtdr::parse_frames("2-9").last == 9);
  for (const char* bad : {"", "-", "3-", "-3", "9-2", "a", "1-2-3"})
    CHECK_THROWS_AS(rtdr::parse_frames(bad), rtdr::Error);
  // The documented bound, kMaxFrameIndex: every loop over a range stays far from INT_MAX.
  CHECK(rtdr::parse_frames("0-999999").last == 999999);
  for (const char* bad : {"1000000", "0-1000000", "2147483647", "0-2147483647", "0-2147483648"})
    CHECK_THROWS_WITH(rtdr::parse_frames(bad), Catch::Contains("999999"));
  CHECK(rtdr::parse_pixel("640,360", "--pixel").x == 640);
  CHECK(rtdr::parse_pixel("640,360", "--pixel").y == 360);
  for (const char* bad : {"5,6junk", "99999999999,0", "5", "5,", ",6", "5;6", " 5,6", "5,6 ", "5.0,6"})
    CHECK_THROWS_WITH(rtdr::parse_pixel(bad, "--pixel"), Catch::Contains("--pixel"));
}

TEST_CASE("rtdr bench --stage gradients times a frame with and without gradient samples") {
  const fs::path dir = scratch("bench_gradients");
  const fs::path csv = dir / "bench.csv";
  const RunResult r = run_rtdr("bench --stage gradients --scenes cornell --size 30x18 --runs 1 --warmup 0 "
                               "--gradient-stratum-size 2 --csv " + csv.string(), dir);
  INFO(r.out << r.err);
  REQUIRE(r.exit_code == 0);
  CHECK_THAT(r.out, Catch::Contains("strata of 2"));
  const std::string text = read_file(csv);
  for (const char* metric : {"plain_ms", "gradients_ms", "ratio", "gradient_share"})
    CHECK_THAT(text, Catch::Contains(std::string("gradients,cornell,30,18,")) && Catch::Contains(metric));
  // The share of gradient pixels: at most one per 2x2 stratum, 25%.
  const std::regex share("gradient_share,([0-9.e-]+)");
  std::smatch m;
  REQUIRE(std::regex_search(text, m, share));
  CHECK(std::stod(m[1].str()) > 0.0);
  CHECK(std::stod(m[1].str()) <= 0.25);
  CHECK(run_rtdr("bench --stage gradients --size 30x18 --runs 1 --gradient-stratum-size 1", dir).exit_code != 0);
}

TEST_CASE("rtdr bench --stage motion times the shadow motion and its splat beside the frame's tracing") {
  const fs::path dir = scratch("bench_motion");
  const fs::path csv = dir / "bench.csv";
  const RunResult r = run_rtdr("bench --stage motion --scenes pillars --size 48x27 --runs 1 --warmup 0 --csv " +
                               csv.string(), dir);
  INFO(r.out << r.err);
  REQUIRE(r.exit_code == 0);
  const std::string text = read_file(csv);
  for (const char* metric : {"trace_ms", "shadow_ms", "splat_ms", "share", "valid_share"})
    CHECK_THAT(text, Catch::Contains(std::string("motion,pillars,48,27,")) && Catch::Contains(metric));
  // pillars' shadows cover part of the floor: some pixels, not all, have a valid shadow vector.
  const std::regex valid("valid_share,([0-9.e-]+)");
  std::smatch m;
  REQUIRE(std::regex_search(text, m, valid));
  CHECK(std::stod(m[1].str()) > 0.01);
  CHECK(std::stod(m[1].str()) < 0.9);
}

TEST_CASE("rtdr bench --stage filter runs the method with the parameters given, on each back end") {
  const fs::path dir = scratch("bench");
  std::string backends = "cpu";
  if (rtdr::VulkanContext::available()) backends += ",vulkan";
  const fs::path csv = dir / "bench.csv";
  const RunResult r = run_rtdr("bench --backend " + backends + " --size 32x18 --runs 1 --warmup 1 --atrous-levels 2 " +
                                   "--kernel-size 3 --csv " + csv.string(),
                               dir);
  INFO(r.out << r.err);
  REQUIRE(r.exit_code == 0);
  CHECK_THAT(r.out, Catch::StartsWith("svgf:atrous_levels=2:kernel_size=3 on pillars at 32x18"));
  const std::string text = read_file(csv);
  for (const std::string backend : {"cpu", "vulkan"}) {
    if (backends.find(backend) == std::string::npos) continue;
    CHECK_THAT(text, Catch::Contains("filter:svgf:atrous_levels=2:kernel_size=3:" + backend + ",pillars,32,18,"));
  }
  if (backends != "cpu") {  // the ports ran two a-trous levels, each its own command
    const std::regex levels("command by command.* atrous [0-9.]+ atrous [0-9.]+ modulate ");
    CHECK(std::regex_search(r.out, levels));
  }
  // A parameter out of its range is one line, before anything runs.
  const RunResult bad = run_rtdr("bench --backend cpu --size 32x18 --runs 1 --kernel-size 4", dir);
  CHECK(bad.exit_code != 0);
  CHECK(bad.err == "rtdr: error: svgf parameter kernel_size must be 3 or 5\n");
}
