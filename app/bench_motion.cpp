// rtdr bench --stage motion: what TRMV's motion vectors add to a 1-spp frame, per shipped scene at --size: the
// median time of the shadow vector [TRMV21 Eq. 3] over every pixel (motion/shadow.h, from the frame's path record),
// of its splat [TRMV21 Sec. 4.1] (filters/trmv/splat.h, the filter's, at the shadow filter's window for --size), of
// the dual vector [TRMV21 Eq. 6] (motion/dual.h, the
// previous frame's rasterization included) and of the glossy vector [TRMV21 Eq. 5] (motion/glossy.h), beside the
// 1-spp frame's tracing loop
// (trace_layers' own time, TraceStats::seconds), and their sum as a share of it; and the same share of TRMV's own
// input frame, which also traces the shading term direct.shading (kTrmvShadingSamples light samples a pixel,
// trace/shading.h). Target: at most 5 % (the paper's vectors cost under 0.23 ms on a GPU [TRMV21 Fig. 13], inside
// its ray-generation shader). Also the share of pixels with a valid shadow vector.
// With --backend vulkan (or cpu,vulkan), also the device time of the Vulkan ports of the shadow vector, its splat
// (gpu/motion_shadow_gpu.h, gpu/trmv_splat_gpu.h), the dual vector (gpu/motion_dual_gpu.h) and the glossy vector
// (gpu/motion_glossy_gpu.h), the median of their dispatches' timestamps over the same runs, beside the CPU columns.
// A vk column is the shader's dispatch alone: not the packing, upload or readback, nor the dual port's host part
// (the previous frame's rasterization and every sample's object point, which the dual ms column includes).
#include "app/backend.h"
#include "app/bench.h"
#include "core/parallel.h"
#include "filters/surface_planes.h"
#include "filters/trmv/footprint.h"
#include "filters/trmv/trmv.h"
#include "gpu/motion_dual_gpu.h"
#include "gpu/motion_glossy_gpu.h"
#include "gpu/motion_shadow_gpu.h"
#include "gpu/trmv_splat_gpu.h"
#include "motion/dual.h"
#include "motion/glossy.h"
#include "motion/shadow.h"
#include "scenes/gltf_loader.h"
#include "trace/render_frame.h"

#include <algorithm>
#include <cstdio>
#include <memory>

