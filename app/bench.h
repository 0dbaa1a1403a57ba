// Shared pieces of `rtdr bench`: options, the median timer and the scene list. Each stage is one file:
// bench_raster.cpp, bench_trace.cpp, bench_gradients.cpp, bench_motion.cpp, bench_filter.cpp.
#pragma once

#include "app/commands.h"
#include "core/frame.h"
#include "core/progress.h"
#include "gpu/vulkan_context.h"
#include "raster/gbuffer_frame.h"
#include "scenes/scene.h"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <memory>
#include <ostream>
#include <string>
#include <utility>
#include <vector>

namespace rtdr {

struct BenchOptions {
  std::string stage = "raster";
  std::string size = "1280x720";
  std::string scenes = "all";
  int runs = 20;
  int warmup = 3;
  std::string csv;
  std::string method = "svgf";   // --stage filter
  std::string backend = "cpu";   // --stage filter: cpu, vulkan or cpu,vulkan
  int submits = 1;               // --stage filter, vulkan: each frame's batch submitted this often, the last timed
  GradientParams gradient;       // --stage gradients: --gradient-stratum-size 3, ...
  MethodParams params;           // --stage filter: the method's parameters (--atrous-levels 4, --kernel-size 3, ...)
};

// The median of a non-empty set of measurements (the upper one of the middle two for an even count).
inline double median(std::vector<double> values) {
  std::nth_element(values.begin(), values.begin() + ptrdiff_t(values.size() / 2), values.end());
  return values[values.size() / 2];
}

// Median wall time in milliseconds of `runs` calls of fn, after `warmup` untimed calls; each call advances `bar`
// (when given) by one.
template <class Fn>
double median_ms(int warmup, int runs, Fn&& fn, ProgressBar* bar = nullptr) {
  for (int i = 0; i < warmup; ++i) {
    fn();
    if (bar) bar->advance();
  }
  std::vector<double> ms;
  for (int i = 0; i < runs; ++i) {
    const auto t0 = std::chrono::steady_clock::now();
    fn();
    ms.push_back(std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count());
    if (bar) bar->advance();
  }
  return median(ms);
}

// The median device time (ComputeBatch timestamps, a port's `ms` out-parameter) of `runs` calls of run(double* ms),
// after `warmup` untimed ones (at least one: lavapipe compiles the shader on the first); likewise with `bar`.
template <class Run>
double median_device_ms(int warmup, int runs, Run&& run, ProgressBar* bar = nullptr) {
  for (int i = 0; i < std::max(1, warmup); ++i) {
    run(nullptr);
    if (bar) bar->advance();
  }
  std::vector<double> ms;
  for (int i = 0; i < runs; ++i) {
    double t = 0.0;
    run(&t);
    ms.push_back(t);
    if (bar) bar->advance();
  }
  return median(ms);
}

// The calls median_ms and median_device_ms make per measurement: what a stage's ProgressBar counts.
inline uint64_t calls_per_measurement(const BenchOptions& o, bool device = false) {
  return uint64_t(device ? std::max(1, o.warmup) : o.warmup) + uint64_t(o.runs);
}

// A table on stdout whose header and rows are formatted with the same widths, so that they cannot drift apart:
// the first column (the scene or the pass) left-aligned and as wide as its longest cell, every other one
// right-aligned to the wider of its name and `width`. Each row is flushed, so a pipe sees it at once.
class BenchTable {
 public:
  // `first`: the first column's name and every cell it will hold (the scene names); then (name, width) pairs.
  BenchTable(const std::string& first, const std::vector<std::string>& cells,
             std::vector<std::pair<std::string, int>> columns);
  void header(const std::string& note = "") const;  // the names, then `note` (the runs and threads)
  void row(const std::string& first, const std::vector<std::string>& cells) const;

 private:
  std::string first_;
  int first_width_;
  std::vector<std::pair<std::string, int>> columns_;
};
// printf into a string: a cell of a BenchTable.
std::string cell(const char* format, ...) __attribute__((format(printf, 1, 2)));

// The render side's stages (gradients, motion): the device their ports run on when --backend names vulkan, after
// printing it and that `columns` are the ports' device times; null for --backend cpu.
std::unique_ptr<VulkanContext> bench_ports_context(const BenchOptions& o, const std::string& columns);

// "all" or a comma-separated list of scene names.
std::vector<std::string> bench_scene_list(const std::string& text);

// The frame a stage times on: the scene's frame at t = 1/2 s, its geometry, and its G-buffer and motion layers
// (what trace_layers adds to).
struct BenchFrame {
  FrameGeometry geometry;
  Frame frame;
};
BenchFrame bench_frame(const Scene& scene, Size size);

// One stage: prints a table on stdout and, when csv is set, appends rows "stage,scene,...,metric,value".
void bench_raster(const BenchOptions& o, Size size, std::ostream* csv);
void bench_trace(const BenchOptions& o, Size size, std::ostream* csv);
void bench_filter(const BenchOptions& o, Size size, std::ostream* csv);
void bench_gradients(const BenchOptions& o, Size size, std::ostream* csv);
void bench_motion(const BenchOptions& o, Size size, std::ostream* csv);

}  // namespace rtdr
