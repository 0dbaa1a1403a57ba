// The options every subcommand shares (app/options.cpp, app/cli.cpp, app/main.cpp), as a user types them: --threads
// before or after the subcommand, TRMV's motion row by name or by number, and a malformed option's error pointing to
// the subcommand's own --help. Runs the real binary (RTDR_EXE) on frames rendered at 24x14.
#include "core/exr_io.h"
#include "core/frame.h"
#include "filters/trmv/trmv_params.h"

#include "cli_fixtures.h"

#include <catch2/catch.hpp>

#include <filesystem>
#include <iterator>
#include <utility>
#include <string>

namespace fs = std::filesystem;
using namespace rtdr::cli;

namespace {

fs::path scratch(const std::string& name) { return rtdr::cli::scratch("rtdr_options_test", name); }

// Whether two frames hold the same channels with the same values, bit for bit.
bool same_frame(const rtdr::Frame& a, const rtdr::Frame& b) {
  if (a.float_channels().size() != b.float_channels().size()) return false;
  for (const auto& [name, plane] : a.float_channels())
    if (!b.float_channels().count(name) || b.float_channel(name).data != plane.data) return false;
  return true;
}

}  // namespace

TEST_CASE("rtdr accepts --threads after the subcommand as before it, with the same frames") {
  const fs::path dir = scratch("threads");
  const std::string before = (dir / "before").string(), after = (dir / "after").string();
  REQUIRE(run_rtdr("--threads 1 render --scene pillars --frames 0 --size 24x14 --out " + before, dir).exit_code == 0);
  const RunResult r = run_rtdr("render --scene pillars --frames 0 --size 24x14 --threads 2 --out " + after, dir);
  INFO(r.err);
  REQUIRE(r.exit_code == 0);
  CHECK(same_frame(rtdr::read_exr(before + "/frame_0000.exr"), rtdr::read_exr(after + "/frame_0000.exr")));
  // Still range-checked, wherever it stands, and every subcommand's --help says it exists.
  const RunResult bad = run_rtdr("render --frames 0 --size 24x14 --threads -1 --out " + (dir / "bad").string(), dir);
  CHECK(bad.exit_code == 2);
  CHECK_THAT(bad.err, Catch::StartsWith("rtdr: error: --threads") && Catch::EndsWith("(see rtdr render --help)\n"));
  CHECK_FALSE(fs::exists(dir / "bad"));
  for (const std::string sub : {"render", "filter", "probe", "eval", "bench", "compare", "check"})
    CHECK_THAT(run_rtdr(sub + " --help", dir).out, Catch::Contains("--threads N"));
}

TEST_CASE("rtdr filter --trmv-motion takes the motion's names and its numbers, as eval's trmv:motion= does") {
  const fs::path dir = scratch("motion");
  const std::string in = (dir / "in").string();
  REQUIRE(run_rtdr("render --scene fence --frames 0-1 --size 24x14 --shading-samples 2 --out " + in, dir).exit_code ==
          0);
  for (int m = 0; m < int(std::size(rtdr::kTrmvMotionNames)); ++m) {
    const std::string name = rtdr::kTrmvMotionNames[m];
    INFO(name);
    const std::string by_name = (dir / ("name_" + name)).string(), by_number = (dir / ("number_" + name)).string();
    const RunResult a = run_rtdr("filter --method trmv --trmv-motion " + name + " --in " + in + " --out " + by_name, dir);
    const RunResult b = run_rtdr("filter --method trmv --trmv-motion " + std::to_string(m) + " --in " + in +
                                     " --out " + by_number, dir);
    REQUIRE(a.exit_code == 0);
    REQUIRE(b.exit_code == 0);
    CHECK(same_frame(rtdr::read_exr(by_name + "/frame_0001.exr"), rtdr::read_exr(by_number + "/frame_0001.exr")));
  }
  // The motions differ: the name reaches the filter (shadow against traditional on the fence's moving shadows).
  CHECK_FALSE(same_frame(rtdr::read_exr(dir / "name_shadow/frame_0001.exr"),
                         rtdr::read_exr(dir / "name_traditional/frame_0001.exr")));
  // Anything else names the values and the subcommand's own help, for every subcommand with the flag.
  const std::string out = " --out " + (dir / "never").string();
  for (const auto& [sub, rest] : {std::pair<std::string, std::string>{"filter", " --in " + in + out},
                                  {"probe", " --in " + in + " --frame 0 --pixel 1,1"},
                                  {"compare", " --in " + in},
                                  {"bench", ""}}) {
    INFO(sub);
    const RunResult bad = run_rtdr(sub + " --method trmv --trmv-motion sideways" + rest, dir);
    CHECK(bad.exit_code == 2);
    CHECK_THAT(bad.err, Catch::StartsWith("rtdr: error: ") && Catch::Contains("'sideways' is not one of traditional 0, "
                                                                              "shadow 1, dual 2, glossy 3, all 4") &&
                            Catch::EndsWith("(see rtdr " + sub + " --help)\n"));
    CHECK(run_rtdr(sub + " --method trmv --trmv-motion 5" + rest, dir).exit_code == 2);
  }
  CHECK_FALSE(fs::exists(dir / "never"));
  CHECK_THAT(run_rtdr("filter --help", dir).out, Catch::Contains("a name or its number: traditional 0"));
}
