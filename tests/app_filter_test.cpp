// `rtdr filter`, `rtdr probe` and the bad input of `rtdr compare` (app/cmd_filter.cpp, app/cmd_compare.cpp,
// app/sequence.cpp) as a user meets them, running the real binary (RTDR_EXE) on a 3-frame cornell sequence
// rendered at 32x18: the files and layers a good run writes, the probe's JSON and text, and bad input: one line on
// stderr starting "rtdr: error: ", a non-zero exit and no output files. rtdr compare's report is checked in
// tests/gpu_svgf_test.cpp.
#include "core/exr_io.h"
#include "core/frame.h"
#include "filters/method.h"
#include "gpu/vulkan_context.h"
#include "scenes/gltf_loader.h"
#include "trace/render_frame.h"

#include "cli_fixtures.h"
#include "test_skip.h"

#include <catch2/catch.hpp>
#include <nlohmann/json.hpp>

#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>
#include <set>
#include <sstream>
#include <string>
#include <vector>

namespace fs = std::filesystem;

namespace {

using namespace rtdr::cli;

fs::path scratch(const std::string& name) { return rtdr::cli::scratch("rtdr_filter_test", name); }

// The input sequence: frames 0-2 of cornell at 32x18, rendered once per process by `rtdr render`.
const fs::path& sequence() {
  static const fs::path dir = [] {
    const fs::path d = scratch("sequence");
    const RunResult r = run_rtdr("render --scene cornell --frames 0-2 --size 32x18 --out " + (d / "in").string(), d);
    REQUIRE(r.exit_code == 0);
    return d / "in";
  }();
  return dir;
}

std::set<std::string> channels(const rtdr::Frame& f) {
  std::set<std::string> names;
  for (const auto& [name, plane] : f.float_channels()) names.insert(name);
  for (const auto& [name, plane] : f.uint_channels()) names.insert(name);
  return names;
}

// The layers --dump-passes adds for svgf with its 5 a-trous levels, as its passes declare them
// (filters/passes.h, docs/buffers.md "Filter passes"). Counted by hand: per stream, temporal (3 channels),
// the two moments, the history length, the variance and which estimate it is, per level 3 + 2, and filtered (3);
// then filter.tonemapped.
std::set<std::string> dump_channels() {
  const std::vector<std::string> declared = rtdr::make_method("svgf")->dump_channels();
  const std::set<std::string> names(declared.begin(), declared.end());
  CHECK(names.size() == declared.size());
  CHECK(names.size() == 2 * (3 + 2 + 1 + 1 + 1 + 5 * (3 + 2) + 3) + 3);
  return names;
}

const std::set<std::string> kOutputChannels = {"color.R", "color.G", "color.B", "display.R", "display.G", "display.B"};

}  // namespace

TEST_CASE("rtdr filter writes an EXR with color and display and a PNG per frame") {
  const fs::path dir = scratch("filter");
  const fs::path out = dir / "out";
  const RunResult r = run_rtdr("filter --in " + sequence().string() + " --out " + out.string(), dir);
  REQUIRE(r.exit_code == 0);
  CHECK(r.err.empty());
  CHECK(files_in(out) == std::set<std::string>{"frame_0000.exr", "frame_0000.png", "frame_0001.exr",
                                               "frame_0001.png", "frame_0002.exr", "frame_0002.png"});
  for (int f = 0; f < 3; ++f) {
    INFO("frame " << f);
    const rtdr::Frame frame = rtdr::read_exr((out / ("frame_000" + std::to_string(f) + ".exr")).string());
    CHECK(frame.width() == 32);
    CHECK(frame.height() == 18);
    CHECK(channels(frame) == kOutputChannels);
    for (const std::string& name : kOutputChannels) {
      const std::vector<float>& v = frame.float_channel(name).data;
      CHECK(std::all_of(v.begin(), v.end(), [](float x) { return std::isfinite(x); }));
    }
    CHECK(fs::file_size(out / ("frame_000" + std::to_string(f) + ".png")) > 0);
  }
}

