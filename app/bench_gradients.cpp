// rtdr bench --stage gradients: what A-SVGF's gradient samples add to a 1-spp frame (trace/gradients.h), per
// shipped scene at --size: the median time of a plain frame (render_frame) and of the same frame with its
// gradient samples from the frame before (render_frame_with_gradients: selection, forward projection, merge,
// and the re-shading, which replaces a pixel's shading rather than adding one), and the ratio. Target: at most
// 10% over the plain frame. Also the share of pixels that are gradient samples (at most 1/9 with 3x3 strata).
// With --backend vulkan (or cpu,vulkan), also the two integer steps of the samples [ASVGF18 Sec. 3.3] alone: the
// selection of a source pixel per stratum (step 2, select_gradient_source at every stratum) and the merge of the
// candidates that survive forward projection into one per stratum of the frame (step 5, gradient_winners), each
// on the CPU (wall time, the selection over parallel stratum rows) and as its Vulkan port (gpu/gradient_select_gpu.h,
// the median of its dispatches' timestamps over the same runs).
#include "app/backend.h"
#include "app/bench.h"
#include "core/parallel.h"
#include "gpu/gradient_select_gpu.h"
#include "scenes/gltf_loader.h"
#include "trace/gradients.h"

#include <malloc.h>

#include <algorithm>
#include <cstdio>
#include <memory>

namespace rtdr {
namespace {

// Steps 2 and 5 of frame f's gradient samples [ASVGF18 Sec. 3.3], timed on the CPU and as the Vulkan ports.
struct StepTimes {
  double select_ms = 0.0, merge_ms = 0.0, select_vulkan_ms = 0.0, merge_vulkan_ms = 0.0;
};

StepTimes time_steps(const BenchOptions& o, VulkanContext& context, const Scene& scene, const Frame& prev, int f,
                     Size size, uint32_t seed, ProgressBar* bar) {
  const PreviousFrame previous = PreviousFrame::from_frame(prev);
  const FrameGeometry current = rasterize_frame(scene, f, size.width, size.height);
  const int s = o.gradient.stratum_size;
  const int strata_x = (size.width + s - 1) / s, strata_y = (size.height + s - 1) / s;
  StepTimes t;
  // Step 2 as gradient_samples runs it, stratum rows in parallel.
  std::vector<uint32_t> sources(size_t(strata_x) * size_t(strata_y));
  t.select_ms = median_ms(
      o.warmup, o.runs,
      [&] {
        parallel_rows(strata_y, [&](int sy) {
          for (int sx = 0; sx < strata_x; ++sx)
            sources[size_t(sy) * size_t(strata_x) + size_t(sx)] =
                select_gradient_source(previous, sx, sy, o.gradient, seed, f);
        });
      },
      bar);
  t.select_vulkan_ms = median_device_ms(
      o.warmup, o.runs,
      [&](double* ms) { select_gradient_sources_vulkan(context, previous, o.gradient, seed, f, ms); }, bar);
  // Step 5 on the candidates of steps 2-4.
  const std::vector<GradientCandidate> candidates =
      candidate_list(gradient_candidates(scene, current, previous, o.gradient, seed));
  t.merge_ms = median_ms(o.warmup, o.runs, [&] { gradient_winners(candidates, s, strata_x, strata_y); }, bar);
  t.merge_vulkan_ms = median_device_ms(
      o.warmup, o.runs,
      [&](double* ms) { gradient_winners_vulkan(context, candidates, size.width, size.height, s, ms); }, bar);
  return t;
}

}  // namespace

void bench_gradients(const BenchOptions& o, const Size size, std::ostream* csv) {
  // Each run builds a new frame of some 200 MB at 720p and drops the last one. By default glibc hands such blocks
  // back to the kernel and faults them in again, which costs more than the gradient samples and varies from run to
  // run by a factor of three. Keep freed memory in the process, so that both columns time the rendering.
  mallopt(M_MMAP_THRESHOLD, 1 << 30);
  mallopt(M_TRIM_THRESHOLD, 1 << 30);
  // The ports' device, with --backend vulkan.
  const std::unique_ptr<VulkanContext> context = bench_ports_context(o, "select vk and merge vk are");
  std::vector<std::pair<std::string, int>> columns = {
      {"size", 9}, {"plain ms", 10}, {"gradients ms", 14}, {"ratio", 7}, {"gradients", 10}};
  if (context) columns.insert(columns.end(), {{"select ms", 9}, {"select vk", 9}, {"merge ms", 9}, {"merge vk", 9}});
  const std::vector<std::string> scenes = bench_scene_list(o.scenes);
  const BenchTable table("scene", scenes, columns);
  table.header(cell("(median of %d runs, %d threads, strata of %d)", o.runs, thread_count(), o.gradient.stratum_size));
  const RenderSettings settings;  // 1 spp, seed 0: what A-SVGF gets
  for (const std::string& name : scenes) {
    const Scene scene = load_scene(name);
    const int f = int(scene.fps / 2);
    const Frame prev = render_frame_with_gradients(scene, f - 1, size.width, size.height, settings, o.gradient, nullptr);
    Frame plain, frame;
    double plain_ms = 0.0, gradient_ms = 0.0;
    StepTimes steps;
    {  // the bar's line ends before the row is printed
      ProgressBar bar("bench gradients " + name,
                      2 * calls_per_measurement(o) + (context ? 2 * calls_per_measurement(o, true) +
                                                                    2 * calls_per_measurement(o) : 0));
      plain_ms =
          median_ms(o.warmup, o.runs, [&] { plain = render_frame(scene, f, size.width, size.height, settings); }, &bar);
      gradient_ms = median_ms(
          o.warmup, o.runs,
          [&] { frame = render_frame_with_gradients(scene, f, size.width, size.height, settings, o.gradient, &prev); },
          &bar);
      if (context) steps = time_steps(o, *context, scene, prev, f, size, settings.seed, &bar);
    }
    const double share = gradient_sample_share(frame);
    const double ratio = gradient_ms / plain_ms;
    std::vector<std::string> cells = {cell("%dx%d", size.width, size.height), cell("%.1f", plain_ms),
                                      cell("%.1f", gradient_ms), cell("%.3f", ratio), cell("%.2f%%", 100.0 * share)};
    if (context)
      cells.insert(cells.end(), {cell("%.3f", steps.select_ms), cell("%.3f", steps.select_vulkan_ms),
                                 cell("%.3f", steps.merge_ms), cell("%.3f", steps.merge_vulkan_ms)});
    table.row(name, cells);
    if (csv) {
      const std::string row = "gradients," + name + ',' + std::to_string(size.width) + ',' +
                              std::to_string(size.height) + ',' + std::to_string(thread_count()) + ',';
      *csv << row << "plain_ms," << plain_ms << '\n'
           << row << "gradients_ms," << gradient_ms << '\n'
           << row << "ratio," << ratio << '\n'
           << row << "gradient_share," << share << '\n';
      if (context)
        *csv << row << "select_ms," << steps.select_ms << '\n'
             << row << "select_vulkan_ms," << steps.select_vulkan_ms << '\n'
             << row << "merge_ms," << steps.merge_ms << '\n'
             << row << "merge_vulkan_ms," << steps.merge_vulkan_ms << '\n';
    }
  }
}

}  // namespace rtdr
