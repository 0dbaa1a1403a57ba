// eval/render_plan.h: a plan lists exactly the frames the same run would render, no more and no less: on a cold
// cache every frame the run then stores, on a warm one none, and after damage exactly the frames (and runs of
// gradient frames) the run renders again. Each job is `rtdr render` with every setting of the frame's key on its
// command line. That those command lines give frames the eval then finds cached is shown by running them:
// tests/tools_farm_test.py.
#include "eval/render_plan.h"

#include "cli_fixtures.h"
#include "core/error.h"
#include "eval/frame_cache.h"
#include "scenes/gltf_loader.h"

#include <catch2/catch.hpp>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <map>

namespace fs = std::filesystem;
using namespace rtdr;

namespace {

const std::string kRtdr = "/opt/rtdr/bin/rtdr";  // argv[0] of every job: any absolute path

// Every method's input (asvgf: gradient samples; trmv: the shading term; a stratum study: a second gradient
// sequence), frames 2-4, so the first run of gradient frames reaches back to frame 0.
EvalConfig small_run(const fs::path& cache) {
  EvalConfig c;
  c.scene = "pillars";
  for (const char* m : {"svgf", "asvgf", "trmv", "asvgf:gradient_stratum_size=2"})
    c.methods.push_back(parse_method_spec(m));
  c.first_frame = 2;
  c.last_frame = 4;
  c.width = 32;
  c.height = 18;
  c.ref_spp = 4;
  c.seed = 7;
  c.cache_dir = cache.string();
  return c;
}

// Every frame file in the cache (staging folders aside), with its identity on disk (cli::file_id).
std::map<std::string, std::pair<uint64_t, uint64_t>> entries_in(const fs::path& cache) {
  std::map<std::string, std::pair<uint64_t, uint64_t>> files;
  if (!fs::exists(cache)) return files;
  for (const auto& e : fs::recursive_directory_iterator(cache))
    if (e.is_regular_file() && e.path().extension() == ".exr" && e.path().string().find("/.rtdr-") == std::string::npos)
      files[e.path().string()] = cli::file_id(e.path());
  return files;
}

// The entries a run rendered and stored: new files, and files written again.
std::set<std::string> stored_by_run(const EvalConfig& c) {
  const auto before = entries_in(c.cache_dir);
  run_eval(c);
  std::set<std::string> stored;
  for (const auto& [path, id] : entries_in(c.cache_dir))
    if (!before.count(path) || before.at(path) != id) stored.insert(path);
  return stored;
}

std::set<std::string> planned(const std::vector<RenderJob>& jobs) {
  std::set<std::string> entries;
  for (const RenderJob& j : jobs) entries.insert(j.entries.begin(), j.entries.end());
  return entries;
}

// The value after `flag` in a job's argv ("" when the flag is not there).
std::string flag_value(const RenderJob& job, const std::string& flag) {
  const auto it = std::find(job.argv.begin(), job.argv.end(), flag);
  return it == job.argv.end() || it + 1 == job.argv.end() ? "" : *(it + 1);
}

}  // namespace

TEST_CASE("a plan on a cold cache lists exactly the frames the run then renders, and on a warm cache none") {
  const fs::path cache = cli::scratch("rtdr_render_plan_test", "cold") / "cache";
  const EvalConfig c = small_run(cache);
  const std::vector<RenderJob> jobs = plan_renders(c, kRtdr);
  // 3 references, and two gradient sequences (the run's, the stratum study's) of frames 0-4, one job each.
  REQUIRE(jobs.size() == 5);
  CHECK(std::count_if(jobs.begin(), jobs.end(), [](const RenderJob& j) { return j.dependent; }) == 2);
  for (const RenderJob& j : jobs) {
    CHECK(j.entries.size() == size_t(j.last - j.first + 1));
    CHECK(j.cost() == 32 * 18 * j.spp * (j.last - j.first + 1));
    if (j.dependent) CHECK((j.first == 0 && j.last == 4 && j.previous.empty()));
  }
  const std::set<std::string> entries = planned(jobs);
  CHECK(entries.size() == 13);  // each frame once
  CHECK(stored_by_run(c) == entries);
  CHECK(plan_renders(c, kRtdr).empty());
  CHECK(stored_by_run(c).empty());  // and the run renders nothing either
}

