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
// (gpu/motion_shadow_gpu.h, gpu/trmv_splat_gpu.h), the dual vector (gpu/motion_dual_gpu.h) and the glossy vector (gpu/motion_glossy_gpu.h),
// the median of their dispatches' timestamps over the same runs, beside the CPU columns. A vk column is the shader's
// dispatch alone: not the packing, upload or readback, nor the dual port's host part (the previous frame's
// rasterization and every sample's object point, which the dual ms column includes).
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
                            const RenderSettings& settings, Frame& frame) {
  for (int i = 0; i < o.warmup; ++i) trace_layers(scene, g, settings, frame);
  std::vector<double> seconds;
  for (int i = 0; i < o.runs; ++i) seconds.push_back(trace_layers(scene, g, settings, frame).seconds);
  return 1e3 * median(seconds);
}

}  // namespace

void bench_motion(const BenchOptions& o, const Size size, std::ostream* csv) {
  // The ports' device, with --backend vulkan.
  const std::unique_ptr<VulkanContext> context = bench_ports_context(o, "the vk columns are");
  std::printf("%-14s %9s %9s %10s %9s %9s", "scene", "size", "trace ms", "+shading", "shadow ms", "splat ms");
  if (context) std::printf(" %9s %9s", "shadow vk", "splat vk");
  std::printf(" %9s %9s", "dual ms", "glossy ms");
  if (context) std::printf(" %9s %9s", "dual vk", "glossy vk");
  std::printf(" %7s %11s %8s   (median of %d runs, %d threads)\n", "share", "of +shading", "valid", o.runs,
              thread_count());
  const RenderSettings settings;  // 1 spp, seed 0
  RenderSettings trmv_settings;   // and TRMV's input: with the shading term
  trmv_settings.trace.shading_samples = kTrmvShadingSamples;
  for (const std::string& name : bench_scene_list(o.scenes)) {
    const Scene scene = load_scene(name);
    BenchFrame b = bench_frame(scene, size);
    const FrameGeometry& g = b.geometry;
    Frame& frame = b.frame;
    const double trace_ms = median_trace_loop_ms(o, scene, g, settings, frame);
    const double trmv_trace_ms = median_trace_loop_ms(o, scene, g, trmv_settings, frame);
    std::vector<ShadowMotion> shadow;
    const double shadow_ms = median_ms(o.warmup, o.runs, [&] { shadow = shadow_motion(g, frame); });
    const std::vector<glm::vec2> surface = frame.get_vec2("motion");
    // The splat over the shadow filter's window at this size (filters/trmv/footprint.h), on the vectors just made.
    Frame with_shadow = frame;
    write_shadow_motion_layers(g, with_shadow);
    const TrmvSplatPlanes splat_planes =
        trmv_splat_planes(with_shadow, SurfacePlanes::from_frame(with_shadow), FloatPlane());
    const int splat_size = trmv_windows(TrmvParams{}, size.height).splat_size;
    const double splat_ms = median_ms(o.warmup, o.runs, [&] { trmv_splat_pass(splat_planes, splat_size); });
    // The Vulkan ports on the same frame and vectors (device time only: packing and readback are not counted).
    double shadow_vulkan_ms = 0.0, splat_vulkan_ms = 0.0;
    if (context) {
      shadow_vulkan_ms =
          median_device_ms(o.warmup, o.runs, [&](double* ms) { shadow_motion_vulkan(*context, g, frame, ms); });
      splat_vulkan_ms = median_device_ms(o.warmup, o.runs,
                                         [&](double* ms) { trmv_splat_vulkan(*context, splat_planes, splat_size, ms); });
    }
    const double dual_ms = median_ms(o.warmup, o.runs, [&] { dual_motion(scene, g, surface); });
    const double glossy_ms = median_ms(o.warmup, o.runs, [&] { glossy_motion(g, frame); });
    // Their ports' device time (the dual port's host part, previous_visibility and object_point, not counted).
    double dual_vulkan_ms = 0.0, glossy_vulkan_ms = 0.0;
    if (context) {
      dual_vulkan_ms = median_device_ms(o.warmup, o.runs,
                                        [&](double* ms) { dual_motion_vulkan(*context, scene, g, surface, ms); });
      glossy_vulkan_ms =
          median_device_ms(o.warmup, o.runs, [&](double* ms) { glossy_motion_vulkan(*context, g, frame, ms); });
    }
    size_t valid = 0;
    for (const ShadowMotion& m : shadow) valid += m.valid;
    const double vectors_ms = shadow_ms + splat_ms + dual_ms + glossy_ms;
    const double share = vectors_ms / trace_ms, valid_share = double(valid) / double(shadow.size());
    const double trmv_share = vectors_ms / trmv_trace_ms;
    std::printf("%-14s %4dx%-4d %9.1f %9.1f %9.2f %9.2f", name.c_str(), size.width, size.height, trace_ms,
                trmv_trace_ms, shadow_ms, splat_ms);
    if (context) std::printf(" %9.3f %9.3f", shadow_vulkan_ms, splat_vulkan_ms);
    std::printf(" %9.2f %9.2f", dual_ms, glossy_ms);
    if (context) std::printf(" %9.3f %9.3f", dual_vulkan_ms, glossy_vulkan_ms);
    std::printf(" %6.1f%% %10.1f%% %7.1f%%\n", 100.0 * share, 100.0 * trmv_share, 100.0 * valid_share);
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
