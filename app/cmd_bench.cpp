// rtdr bench: timings that the test suite never asserts. Each stage is timed as the median of --runs
// runs after --warmup runs, per shipped scene, on as many threads as --threads allows.
//   --stage raster: visibility buffer, G-buffer resolve and motion back-projection (bench_raster.cpp)
//   --stage trace:  the path tracer at 1 spp, its rays per second against a bare Embree loop over the same
//                   rays, and the memory of a frame's planes (bench_trace.cpp)
//   --stage gradients: a 1-spp frame with and without A-SVGF's gradient samples, and with --backend vulkan the
//                   ports of their selection and merge (bench_gradients.cpp)
//   --stage motion: TRMV's motion vectors (shadow, splat, dual, glossy) beside a 1-spp frame's tracing, and with
//                   --backend vulkan their ports (bench_motion.cpp)
//   --stage filter: a denoising method per pass on a rendered sequence, on each --backend (bench_filter.cpp); the
//                   default stage when --backend is given
#include "app/backend.h"
#include "app/bench.h"
#include "core/atomic_file.h"
#include "core/error.h"
#include "eval/run_memory.h"
#include "motion/backproject.h"
#include "scenes/catalog.h"
#include "scenes/gltf_loader.h"

#include <algorithm>
#include <cstdarg>
#include <cstdio>
#include <memory>
#include <sstream>