TEST_CASE("a plan lists exactly the frames the cache lost or holds invalid, and the run of gradient frames after") {
  const fs::path cache = cli::scratch("rtdr_render_plan_test", "damaged") / "cache";
  EvalConfig c = small_run(cache);
  c.methods = {parse_method_spec("asvgf")};
  run_eval(c);
  const Scene scene = load_scene("pillars");
  const FrameCache lookup(fs::absolute(cache).string(), scene);
  const EvalRenders renders = eval_renders(c, {make_method("asvgf", MethodParams{}).get()});
  REQUIRE(renders.inputs.size() == 1);
  REQUIRE(renders.inputs[0].gradient.has_value());
  REQUIRE(renders.references.size() == 1);
  const auto input = [&](int f) {
    return lookup.path(render_key(scene, f, 32, 18, renders.inputs[0].settings, &*renders.inputs[0].gradient));
  };
  const std::string reference = lookup.path(render_key(scene, 4, 32, 18, renders.references[0]));
  fs::remove(input(3));  // a hole in the gradient sequence: frame 3 from the cached frame 2, 4 kept
  std::ofstream(reference, std::ios::trunc) << "not a frame";  // an invalid entry is rendered again
  const std::vector<RenderJob> jobs = plan_renders(c, kRtdr);
  REQUIRE(jobs.size() == 2);
  CHECK(jobs[0].what == "reference");
  CHECK(jobs[0].entries == std::vector<std::string>{reference});
  CHECK(jobs[1].dependent);
  CHECK((jobs[1].first == 3 && jobs[1].last == 3));
  CHECK(jobs[1].entries == std::vector<std::string>{input(3)});
  CHECK(jobs[1].previous == input(2));
  CHECK(flag_value(jobs[1], "--frames") == "3-3");
  CHECK(stored_by_run(c) == planned(jobs));
}

TEST_CASE("each job is rtdr render with every setting of the frames' render key on its command line") {
  const fs::path dir = cli::scratch("rtdr_render_plan_test", "argv");
  const EvalConfig c = small_run(dir / "cache");
  const std::vector<RenderJob> jobs = plan_renders(c, kRtdr);
  REQUIRE(jobs.size() == 5);
  for (const RenderJob& j : jobs) {
    CHECK(j.argv[0] == kRtdr);
    CHECK(j.argv[1] == "render");
    CHECK(flag_value(j, "--scene") == (fs::path(RTDR_SCENE_DIR) / "pillars.gltf").lexically_normal().string());
    CHECK(flag_value(j, "--size") == "32x18");
    CHECK(flag_value(j, "--frames") == std::to_string(j.first) + "-" + std::to_string(j.last));
    CHECK(flag_value(j, "--max-bounces") == "1");
    CHECK(std::find(j.argv.begin(), j.argv.end(), "--out") == j.argv.end());  // the runner's to give
    CHECK(j.cache == fs::absolute(dir / "cache").lexically_normal().string());
    for (const std::string& e : j.entries) CHECK(e.rfind(j.cache + "/", 0) == 0);
    if (j.what == "reference") {
      CHECK(flag_value(j, "--spp") == "4");
      CHECK(flag_value(j, "--seed") == std::to_string(7 + 1000003));  // reference_settings
      CHECK(flag_value(j, "--shading-samples") == "0");
      CHECK(flag_value(j, "--gradient-stratum-size").empty());
    } else {
      CHECK(flag_value(j, "--spp") == "1");
      CHECK(flag_value(j, "--seed") == "7");
      CHECK(flag_value(j, "--shading-samples") == std::to_string(kTrmvShadingSamples));  // trmv reads it
      CHECK(std::count(j.argv.begin(), j.argv.end(), "--gradients") == 1);
      for (const ParamInfo& row : gradient_param_table()) {
        std::string flag = "--gradient-" + row.name;
        std::replace(flag.begin(), flag.end(), '_', '-');
        CHECK_FALSE(flag_value(j, flag).empty());
      }
    }
  }
  // The two gradient sequences differ in the stratum study's row alone.
  std::vector<std::string> strata;
  for (const RenderJob& j : jobs)
    if (j.dependent) strata.push_back(flag_value(j, "--gradient-stratum-size"));
  std::sort(strata.begin(), strata.end());
  CHECK(strata == std::vector<std::string>{"2", "3"});
}

