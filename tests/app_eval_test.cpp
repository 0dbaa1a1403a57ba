// `rtdr eval` (app/cmd_eval.cpp, app/backend.cpp's SpecMethods) as a user meets it, running the real binary
// (RTDR_EXE): bad method specs give one line on stderr, a non-zero exit and nothing rendered or written; with
// backend=vulkan in a spec, the shader ports run beside the golden passes and are measured by the same metrics;
// --plan writes the jobs of the run's renders (eval/render_plan.h) and nothing else.
//
// Bound on the ports' RMSE (the Vulkan test below). The pipeline's colour c' is within d of the golden colour c
// per channel, relative to max(|c|, f) with f = 1e-2: d = 2e-3 with fp32 illumination records and 2e-2 with fp16
// (derived in tests/gpu_svgf_test.cpp). So |c' - c| <= d (|c| + f) channel by channel, and taking root mean squares
// (Minkowski) rms(c' - c) <= d (rms(c) + f). By the triangle inequality |rmse' - rmse| <= rms(c' - c), and
// rms(c) <= rmse + rms(ref), rmse being the golden colour's distance to the reference ref. Hence
//   |rmse' - rmse| <= d (rmse + rms(ref) + f),
// with rms(ref) computed here from the reference frames rtdr eval left in its cache.
#include "eval/experiment.h"
#include "eval/frame_cache.h"
#include "gpu/vulkan_context.h"
#include "scenes/gltf_loader.h"

#include "cli_fixtures.h"
#include "test_skip.h"

#include <catch2/catch.hpp>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <map>
#include <set>
#include <sstream>
#include <string>
#include <vector>

namespace fs = std::filesystem;

namespace {

using namespace rtdr::cli;

fs::path scratch(const std::string& name) { return rtdr::cli::scratch("rtdr_eval_test", name); }

// metrics.csv as rows of column name -> text.
std::vector<std::map<std::string, std::string>> read_metrics(const fs::path& csv) {
  std::istringstream in(read_text(csv));
  std::string line;
  std::getline(in, line);
  const std::vector<std::string> header = csv_cells(line);
  std::vector<std::map<std::string, std::string>> rows;
  while (std::getline(in, line)) {
    const std::vector<std::string> row = csv_cells(line);
    REQUIRE(row.size() == header.size());
    std::map<std::string, std::string>& r = rows.emplace_back();
    for (size_t i = 0; i < header.size(); ++i) r[header[i]] = row[i];
  }
  return rows;
}

// Root mean square over the pixels and channels of the colour a frame shows.
double rms_colour(const rtdr::Frame& f) {
  const rtdr::RgbPlane c = rtdr::frame_colour(f);
  double sum = 0.0;
  for (const glm::vec3& p : c.data) sum += double(p.x) * p.x + double(p.y) * p.y + double(p.z) * p.z;
  return std::sqrt(sum / (3.0 * double(c.data.size())));
}

}  // namespace

TEST_CASE("rtdr eval: a bad method spec gives one line before anything is rendered or written") {
  const fs::path dir = scratch("bad");
  const std::vector<std::string> bad_specs = {
      "svgf:backend=metal",               // no such back end
      "svgf:illumination=fp16",           // records without the ports
      "svgf:backend=vulkan:illumination=fp8",
      "svgf,eaw:backend=vulkan",          // no Vulkan port (or, without a device, no device)
  };
  for (const std::string& specs : bad_specs) {
    INFO("--methods " << specs);
    const RunResult r = run_rtdr("eval --scene pillars --methods " + specs + " --frames 0-1 --size 24x16 --ref-spp 2 " +
                                     "--cache " + (dir / "cache").string() + " --out " + (dir / "out").string(),
                                 dir);
    CHECK(r.exit_code != 0);
    CHECK_THAT(r.err, Catch::StartsWith("rtdr: error: "));
    CHECK(std::count(r.err.begin(), r.err.end(), '\n') == 1);
    CHECK(files_in(dir / "cache").empty());
    CHECK(files_in(dir / "out").empty());
  }
}

