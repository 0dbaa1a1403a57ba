// `rtdr bench`'s output as a user reads it (app/cmd_bench.cpp's BenchTable, app/bench_*.cpp): every column's values
// end where its name ends, whatever a scene's name (a path of 60 characters here); progress on stderr while a scene
// is timed; --stage filter's passes in the order the method runs them, "total" last. Runs the real binary
// (RTDR_EXE) at 24x14 with one run. Timings themselves are never asserted.
#include "filters/method.h"
#include "gpu/vulkan_context.h"

#include "cli_fixtures.h"

#include <catch2/catch.hpp>

#include <algorithm>
#include <filesystem>
#include <sstream>
#include <string>
#include <vector>

namespace fs = std::filesystem;
using namespace rtdr::cli;

namespace {

fs::path scratch(const std::string& name) { return rtdr::cli::scratch("rtdr_bench_test", name); }

std::vector<std::string> lines(const std::string& text) {
  std::vector<std::string> out;
  std::istringstream in(text);
  for (std::string line; std::getline(in, line);) out.push_back(line);
  return out;
}

// Checks that in every row (the lines that start with one of `scenes`) each of `columns`' values ends in the
// character above which the header's name ends, the next character being a space or the line's end.
void check_aligned(const std::string& out, const std::vector<std::string>& scenes,
                   const std::vector<std::string>& columns) {
  const std::vector<std::string> all = lines(out);
  const auto header = std::find_if(all.begin(), all.end(), [](const std::string& l) { return l.starts_with("scene "); });
  REQUIRE(header != all.end());
  size_t rows = 0;
  for (const std::string& row : all) {
    if (std::none_of(scenes.begin(), scenes.end(), [&](const std::string& s) { return row.starts_with(s + " "); }))
      continue;
    ++rows;
    size_t from = 0;
    for (const std::string& column : columns) {
      const size_t at = header->find(" " + column, from);
      REQUIRE(at != std::string::npos);
      const size_t end = at + 1 + column.size();  // one past the name's last character
      from = end;
      INFO("column '" << column << "' in\n" << *header << "\n" << row);
      REQUIRE(end <= row.size());
      CHECK(row[end - 1] != ' ');
      CHECK((end == row.size() || row[end] == ' '));
    }
  }
  CHECK(rows == scenes.size());
}

}  // namespace

TEST_CASE("rtdr bench: each column's values end under its name, for a scene with a long name too") {
  const fs::path dir = scratch("columns");
  const fs::path scene = dir / "a_scene_whose_name_is_longer_than_any_column.gltf";
  fs::copy_file(fs::path(RTDR_SOURCE_DIR) / "scenes/cornell.gltf", scene);
  const std::string scenes = " --scenes cornell," + scene.string() + " --size 24x14 --runs 1 --warmup 0";
  const std::vector<std::string> names = {"cornell", scene.string()};
  const RunResult raster = run_rtdr("bench --stage raster" + scenes, dir);
  REQUIRE(raster.exit_code == 0);
  check_aligned(raster.out, names, {"size", "visibility", "gbuffer", "vis+gbuffer", "motion"});
  const RunResult trace = run_rtdr("bench --stage trace" + scenes, dir);
  REQUIRE(trace.exit_code == 0);
  check_aligned(trace.out, names, {"size", "frame ms", "loop ms", "Mrays", "tracer Mr/s", "bare Mr/s", "ratio",
                                   "frame MB", "layers"});
  const RunResult gradients = run_rtdr("bench --stage gradients" + scenes, dir);
  REQUIRE(gradients.exit_code == 0);
  check_aligned(gradients.out, names, {"size", "plain ms", "gradients ms", "ratio", "gradients"});
  // --stage motion, whose header spanned the wrong columns: with the ports' columns where a device exists.
  const bool vulkan = rtdr::VulkanContext::available();
  const RunResult motion = run_rtdr("bench --stage motion" + scenes + (vulkan ? " --backend cpu,vulkan" : ""), dir);
  INFO(motion.out << motion.err);
  REQUIRE(motion.exit_code == 0);
  std::vector<std::string> columns = {"size", "trace ms", "+shading", "shadow ms", "splat ms"};
  if (vulkan) columns.insert(columns.end(), {"shadow vk", "splat vk"});
  columns.insert(columns.end(), {"dual ms", "glossy ms"});
  if (vulkan) columns.insert(columns.end(), {"dual vk", "glossy vk"});
  columns.insert(columns.end(), {"share", "of +shading", "valid"});
  check_aligned(motion.out, names, columns);
}

TEST_CASE("rtdr bench shows each scene's progress on stderr while it times it") {
  const fs::path dir = scratch("progress");
  // stderr is a file here: the bar prints a plain line at every tenth, the last at 100%.
  for (const std::string stage : {"raster", "trace", "gradients", "motion"}) {
    const RunResult r = run_rtdr("bench --stage " + stage + " --scenes cornell,pillars --size 24x14 --runs 2", dir);
    INFO(stage << ": " << r.err);
    REQUIRE(r.exit_code == 0);
    CHECK_THAT(r.err, Catch::Contains("bench " + stage + " cornell 100%") &&
                          Catch::Contains("bench " + stage + " pillars 100%"));
  }
  const RunResult filter = run_rtdr("bench --backend cpu --size 24x14 --runs 1 --warmup 1", dir);
  REQUIRE(filter.exit_code == 0);
  CHECK_THAT(filter.err, Catch::Contains("bench filter pillars 100%"));
}

TEST_CASE("rtdr bench --stage filter lists the passes in the order the method runs them, total last") {
  const fs::path dir = scratch("order");
  for (const std::string method : {"svgf", "asvgf", "trmv"}) {
    INFO(method);
    const RunResult r = run_rtdr("bench --backend cpu --method " + method + " --size 24x14 --runs 1 --warmup 1", dir);
    INFO(r.out << r.err);
    REQUIRE(r.exit_code == 0);
    std::vector<std::string> rows;  // the pass column, below the header "  pass"
    bool below = false;
    for (const std::string& line : lines(r.out)) {
      if (line.starts_with("  pass ")) below = true;
      else if (below && line.starts_with("  ")) rows.push_back(line.substr(2, line.find(' ', 2) - 2));
    }
    REQUIRE(rows.size() >= 3);
    CHECK(rows.back() == "total");
    const std::vector<std::string> order = rtdr::make_method(method)->probe_passes();
    // The method's own passes first, in its order; then what else a back end times (trmv's remodulation and tone
    // mapping), by name.
    std::vector<size_t> ranks;  // each listed pass's place in the method's order
    std::vector<std::string> others;
    for (size_t k = 0; k + 1 < rows.size(); ++k) {
      const auto it = std::find(order.begin(), order.end(), rows[k]);
      if (it == order.end()) {
        others.push_back(rows[k]);
      } else {
        CHECK(others.empty());
        ranks.push_back(size_t(it - order.begin()));
      }
    }
    CHECK(ranks.size() >= 3);
    CHECK(std::is_sorted(ranks.begin(), ranks.end()));
    CHECK(std::is_sorted(others.begin(), others.end()));
  }
}