TEST_CASE("rtdr filter --backend vulkan writes what --backend cpu writes, within the pipeline's bound") {
  rtdr::test::skip_without_vulkan();
  const fs::path dir = scratch("backend");
  for (const std::string backend : {"cpu", "vulkan"}) {
    const RunResult r = run_rtdr("filter --backend " + backend + " --in " + sequence().string() + " --out " +
                                     (dir / backend).string(), dir);
    INFO("stderr: " << r.err);
    REQUIRE(r.exit_code == 0);
  }
  CHECK(files_in(dir / "vulkan") == files_in(dir / "cpu"));
  for (int f = 0; f < 3; ++f) {
    const std::string name = "frame_000" + std::to_string(f) + ".exr";
    const rtdr::Frame cpu = rtdr::read_exr((dir / "cpu" / name).string());
    const rtdr::Frame gpu = rtdr::read_exr((dir / "vulkan" / name).string());
    REQUIRE(channels(gpu) == kOutputChannels);
    // tests/gpu_svgf_test.cpp derives the colour's bound: 2e-3 relative to max(|cpu|, 1e-2).
    double worst = 0.0;
    for (const char* c : {"color.R", "color.G", "color.B"}) {
      const std::vector<float>&a = cpu.float_channel(c).data, &b = gpu.float_channel(c).data;
      for (size_t i = 0; i < a.size(); ++i)
        worst = std::max(worst, double(std::abs(a[i] - b[i])) / std::max(double(std::abs(a[i])), 1e-2));
    }
    INFO(name << ": colour max relative error " << worst);
    CHECK(worst <= 2e-3);
  }
}

TEST_CASE("every parameter table reaches the CLI: EAW, tone mapping and TAA flags change what they say") {
  const fs::path dir = scratch("tables");
  const std::string in = " --in " + sequence().string();
  // --eaw-levels 2: the dump holds EAW levels 0 and 1 only.
  REQUIRE(run_rtdr("filter --method eaw --eaw-levels 2 --dump-passes" + in + " --out " + (dir / "eaw").string(), dir)
              .exit_code == 0);
  const rtdr::Frame eaw = rtdr::read_exr((dir / "eaw" / "frame_0002.exr").string());
  CHECK(eaw.has("filter.direct.level1.R"));
  CHECK_FALSE(eaw.has("filter.direct.level2.R"));

  // --tonemap-exposure 0: L = 0 L_w, so the display is black [Reinhard02 Eq. 2, 3]; the colour is untouched.
  // --taa-alpha 1: the display is the current frame's tone-mapped colour, no history (up to the rounding of
  // TAA's round trip through YCoCg).
  REQUIRE(run_rtdr("filter" + in + " --out " + (dir / "plain").string(), dir).exit_code == 0);
  REQUIRE(run_rtdr("filter --tonemap-exposure 0" + in + " --out " + (dir / "black").string(), dir).exit_code == 0);
  REQUIRE(run_rtdr("filter --taa-alpha 1 --dump-passes" + in + " --out " + (dir / "no_taa").string(), dir).exit_code ==
          0);
  const rtdr::Frame plain = rtdr::read_exr((dir / "plain" / "frame_0002.exr").string());
  const rtdr::Frame black = rtdr::read_exr((dir / "black" / "frame_0002.exr").string());
  const rtdr::Frame no_taa = rtdr::read_exr((dir / "no_taa" / "frame_0002.exr").string());
  for (const char* c : {"R", "G", "B"}) {
    INFO("channel " << c);
    const std::string display = std::string("display.") + c, colour = std::string("color.") + c;
    CHECK(black.float_channel(colour).data == plain.float_channel(colour).data);
    for (const float v : black.float_channel(display).data) CHECK(v == 0.0f);
    const std::vector<float>& shown = no_taa.float_channel(display).data;
    const std::vector<float>& tonemapped = no_taa.float_channel(std::string("filter.tonemapped.") + c).data;
    float worst = 0.0f;
    for (size_t i = 0; i < shown.size(); ++i) worst = std::max(worst, std::abs(shown[i] - tonemapped[i]));
    CHECK(worst <= 1e-6f);
    CHECK(shown != plain.float_channel(display).data);  // TAA does blend by default
  }
}

TEST_CASE("rtdr filter --dump-passes adds every filter.* layer and changes nothing else") {
  const fs::path dir = scratch("dump");
  const RunResult plain = run_rtdr("filter --in " + sequence().string() + " --out " + (dir / "plain").string(), dir);
  REQUIRE(plain.exit_code == 0);
  const RunResult r =
      run_rtdr("filter --in " + sequence().string() + " --out " + (dir / "dump").string() + " --dump-passes", dir);
  REQUIRE(r.exit_code == 0);
  CHECK(r.err.empty());
  CHECK(files_in(dir / "dump").size() == 6);
  std::set<std::string> expected = dump_channels();
  expected.insert(kOutputChannels.begin(), kOutputChannels.end());
  for (int f = 0; f < 3; ++f) {
    INFO("frame " << f);
    const std::string name = "frame_000" + std::to_string(f) + ".exr";
    const rtdr::Frame dumped = rtdr::read_exr((dir / "dump" / name).string());
    CHECK(channels(dumped) == expected);
    const rtdr::Frame frame = rtdr::read_exr((dir / "plain" / name).string());
    for (const std::string& c : kOutputChannels) CHECK(dumped.float_channel(c).data == frame.float_channel(c).data);
  }
}