TEST_CASE("rtdr eval --plan writes one rtdr render job per line, with this rtdr's path, and renders nothing") {
  const fs::path dir = scratch("plan");
  const fs::path cache = dir / "cache", out = dir / "out", plan = dir / "plan.jsonl";
  // A port's spec is planned from its golden method's inputs: no device is opened.
  const RunResult r = run_rtdr("eval --scene pillars --methods svgf,asvgf:backend=vulkan --frames 0-1 --size 24x16 "
                               "--ref-spp 2 --cache " + cache.string() + " --out " + out.string() + " --plan " +
                                   plan.string(), dir);
  REQUIRE(r.exit_code == 0);
  CHECK_THAT(r.out, Catch::StartsWith("wrote 3 job(s) to " + plan.string()));
  std::istringstream lines(read_text(plan));
  std::vector<nlohmann::json> jobs;
  for (std::string line; std::getline(lines, line);) jobs.push_back(nlohmann::json::parse(line));
  REQUIRE(jobs.size() == 3);  // the references of frames 0 and 1, and the run of gradient frames 0-1
  for (const nlohmann::json& job : jobs) {
    CHECK(job.at("argv").at(0) == fs::canonical(RTDR_EXE).string());
    CHECK(job.at("argv").at(1) == "render");
  }
  CHECK(jobs[2].at("dependent") == true);
  CHECK(jobs[2].at("frames") == nlohmann::json::array({0, 1}));
  CHECK_FALSE(fs::exists(cache));  // nothing rendered
  CHECK(files_in(dir) == std::set<std::string>{"plan.jsonl", "stderr.txt", "stdout.txt"});  // no temporary left
}

TEST_CASE("rtdr eval --plan is refused without a cache, and into a folder that does not exist, leaving no file") {
  const fs::path dir = scratch("plan_refused");
  const std::vector<std::string> run = {"eval", "--scene", "pillars", "--methods", "svgf", "--frames", "0-1",
                                        "--size", "24x16", "--ref-spp", "2", "--out", (dir / "out").string()};
  std::vector<std::string> no_cache = run, no_folder = run;
  no_cache.insert(no_cache.end(), {"--cache", "", "--plan", (dir / "plan.jsonl").string()});
  no_folder.insert(no_folder.end(),
                   {"--cache", (dir / "cache").string(), "--plan", (dir / "no" / "plan.jsonl").string()});
  for (const auto& args : {no_cache, no_folder}) {
    const RunResult r = run_rtdr_args(args, dir);
    CHECK(r.exit_code == 1);
    CHECK_THAT(r.err, Catch::StartsWith("rtdr: error: "));
    CHECK(std::count(r.err.begin(), r.err.end(), '\n') == 1);
  }
  CHECK(files_in(dir) == std::set<std::string>{"stderr.txt", "stdout.txt"});
}