TEST_CASE("a plan line is one line of JSON holding the job") {
  RenderJob job;
  job.what = "input with gradient samples";
  job.argv = {kRtdr, "render", "--scene", "/a b/it's \"quoted\".gltf"};
  job.first = 3;
  job.last = 5;
  job.entries = {"/c/f3.exr", "/c/f4.exr", "/c/f5.exr"};
  job.dependent = true;
  job.previous = "/c/f2.exr";
  job.cache = "/c";
  job.pixels = 1920 * 1080;
  job.spp = 1024;
  const std::string line = plan_line(job, 17);
  CHECK(line.find('\n') == std::string::npos);
  const nlohmann::json j = nlohmann::json::parse(line);
  CHECK(j.at("job") == 17);
  CHECK(j.at("argv").get<std::vector<std::string>>() == job.argv);
  CHECK(j.at("frames") == nlohmann::json::array({3, 5}));
  CHECK(j.at("entries").get<std::vector<std::string>>() == job.entries);
  CHECK(j.at("previous") == "/c/f2.exr");
  CHECK(j.at("dependent") == true);
  CHECK(j.at("cost").get<int64_t>() == int64_t(1920) * 1080 * 1024 * 3);  // past 2^32
  job.previous.clear();
  CHECK(nlohmann::json::parse(plan_line(job, 0)).at("previous").is_null());
  job.entries[0] = "/c/\xff.exr";
  CHECK_THROWS_WITH(plan_line(job, 0), Catch::Contains("not UTF-8"));
}

TEST_CASE("a plan is refused where the run would be, and without a cache") {
  const fs::path dir = cli::scratch("rtdr_render_plan_test", "refused");
  EvalConfig c = small_run(dir / "cache");
  c.cache_dir = "";
  CHECK_THROWS_WITH(plan_renders(c, kRtdr), Catch::Contains("--cache"));
  c = small_run(dir / "cache");
  c.width = 8;
  CHECK_THROWS_WITH(plan_renders(c, kRtdr), Catch::Contains("SSIM window"));
  c = small_run(dir / "cache");
  c.scene = (dir / "missing.gltf").string();
  CHECK_THROWS_AS(plan_renders(c, kRtdr), Error);
  CHECK_FALSE(fs::exists(dir / "cache"));  // nothing made
}

TEST_CASE("a spec's own max_bounces adds its inputs and its references to the plan, exactly as the run renders them") {
  const fs::path cache = cli::scratch("rtdr_render_plan_test", "bounces") / "cache";
  EvalConfig c = small_run(cache);
  c.methods = {parse_method_spec("svgf"), parse_method_spec("svgf:max_bounces=0")};
  c.last_frame = 3;
  const std::vector<RenderJob> jobs = plan_renders(c, kRtdr);
  // Frames 2 and 3 of the references and of the inputs, each with 1 bounce (the run's) and with 0: one job each.
  REQUIRE(jobs.size() == 8);
  std::map<std::string, int> per_bounces;
  for (const RenderJob& j : jobs) ++per_bounces[j.what + " " + flag_value(j, "--max-bounces")];
  CHECK(per_bounces == std::map<std::string, int>{{"input 0", 2}, {"input 1", 2}, {"reference 0", 2}, {"reference 1", 2}});
  CHECK(stored_by_run(c) == planned(jobs));
}