// Runs `rtdr probe ... --json` and returns the parsed document.
nlohmann::json probe_json(const std::string& args, const fs::path& dir) {
  const RunResult r = run_rtdr(args + " --json", dir);
  REQUIRE(r.exit_code == 0);
  CHECK(r.err.empty());
  nlohmann::json doc;
  REQUIRE_NOTHROW(doc = nlohmann::json::parse(r.out));
  return doc;
}

// Line `number` (from 1) of a file, or "" past its end.
std::string read_line(const fs::path& path, int number) {
  std::istringstream lines(read_text(path));
  std::string line;
  for (int i = 0; i < number && std::getline(lines, line);) ++i;
  return line;
}

std::set<std::string> term_names(const nlohmann::json& doc) {
  std::set<std::string> names;
  for (const nlohmann::json& t : doc.at("terms")) names.insert(t.at("name").get<std::string>());
  return names;
}

TEST_CASE("rtdr probe prints the terms of a pass as JSON, or as text one term per line") {
  const fs::path dir = scratch("probe");
  const std::string probe = "probe --in " + sequence().string() + " --frame 2 --pass atrous --level 1 --pixel ";

  // At 32x18 the Cornell box covers about columns 8 to 24: pixel (5, 5) sees the background, where the
  // a-trous passes its input through [filters/svgf/atrous.h], and says so.
  const nlohmann::json background = probe_json(probe + "5,5", dir);
  CHECK(background.at("pixel") == nlohmann::json::array({5, 5}));
  REQUIRE(background.at("terms").is_array());
  CHECK_FALSE(background.at("terms").empty());
  CHECK(term_names(background).count("no surface: passed through") == 1);

  // Pixel (16, 9), on the box, records every tap's edge-stopping weights [SVGF17 Eq. 3-5] and the result.
  const std::string args = probe + "16,9";
  const nlohmann::json doc = probe_json(args, dir);
  CHECK(doc.at("pass") == "atrous");
  CHECK(doc.at("frame") == 2);
  CHECK(doc.at("level") == 1);
  CHECK(doc.at("stream") == "direct");
  CHECK(doc.at("pixel") == nlohmann::json::array({16, 9}));
  const nlohmann::json& terms = doc.at("terms");
  REQUIRE(terms.is_array());
  CHECK(terms.size() > 25 * 3);  // 25 taps, three weights each
  for (const nlohmann::json& t : terms) {
    CHECK(t.at("value").is_array());
    CHECK(t.contains("group"));
    CHECK(t.contains("cite"));
    // Where the golden function computed it: a note() of filters/svgf/atrous.cpp, at that line.
    CHECK(t.at("file") == "filters/svgf/atrous.cpp");
    const std::string line = read_line(fs::path(RTDR_SOURCE_DIR) / "filters/svgf/atrous.cpp", t.at("line").get<int>());
    CHECK(line.find("note(") != std::string::npos);
    CHECK(t.at("equations").is_array());
  }
  const std::set<std::string> names = term_names(doc);
  for (const char* w : {"w_z", "w_n", "w_l", "c_{i+1}(p)"}) {
    INFO(w);
    CHECK(names.count(w) == 1);
  }

  // The text: '#' header lines, then "group | name = value[ | cite]", one line per JSON term, same order.
  const RunResult t = run_rtdr(args, dir);
  REQUIRE(t.exit_code == 0);
  CHECK(t.err.empty());
  std::istringstream lines(t.out);
  std::vector<std::string> term_lines;
  for (std::string line; std::getline(lines, line);)
    if (!line.empty() && line[0] != '#') term_lines.push_back(line);
  REQUIRE(term_lines.size() == terms.size());
  for (size_t i = 0; i < term_lines.size(); ++i) {
    INFO(term_lines[i]);
    const std::string name = terms[i].at("name").get<std::string>();
    CHECK(term_lines[i].find(" | " + name + " = ") != std::string::npos);
  }
}