namespace rtdr {
namespace {

// The median of trace_layers' own tracing time (TraceStats::seconds) over o.runs runs, after o.warmup untimed ones.
double median_trace_loop_ms(const BenchOptions& o, const Scene& scene, const FrameGeometry& g,
                            const RenderSettings& settings, Frame& frame, ProgressBar& bar) {
  for (int i = 0; i < o.warmup; ++i) {
    trace_layers(scene, g, settings, frame);
    bar.advance();
  }
  std::vector<double> seconds;
  for (int i = 0; i < o.runs; ++i) {
    seconds.push_back(trace_layers(scene, g, settings, frame).seconds);
    bar.advance();
  }
  return 1e3 * median(seconds);
}

// The medians of one scene (milliseconds; the vk ones are device times, 0 without --backend vulkan).
struct MotionTimes {
  double trace = 0, trace_shading = 0, shadow = 0, splat = 0, dual = 0, glossy = 0;
  double shadow_vk = 0, splat_vk = 0, dual_vk = 0, glossy_vk = 0;
  double valid_share = 0;  // the share of pixels with a valid shadow vector
};

MotionTimes time_motion(const BenchOptions& o, VulkanContext* context, const Scene& scene, Size size,
                        const std::string& name) {
  const RenderSettings settings;  // 1 spp, seed 0
  RenderSettings trmv_settings;   // and TRMV's input: with the shading term
  trmv_settings.trace.shading_samples = kTrmvShadingSamples;
  BenchFrame b = bench_frame(scene, size);
  const FrameGeometry& g = b.geometry;
  Frame& frame = b.frame;
  MotionTimes t;
  ProgressBar bar("bench motion " + name,
                  6 * calls_per_measurement(o) + (context ? 4 * calls_per_measurement(o, true) : 0));
  t.trace = median_trace_loop_ms(o, scene, g, settings, frame, bar);
  t.trace_shading = median_trace_loop_ms(o, scene, g, trmv_settings, frame, bar);
  std::vector<ShadowMotion> shadow;
  t.shadow = median_ms(o.warmup, o.runs, [&] { shadow = shadow_motion(g, frame); }, &bar);
  const std::vector<glm::vec2> surface = frame.get_vec2("motion");
  // The splat over the shadow filter's window at this size (filters/trmv/footprint.h), on the vectors just made.
  Frame with_shadow = frame;
  write_shadow_motion_layers(g, with_shadow);
  const TrmvSplatPlanes splat_planes =
      trmv_splat_planes(with_shadow, SurfacePlanes::from_frame(with_shadow), FloatPlane());
  const int splat_size = trmv_windows(TrmvParams{}, size.height).splat_size;
  t.splat = median_ms(o.warmup, o.runs, [&] { trmv_splat_pass(splat_planes, splat_size); }, &bar);
  t.dual = median_ms(o.warmup, o.runs, [&] { dual_motion(scene, g, surface); }, &bar);
  t.glossy = median_ms(o.warmup, o.runs, [&] { glossy_motion(g, frame); }, &bar);
  // The Vulkan ports on the same frame and vectors (device time only: packing and readback are not counted, nor the
  // dual port's host part, previous_visibility and object_point).
  if (context) {
    t.shadow_vk =
        median_device_ms(o.warmup, o.runs, [&](double* ms) { shadow_motion_vulkan(*context, g, frame, ms); }, &bar);
    t.splat_vk = median_device_ms(
        o.warmup, o.runs, [&](double* ms) { trmv_splat_vulkan(*context, splat_planes, splat_size, ms); }, &bar);
    t.dual_vk = median_device_ms(
        o.warmup, o.runs, [&](double* ms) { dual_motion_vulkan(*context, scene, g, surface, ms); }, &bar);
    t.glossy_vk =
        median_device_ms(o.warmup, o.runs, [&](double* ms) { glossy_motion_vulkan(*context, g, frame, ms); }, &bar);
  }
  size_t valid = 0;
  for (const ShadowMotion& m : shadow) valid += m.valid;
  t.valid_share = double(valid) / double(shadow.size());
  return t;
}

}  // namespace

void bench_motion(const BenchOptions& o, const Size size, std::ostream* csv) {
  // The ports' device, with --backend vulkan.
  const std::unique_ptr<VulkanContext> context = bench_ports_context(o, "the vk columns are");
  std::vector<std::pair<std::string, int>> columns = {
      {"size", 9}, {"trace ms", 9}, {"+shading", 9}, {"shadow ms", 9}, {"splat ms", 9}};
  if (context) columns.insert(columns.end(), {{"shadow vk", 9}, {"splat vk", 9}});
  columns.insert(columns.end(), {{"dual ms", 9}, {"glossy ms", 9}});
  if (context) columns.insert(columns.end(), {{"dual vk", 9}, {"glossy vk", 9}});
  columns.insert(columns.end(), {{"share", 7}, {"of +shading", 11}, {"valid", 8}});
  const std::vector<std::string> scenes = bench_scene_list(o.scenes);
  const BenchTable table("scene", scenes, columns);
  table.header(cell("(median of %d runs, %d threads)", o.runs, thread_count()));
  for (const std::string& name : scenes) {
    const Scene scene = load_scene(name);
    const MotionTimes t = time_motion(o, context.get(), scene, size, name);  // its bar ends before the row
    const double trace_ms = t.trace, trmv_trace_ms = t.trace_shading, shadow_ms = t.shadow, splat_ms = t.splat;
    const double dual_ms = t.dual, glossy_ms = t.glossy, valid_share = t.valid_share;
    const double shadow_vulkan_ms = t.shadow_vk, splat_vulkan_ms = t.splat_vk, dual_vulkan_ms = t.dual_vk,
                 glossy_vulkan_ms = t.glossy_vk;
    const double vectors_ms = shadow_ms + splat_ms + dual_ms + glossy_ms;
    const double share = vectors_ms / trace_ms;
    const double trmv_share = vectors_ms / trmv_trace_ms;
    std::vector<std::string> cells = {cell("%dx%d", size.width, size.height), cell("%.1f", trace_ms),
                                      cell("%.1f", trmv_trace_ms), cell("%.2f", shadow_ms), cell("%.2f", splat_ms)};
    if (context) cells.insert(cells.end(), {cell("%.3f", shadow_vulkan_ms), cell("%.3f", splat_vulkan_ms)});
    cells.insert(cells.end(), {cell("%.2f", dual_ms), cell("%.2f", glossy_ms)});
    if (context) cells.insert(cells.end(), {cell("%.3f", dual_vulkan_ms), cell("%.3f", glossy_vulkan_ms)});
    cells.insert(cells.end(), {cell("%.1f%%", 100.0 * share), cell("%.1f%%", 100.0 * trmv_share),
                               cell("%.1f%%", 100.0 * valid_share)});
    table.row(name, cells);
    if (csv) {
      const std::string row = "motion," + name + ',' + std::to_string(size.width) + ',' +
                              std::to_string(size.height) + ',' + std::to_string(thread_count()) + ',';
      *csv << row << "trace_ms," << trace_ms << '\n'
           << row << "trace_with_shading_ms," << trmv_trace_ms << '\n'
           << row << "share_with_shading," << trmv_share << '\n'
           << row << "shadow_ms," << shadow_ms << '\n'
           << row << "splat_ms," << splat_ms << '\n'
           << row << "dual_ms," << dual_ms << '\n'
           << row << "glossy_ms," << glossy_ms << '\n'
           << row << "share," << share << '\n'
           << row << "valid_share," << valid_share << '\n';
      if (context)
        *csv << row << "shadow_vulkan_ms," << shadow_vulkan_ms << '\n'
             << row << "splat_vulkan_ms," << splat_vulkan_ms << '\n'
             << row << "dual_vulkan_ms," << dual_vulkan_ms << '\n'
             << row << "glossy_vulkan_ms," << glossy_vulkan_ms << '\n';
    }
  }
}

}  // namespace rtdr