TEST_CASE("rtdr eval runs svgf on the shader ports beside the golden passes, within the pipeline's bound") {
  rtdr::test::skip_without_vulkan();
  const fs::path dir = scratch("ports");
  rtdr::EvalConfig config;  // what the command line below asks for, to find its reference frames in the cache
  config.scene = "pillars";
  config.first_frame = 0;
  config.last_frame = 2;
  config.width = 48;
  config.height = 27;
  config.ref_spp = 4;
  const RunResult r = run_rtdr("eval --scene pillars --methods svgf,svgf:backend=vulkan:illumination=fp32,"
                               "svgf:backend=vulkan:illumination=fp16 --frames 0-2 --size 48x27 --ref-spp 4 "
                               "--cache " + (dir / "cache").string() + " --out " + (dir / "out").string(),
                               dir);
  INFO(r.out << r.err);
  REQUIRE(r.exit_code == 0);
  const auto rows = read_metrics(dir / "out" / "metrics.csv");
  REQUIRE(rows.size() == 9);  // 3 methods x 3 frames, method by method

  const rtdr::Scene scene = rtdr::load_scene("pillars");
  rtdr::FrameCache cache((dir / "cache").string(), scene);
  const std::map<std::string, double> bound = {{"backend=vulkan:illumination=fp32", 2e-3},
                                               {"backend=vulkan:illumination=fp16", 2e-2}};
  for (int f = 0; f < 3; ++f) {
    bool hit = false;
    const double rms_ref = rms_colour(cache.get(f, 48, 27, rtdr::reference_settings(config), &hit));
    REQUIRE(hit);  // the reference rtdr eval measured against
    const auto& golden = rows[size_t(f)];
    REQUIRE(golden.at("params").empty());
    CHECK(golden.at("ms_transfer").empty());
    for (size_t m = 1; m < 3; ++m) {
      const auto& port = rows[m * 3 + size_t(f)];
      INFO(port.at("params") << " frame " << f);
      REQUIRE(std::stoi(port.at("frame")) == f);
      // The ports report the host's transfer apart, and their device times sum to ms_total without it.
      CHECK(std::stod(port.at("ms_transfer")) > 0.0);
      double sum = 0.0;
      for (const char* pass : {"ms_temporal", "ms_variance", "ms_atrous", "ms_modulate", "ms_tonemap", "ms_taa"})
        sum += std::stod(port.at(pass));
      CHECK(std::stod(port.at("ms_total")) == Approx(sum).epsilon(1e-6));
      const double rmse = std::stod(golden.at("rmse")), rmse_port = std::stod(port.at("rmse"));
      const double allowed = bound.at(port.at("params")) * (rmse + rms_ref + 1e-2);
      INFO("rmse golden " << rmse << ", port " << rmse_port << ", allowed difference " << allowed);
      CHECK(std::abs(rmse_port - rmse) <= allowed);
    }
    // The records the spec names are the ones used: halves round the colour, so the two ports' errors differ.
    CHECK(rows[3 + size_t(f)].at("rmse") != rows[6 + size_t(f)].at("rmse"));
  }
}

// asvgf and trmv on their ports (backend=vulkan, gpu/svgf_vulkan.h and gpu/trmv_vulkan.h), beside the golden passes
// on the same input: each port's RMSE within the guard its pipeline test holds its colour to (tests/gpu_svgf_test.cpp,
// tests/gpu_trmv_vulkan_test.cpp: 2e-3 for asvgf with fp32 records, 5e-3 for trmv), relative as above.
TEST_CASE("rtdr eval runs asvgf and trmv on the shader ports beside the golden passes") {
  rtdr::test::skip_without_vulkan();
  const fs::path dir = scratch("ports_asvgf_trmv");
  const RunResult r = run_rtdr("eval --scene fence --methods asvgf,asvgf:backend=vulkan:illumination=fp32,trmv,"
                               "trmv:backend=vulkan --frames 0-2 --size 48x27 --ref-spp 4 --cache " +
                                   (dir / "cache").string() + " --out " + (dir / "out").string(),
                               dir);
  INFO(r.out << r.err);
  REQUIRE(r.exit_code == 0);
  const auto rows = read_metrics(dir / "out" / "metrics.csv");
  REQUIRE(rows.size() == 12);  // 4 methods x 3 frames, method by method
  for (int f = 0; f < 3; ++f)
    for (const auto& [golden_index, guard] : {std::pair<size_t, double>{0, 2e-3}, {2, 5e-3}}) {
      const auto& golden = rows[golden_index * 3 + size_t(f)];
      const auto& port = rows[(golden_index + 1) * 3 + size_t(f)];
      INFO(golden.at("method") << " frame " << f << " " << port.at("params"));
      REQUIRE(golden.at("method") == port.at("method"));
      CHECK(std::stod(port.at("ms_transfer")) > 0.0);
      const double rmse = std::stod(golden.at("rmse")), rmse_port = std::stod(port.at("rmse"));
      CHECK(rmse_port != 0.0);
      CHECK(std::abs(rmse_port - rmse) <= guard * (rmse + 1e-2));
    }
}