TEST_CASE("bad filter and probe input: one error line, a non-zero exit and no output files") {
  const fs::path dir = scratch("bad");
  const rtdr::Frame good = rtdr::read_exr((sequence() / "frame_0000.exr").string());
  const std::string seq = sequence().string();

  // Input folders, each wrong in one way.
  const fs::path empty = scratch("bad/empty");
  const fs::path missing_layer = scratch("bad/missing_layer");
  rtdr::write_exr((missing_layer / "frame_0000.exr").string(), without(good, "direct.R"));
  const fs::path nan = scratch("bad/nan");
  rtdr::Frame with_nan = good;
  with_nan.float_channel("direct.G").at(7, 3) = std::numeric_limits<float>::quiet_NaN();
  rtdr::write_exr((nan / "frame_0000.exr").string(), with_nan);
  const fs::path resized = scratch("bad/resized");
  fs::copy_file(sequence() / "frame_0000.exr", resized / "frame_0000.exr");
  rtdr::write_exr((resized / "frame_0001.exr").string(),
                  rtdr::render_frame(rtdr::load_scene("cornell"), 1, 16, 9, rtdr::RenderSettings{}));

  const std::string out = (dir / "out").string();
  const std::vector<std::string> bad_args = {
      "filter --out " + out,                                                            // --in missing
      "filter --in " + (dir / "no_such_dir").string() + " --out " + out,                // --in not there
      "filter --in " + empty.string() + " --out " + out,                                // no frames
      "filter --in " + missing_layer.string() + " --out " + out,                        // no direct.R
      "filter --in " + nan.string() + " --out " + out,                                  // NaN in direct.G
      "filter --in " + resized.string() + " --out " + out,                              // frame 1 is 16x9
      "filter --in " + seq + " --out " + out + " --method svfg",                        // unknown method
      "filter --in " + seq + " --out " + out + " --sigma-l -1",                         // out of range
      "filter --in " + seq + " --out " + out + " --sigma_l 4",                          // flags have hyphens
      "filter --in " + seq + " --out " + out + " --taa-alpha 1.5",                      // out of range
      "filter --in " + seq + " --out " + out + " --method eaw --eaw-levels 11",         // out of range
      "filter --in " + seq + " --out " + out + " --backend metal",                      // unknown back end
      "filter --in " + seq + " --out " + out + " --backend vulkan --method accum",      // no port
      "compare --in " + seq + " --csv " + out + "/c.csv --rel-floor 0",                 // floor must be > 0
      "compare --in " + seq + " --csv " + out + "/c.csv --max-rel-error -1",            // bound must be >= 0
      "compare --in " + nan.string() + " --csv " + out + "/c.csv",                      // NaN in direct.G
      "compare --in " + resized.string() + " --csv " + out + "/c.csv",                  // frame 1 is 16x9
      "probe --in " + seq + " --frame 2 --pixel 999,999",                               // outside the frame
      "probe --in " + seq + " --frame 2 --pixel 5,5 --pass nonsense",                   // no such pass
      "probe --in " + seq + " --frame 7 --pixel 5,5",                                   // no such frame
      "probe --in " + seq + " --frame 2 --pixel 5",                                     // not X,Y
      "probe --in " + seq + " --frame 2 --pixel 5,5 --method accum --pass atrous",      // not run by accum
  };
  for (const std::string& args : bad_args) {
    INFO("rtdr " << args);
    const RunResult r = run_rtdr(args, dir);
    INFO("stderr: " << r.err);
    CHECK(r.exit_code != 0);
    CHECK(r.err.rfind("rtdr: error: ", 0) == 0);
    CHECK(std::count(r.err.begin(), r.err.end(), '\n') == 1);
    // Every input is checked before anything is written: this once left frame_0000 behind when frame_0001
    // of the `resized` sequence turned out to be 16x9.
    CHECK(files_in(out).empty());
    fs::remove_all(out);
  }

  // The size error names both files (it once named only the second).
  const RunResult r = run_rtdr("filter --in " + resized.string() + " --out " + out, dir);
  INFO("stderr: " << r.err);
  CHECK(r.err.find("frame_0001.exr") != std::string::npos);
  CHECK(r.err.find("frame_0000.exr") != std::string::npos);
  fs::remove_all(out);
}

TEST_CASE("rtdr probe with a pass the method does not run lists the passes it runs, for every method") {
  const fs::path dir = scratch("probe_passes");
  const std::string in = (dir / "in").string();
  REQUIRE(run_rtdr("render --scene pillars --frames 0-1 --size 24x14 --gradients --shading-samples 2 --out " + in, dir)
              .exit_code == 0);
  for (const std::string& method : rtdr::method_names()) {
    INFO(method);
    std::string passes;
    for (const std::string& p : rtdr::make_method(method)->probe_passes()) passes += (passes.empty() ? "" : ", ") + p;
    for (const std::string pass : {"nonsense", method == "trmv" ? "atrous" : "trmv_cleanup"}) {
      const RunResult r = run_rtdr("probe --method " + method + " --in " + in + " --frame 1 --pixel 3,3 --pass " + pass,
                                   dir);
      CHECK(r.exit_code == 1);
      CHECK(r.err == "rtdr: error: --pass '" + pass + "' is not a pass of method " + method +
                         " with these parameters; its passes: " + passes + " (rtdr probe --help says what each prints)\n");
    }
  }
}
