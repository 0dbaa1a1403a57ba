// `rtdr compare`'s verdict (app/cmd_compare.cpp) against the one table of the ports' bounds (gpu/port_bounds.h),
// which the pipeline tests (tests/gpu_svgf_test.cpp, tests/gpu_trmv_vulkan_test.cpp) assert as well: every channel
// with a stated bound is judged against it, the rest are reported only, and the report's columns line up under
// their names for the longest channel name. Runs the real binary (RTDR_EXE) on 3 frames of pillars at 40x24;
// skipped where no Vulkan device exists.
#include "gpu/port_bounds.h"

#include "cli_fixtures.h"
#include "test_skip.h"

#include <catch2/catch.hpp>

#include <algorithm>
#include <filesystem>
#include <sstream>
#include <string>
#include <vector>

namespace fs = std::filesystem;
using namespace rtdr::cli;

TEST_CASE("the ports' bounds table states what the pipeline tests derive, and nothing for the unbounded buffers") {
  const rtdr::PortBound* colour = rtdr::find_port_bound("svgf", "color.G");
  REQUIRE(colour != nullptr);
  CHECK(colour->relative);
  CHECK(colour->bound(false) == 2e-3);
  CHECK(colour->bound(true) == 2e-2);
  const rtdr::PortBound* mu2 = rtdr::find_port_bound("svgf", "filter.indirect.moments.mu2");
  REQUIRE(mu2 != nullptr);
  CHECK(mu2->bound(false) == Approx((1 + 2e-3) * (1 + 2e-3) - 1));
  REQUIRE(rtdr::find_port_bound("svgf", "filter.direct.level3.B") != nullptr);
  CHECK(rtdr::find_port_bound("svgf", "filter.direct.level3.B")->bound(false) == 2e-3);
  REQUIRE(rtdr::find_port_bound("svgf", "filter.direct.history_length") != nullptr);
  CHECK_FALSE(rtdr::find_port_bound("svgf", "filter.direct.history_length")->relative);
  CHECK(rtdr::find_port_bound("asvgf", "filter.direct.alpha")->bound(false) == 1e-3);
  CHECK(rtdr::find_port_bound("trmv", "color.B")->bound(true) == 5e-3);
  // No bound independent of the frame: the variances; the display is bounded against another golden value.
  for (const std::string channel : {"filter.direct.variance", "filter.direct.level0.variance", "display.R"})
    CHECK(rtdr::find_port_bound("svgf", channel) == nullptr);
  CHECK(rtdr::find_port_bound("eaw", "color.R") == nullptr);  // no port
  for (const rtdr::PortBound& b : rtdr::port_bounds()) CHECK(fs::exists(fs::path(RTDR_SOURCE_DIR) / b.test));
}

TEST_CASE("rtdr compare judges each bounded channel against the table and prints a verdict, columns aligned") {
  rtdr::test::skip_without_vulkan();
  const fs::path dir = rtdr::cli::scratch("rtdr_compare_test", "verdict");
  const std::string in = (dir / "in").string();
  REQUIRE(run_rtdr("render --scene pillars --frames 0-2 --size 40x24 --out " + in, dir).exit_code == 0);
  const RunResult r = run_rtdr("compare --in " + in, dir, "RTDR_VK_ILLUMINATION=fp32");
  INFO(r.out << r.err);
  REQUIRE(r.exit_code == 0);
  std::istringstream text(r.out);
  std::string line, header;
  int judged = 0, unjudged = 0;
  while (std::getline(text, line)) {  // the rows lie between the header and the line "largest ..."
    if (line.starts_with("channel ")) {
      header = line;
      continue;
    }
    if (header.empty()) continue;
    if (line.starts_with("largest")) break;
    const std::string channel = line.substr(0, line.find(' '));
    INFO(line);
    // Each value column ends under its name.
    for (const std::string column : {"max abs", "cpu", "vulkan", "max rel", "bound"}) {
      const size_t end = header.find(" " + column + " ") + 1 + column.size();
      REQUIRE(end < line.size());
      CHECK(line[end - 1] != ' ');
      CHECK(line[end] == ' ');
    }
    const rtdr::PortBound* bound = rtdr::find_port_bound("svgf", channel);
    if (bound) {
      ++judged;
      CHECK_THAT(line, Catch::EndsWith(" ok"));
    } else {
      ++unjudged;
      CHECK_THAT(line, Catch::EndsWith(" -"));
    }
  }
  // The dump's bounded channels (gpu_svgf_test.cpp: per stream 7 colours, mu1, mu2, n and which variance) and the
  // colour.
  CHECK(judged == 2 * (7 * 3 + 4) + 3 + 3);
  CHECK(unjudged > 0);
  CHECK_THAT(r.out, Catch::Contains("largest relative difference: "));
  CHECK_THAT(r.out, Catch::Contains("verdict: PASS: all " + std::to_string(judged) + " bounded channels within"));
  // With another floor the relative bounds do not apply: no verdict, and still exit 0.
  const RunResult floor = run_rtdr("compare --in " + in + " --rel-floor 0.5", dir, "RTDR_VK_ILLUMINATION=fp32");
  CHECK(floor.exit_code == 0);
  CHECK_THAT(floor.out, Catch::Contains("verdict: none"));
}