TEST_CASE("rtdr eval --help lists the method names, and no help text says a port runs svgf alone") {
  const fs::path dir = scratch("help");
  const RunResult eval = run_rtdr("eval --help", dir);
  REQUIRE(eval.exit_code == 0);
  for (const std::string& name : rtdr::method_names()) CHECK_THAT(eval.out, Catch::Contains(name));
  CHECK_THAT(eval.out, Catch::Contains("svgf, asvgf, a-eaw, accum, eaw, eaw-accum, none, trmv"));
  CHECK_THAT(eval.out, !Catch::Contains("runs svgf on the"));
  const RunResult compare = run_rtdr("compare --help", dir);
  REQUIRE(compare.exit_code == 0);
  CHECK_THAT(compare.out, !Catch::Contains("run SVGF") && Catch::Contains("svgf, asvgf or trmv"));
}

// A file name is the user's text, never TeX. The scene `$\sqrt$.gltf` (pillars, copied) names
// the charts' titles; matplotlib would read "$\sqrt$" as mathtext and fail after all the rendering.
TEST_CASE("rtdr eval: a scene file named with TeX in it gives its charts, its name shown as written") {
  const fs::path dir = scratch("tex_name");
  const fs::path scene = dir / "$\\sqrt$.gltf";
  fs::copy_file(fs::path(RTDR_SOURCE_DIR) / "scenes/pillars.gltf", scene);
  const fs::path out = dir / "out";
  const RunResult r = run_rtdr_args({"eval", "--scene", scene.string(), "--methods", "accum,none", "--frames", "0-2",
                                     "--size", "24x14", "--ref-spp", "2", "--cache", "", "--out", out.string()},
                                    dir);
  INFO(r.out << r.err);
  REQUIRE(r.exit_code == 0);
  CHECK(files_in(out) == std::set<std::string>{"error_over_frames.png", "metrics.csv", "speed_vs_accuracy.png",
                                               "strip.png", "temporal_error.png"});
}

// strip.png (eval/strip.py) shows every method that ran, parameters included, and none's tile is the input's.
TEST_CASE("rtdr eval: the strip shows each method that ran once, up to --strip-max, and bad strip options fail early") {
  const fs::path dir = scratch("strip");
  const std::string base = "eval --scene pillars --frames 0-1 --size 24x14 --ref-spp 2 --cache " +
                           (dir / "cache").string() + " --methods none,accum,accum:alpha=0.5";
  const RunResult r = run_rtdr(base + " --out " + (dir / "all").string(), dir);
  INFO(r.out << r.err);
  REQUIRE(r.exit_code == 0);
  CHECK_THAT(r.out, Catch::Contains("strip.png, in reading order: | 1 spp input (= none) | accum | accum:alpha=0.5 | "
                                    "reference 2 spp\n"));
  const RunResult capped = run_rtdr(base + " --strip-max 1 --strip-crop 0,0,12,12 --out " + (dir / "one").string(), dir);
  REQUIRE(capped.exit_code == 0);
  CHECK_THAT(capped.out, Catch::Contains("strip.png shows the first 1 of the 2 methods") &&
                             Catch::Contains("in reading order: | 1 spp input (= none) | accum | reference"));
  const RunResult chosen = run_rtdr(base + " --strip accum:alpha=0.5 --out " + (dir / "chosen").string(), dir);
  REQUIRE(chosen.exit_code == 0);
  CHECK_THAT(chosen.out, Catch::Contains("in reading order: | 1 spp input (= none) | accum:alpha=0.5 | reference"));
  // Refused before anything is rendered: nothing in the fresh cache, no output.
  for (const std::string bad : {"--strip-crop 20,0,8,8", "--strip-crop 1,2,3", "--strip svgf", "--chart-metrics psnr"}) {
    INFO(bad);
    const fs::path cache = dir / "bad_cache";
    const RunResult b = run_rtdr("eval --scene pillars --frames 0-1 --size 24x14 --methods accum " + bad + " --cache " +
                                     cache.string() + " --out " + (dir / "bad").string(), dir);
    CHECK(b.exit_code == 1);
    CHECK(std::count(b.err.begin(), b.err.end(), '\n') == 1);
    CHECK_FALSE(fs::exists(dir / "bad"));
    CHECK(files_in(cache).empty());
  }
}
