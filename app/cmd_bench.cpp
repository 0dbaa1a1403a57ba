// rtdr bench: timings that the test suite never asserts. Each stage is timed as the median of --runs
// runs after --warmup runs, per shipped scene, on as many threads as --threads allows.
//   --stage raster: visibility buffer, G-buffer resolve and motion back-projection (issue target:
//                   visibility + G-buffer <= 50 ms at 1280x720 on 2 cores).
#include "app/commands.h"
#include "core/atomic_file.h"
#include "core/error.h"
#include "core/parallel.h"
#include "raster/backproject.h"
#include "raster/gbuffer.h"
#include "raster/view.h"
#include "raster/visibility.h"
#include "scenes/catalog.h"
#include "scenes/gltf_loader.h"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <memory>
#include <sstream>

namespace rtdr {
namespace {

struct BenchOptions {
  std::string stage = "raster";
  std::string size = "1280x720";
  std::string scenes = "all";
  int runs = 20;
  int warmup = 3;
  std::string csv;
};

// Median wall time in milliseconds of `runs` calls of fn, after `warmup` untimed calls.
template <class Fn>
double median_ms(int warmup, int runs, Fn&& fn) {
  for (int i = 0; i < warmup; ++i) fn();
  std::vector<double> ms;
  for (int i = 0; i < runs; ++i) {
    const auto t0 = std::chrono::steady_clock::now();
    fn();
    ms.push_back(std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count());
  }
  std::nth_element(ms.begin(), ms.begin() + ms.size() / 2, ms.end());
  return ms[ms.size() / 2];
}

std::vector<std::string> scene_list(const std::string& text) {
  if (text == "all") return shipped_scene_names();
  std::vector<std::string> names;
  std::stringstream ss(text);
  for (std::string name; std::getline(ss, name, ',');)
    if (!name.empty()) names.push_back(name);
  return names;
}

void bench_raster(const BenchOptions& o, const Size size, std::ostream* csv) {
  std::printf("%-10s %9s %12s %12s %12s %12s   (median ms of %d runs, %d threads)\n", "scene", "size",
              "visibility", "gbuffer", "vis+gbuffer", "motion", o.runs, thread_count());
  if (csv) *csv << "stage,scene,width,height,threads,pass,median_ms\n";
  for (const std::string& name : scene_list(o.scenes)) {
    const Scene scene = load_scene(name);
    // Mid-sequence of the first second, so animated scenes are caught moving.
    const int frame = int(scene.fps / 2);
    const ScenePose pose = scene.pose(scene.time_of_frame(frame));
    const ScenePose prev = scene.pose(scene.time_of_frame(frame - 1));
    const View view = make_view(scene, pose, size.width, size.height);
    const View prev_view = make_view(scene, prev, size.width, size.height);
    // Buffers are allocated once and reused, as a renderer does frame after frame; a fresh 720p G-buffer
    // costs more in page faults than the rasterization itself.
    VisibilityBuffer vis(size.width, size.height);
    GBuffer gbuffer(size.width, size.height);
    rasterize_into(scene, pose, view, vis);

    const double vis_ms = median_ms(o.warmup, o.runs, [&] { rasterize_into(scene, pose, view, vis); });
    const double gb_ms = median_ms(o.warmup, o.runs, [&] { resolve_gbuffer_into(scene, pose, view, vis, gbuffer); });
    const double both_ms = median_ms(o.warmup, o.runs, [&] {
      rasterize_into(scene, pose, view, vis);
      resolve_gbuffer_into(scene, pose, view, vis, gbuffer);
    });
    const double mv_ms = median_ms(o.warmup, o.runs, [&] { backproject_motion(scene, prev, prev_view, vis); });
    std::printf("%-10s %4dx%-4d %12.2f %12.2f %12.2f %12.2f\n", name.c_str(), size.width, size.height, vis_ms, gb_ms,
                both_ms, mv_ms);
    if (csv) {
      const std::pair<const char*, double> rows[] = {
          {"visibility", vis_ms}, {"gbuffer", gb_ms}, {"visibility+gbuffer", both_ms}, {"motion", mv_ms}};
      for (const auto& [pass, ms] : rows)
        *csv << "raster," << name << ',' << size.width << ',' << size.height << ',' << thread_count() << ',' << pass
             << ',' << ms << '\n';
    }
  }
}

void run_bench(const BenchOptions& o) {
  const Size size = parse_size(o.size);
  if (o.stage != "raster") throw Error("--stage '" + o.stage + "' is not one of: raster");
  std::ostringstream csv;
  bench_raster(o, size, o.csv.empty() ? nullptr : &csv);
  if (!o.csv.empty()) {
    write_text_file(o.csv, csv.str());
    std::printf("wrote %s\n", o.csv.c_str());
  }
}

}  // namespace

Command add_bench_command(CLI::App& app) {
  auto o = std::make_shared<BenchOptions>();
  CLI::App* sub = app.add_subcommand("bench", "time a stage on the shipped scenes (median after warm-up)");
  sub->add_option("--stage", o->stage, "what to time: raster")->capture_default_str();
  sub->add_option("--size", o->size, "image size WIDTHxHEIGHT")->capture_default_str();
  sub->add_option("--scenes", o->scenes, "comma-separated scene names, or all")->capture_default_str();
  sub->add_option("--runs", o->runs, "timed runs (the median is reported)")->check(CLI::Range(1, 10000))->capture_default_str();
  sub->add_option("--warmup", o->warmup, "untimed runs first")->check(CLI::Range(0, 1000))->capture_default_str();
  sub->add_option("--csv", o->csv, "also write the timings to this CSV file");
  return {sub, [o] { run_bench(*o); }};
}

}  // namespace rtdr