namespace rtdr {

std::unique_ptr<VulkanContext> bench_ports_context(const BenchOptions& o, const std::string& columns) {
  const std::vector<std::string> backends = parse_backends(o.backend);
  if (std::find(backends.begin(), backends.end(), "vulkan") == backends.end()) return nullptr;
  auto context = std::make_unique<VulkanContext>();
  std::printf("vulkan device %s (%s, %s-buffer inputs): %s the ports' device times\n", context->device_name().c_str(),
              context->memory_summary().c_str(), shader_inputs_name(context->shader_inputs()), columns.c_str());
  return context;
}

std::vector<std::string> bench_scene_list(const std::string& text) {
  if (text == "all") return shipped_scene_names();
  std::vector<std::string> names;
  std::stringstream ss(text);
  for (std::string name; std::getline(ss, name, ',');)
    if (!name.empty()) names.push_back(name);
  return names;
}

BenchTable::BenchTable(const std::string& first, const std::vector<std::string>& cells,
                       std::vector<std::pair<std::string, int>> columns)
    : first_(first), first_width_(int(first.size())), columns_(std::move(columns)) {
  for (const std::string& c : cells) first_width_ = std::max(first_width_, int(c.size()));
  for (auto& [name, width] : columns_) width = std::max(width, int(name.size()));
}

void BenchTable::header(const std::string& note) const {
  std::printf("%-*s", first_width_, first_.c_str());
  for (const auto& [name, width] : columns_) std::printf(" %*s", width, name.c_str());
  std::printf("%s%s\n", note.empty() ? "" : "   ", note.c_str());
  std::fflush(stdout);
}

void BenchTable::row(const std::string& first, const std::vector<std::string>& cells) const {
  std::printf("%-*s", first_width_, first.c_str());
  for (size_t c = 0; c < cells.size() && c < columns_.size(); ++c)
    std::printf(" %*s", columns_[c].second, cells[c].c_str());
  std::printf("\n");
  std::fflush(stdout);
}

std::string cell(const char* format, ...) {
  char text[64];
  va_list args;
  va_start(args, format);
  std::vsnprintf(text, sizeof text, format, args);
  va_end(args);
  return text;
}

BenchFrame bench_frame(const Scene& scene, Size size) {
  BenchFrame b{rasterize_frame(scene, int(scene.fps / 2), size.width, size.height), Frame(size.width, size.height)};
  write_gbuffer_layers(scene, b.geometry, b.frame);
  write_motion_layers(scene, b.geometry, b.frame);
  return b;
}

namespace {

// What the stage will hold at --size, against the memory there is (eval/run_memory.h), before any work: the
// frames it keeps (bench_filter.cpp renders its whole sequence first), counted on the first scene's frame (every
// scene's frames have the same layers).
void require_bench_fits(const BenchOptions& o, Size size) {
  const std::vector<std::string> scenes = bench_scene_list(o.scenes);
  if (scenes.empty()) return;
  const Scene scene = load_scene(scenes.front());
  const bool filter = o.stage == "filter";
  const std::unique_ptr<Method> method = filter ? make_method(o.method, o.params) : nullptr;
  RenderSettings settings;
  if (method && method->reads_shading_term()) settings.trace.shading_samples = kTrmvShadingSamples;
  const bool gradients = o.stage == "gradients" || (method && method->reads_gradient_samples());
  const int frames = filter ? std::max(5, o.warmup) + o.runs : gradients ? 3 : 2;
  require_run_fits("bench --stage " + o.stage, size.width, size.height,
                   bench_planes(rendered_frame_planes(scene, settings, gradients), frames,
                                method ? method_planes(*method) : 0),
                   memory_budget());
}

void run_bench(const BenchOptions& o) {
  const Size size = parse_size(o.size);
  require_bench_fits(o, size);
  std::ostringstream csv;
  std::ostream* csv_out = o.csv.empty() ? nullptr : &csv;
  if (csv_out) csv << "stage,scene,width,height,threads,metric,value\n";
  if (o.stage == "raster")
    bench_raster(o, size, csv_out);
  else if (o.stage == "trace")
    bench_trace(o, size, csv_out);
  else if (o.stage == "filter")
    bench_filter(o, size, csv_out);
  else if (o.stage == "gradients")
    bench_gradients(o, size, csv_out);
  else if (o.stage == "motion")
    bench_motion(o, size, csv_out);
  else
    throw Error("--stage '" + o.stage + "' is not one of: raster, trace, gradients, motion, filter");
  if (!o.csv.empty()) {
    write_text_file(o.csv, csv.str());
    std::printf("wrote %s\n", o.csv.c_str());
  }
}

}  // namespace

Command add_bench_command(CLI::App& app) {
  auto o = std::make_shared<BenchOptions>();
  CLI::App* sub = app.add_subcommand("bench", "time a stage on the shipped scenes (median after warm-up)");
  sub->add_option("--stage", o->stage, "what to time: raster, trace, gradients, motion, filter")->capture_default_str();
  sub->add_option("--size", o->size, "image size WIDTHxHEIGHT; refused when the run would not fit in the memory available")
      ->capture_default_str();
  sub->add_option("--scenes", o->scenes, "comma-separated scene names, or all")->capture_default_str();
  sub->add_option("--runs", o->runs, "timed runs (the median is reported)")->check(CLI::Range(1, 10000))->capture_default_str();
  sub->add_option("--warmup", o->warmup, "untimed runs first")->check(CLI::Range(0, 1000))->capture_default_str();
  sub->add_option("--csv", o->csv, "also write the timings to this CSV file");
  sub->add_option("--method", o->method, "the method --stage filter times (see rtdr filter)")->capture_default_str();
  sub->add_option("--backend", o->backend,
                  "--stage filter, gradients, motion: cpu, vulkan, or cpu,vulkan to compare them (gradients and "
                  "motion: the CPU columns always, the ports' columns with vulkan)")
      ->capture_default_str();
  sub->add_option("--submits", o->submits,
                  "--backend vulkan: submit each frame's work this many times back to back and time the last, so a "
                  "GPU runs at its working clock rather than idling while the host packs the next frame")
      ->check(CLI::Range(1, 1000))
      ->capture_default_str();
  add_method_flags(sub, o->params, o->method);  // --stage filter
  add_gradient_flags(sub, o->gradient);  // --stage gradients
  return {sub, [o, sub] {
            // --backend alone means the filter stage, on pillars, 5 runs (a 1080p CPU frame takes seconds).
            if (sub->count("--backend") > 0 && sub->count("--stage") == 0) o->stage = "filter";
            if (o->stage == "filter" && sub->count("--scenes") == 0) o->scenes = "pillars";
            if (o->stage == "filter" && sub->count("--runs") == 0) o->runs = 5;
            run_bench(*o);
          }};
}

}  // namespace rtdr
