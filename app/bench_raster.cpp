// rtdr bench --stage raster: visibility buffer, G-buffer resolve and motion back-projection per shipped
// scene (issue target: visibility + G-buffer <= 50 ms at 1280x720 on 2 cores; docs/performance.md).
#include "app/bench.h"
#include "core/parallel.h"
#include "motion/backproject.h"
#include "raster/gbuffer_frame.h"
#include "raster/gbuffer.h"
#include "raster/view.h"
#include "raster/visibility.h"
#include "scenes/gltf_loader.h"

#include <cstdio>

namespace rtdr {

void bench_raster(const BenchOptions& o, const Size size, std::ostream* csv) {
  const std::vector<std::string> scenes = bench_scene_list(o.scenes);
  const BenchTable table("scene", scenes,
                         {{"size", 9}, {"visibility", 12}, {"gbuffer", 12}, {"vis+gbuffer", 12}, {"motion", 12}});
  table.header(cell("(median ms of %d runs, %d threads)", o.runs, thread_count()));
  for (const std::string& name : scenes) {
    const Scene scene = load_scene(name);
    // Mid-sequence of the first second, so animated scenes are caught moving.
    const FrameGeometry g = rasterize_frame(scene, int(scene.fps / 2), size.width, size.height);
    const ScenePose& pose = g.pose;
    const View& view = g.view;
    // Buffers are allocated once and reused, as a renderer does frame after frame; a fresh 720p G-buffer
    // costs more in page faults than the rasterization itself.
    VisibilityBuffer vis(size.width, size.height);
    GBuffer gbuffer(size.width, size.height);
    rasterize_into(scene, pose, view, vis);

    double vis_ms = 0.0, gb_ms = 0.0, both_ms = 0.0, mv_ms = 0.0;
    {  // the bar's line ends before the row is printed
      ProgressBar bar("bench raster " + name, 4 * calls_per_measurement(o));
      vis_ms = median_ms(o.warmup, o.runs, [&] { rasterize_into(scene, pose, view, vis); }, &bar);
      gb_ms = median_ms(o.warmup, o.runs, [&] { resolve_gbuffer_into(scene, pose, view, vis, gbuffer); }, &bar);
      both_ms = median_ms(
          o.warmup, o.runs,
          [&] {
            rasterize_into(scene, pose, view, vis);
            resolve_gbuffer_into(scene, pose, view, vis, gbuffer);
          },
          &bar);
      mv_ms = median_ms(o.warmup, o.runs, [&] { backproject_motion(scene, g.prev_pose, g.prev_view, vis); }, &bar);
    }
    table.row(name, {cell("%dx%d", size.width, size.height), cell("%.2f", vis_ms), cell("%.2f", gb_ms),
                     cell("%.2f", both_ms), cell("%.2f", mv_ms)});
    if (csv) {
      const std::pair<const char*, double> rows[] = {
          {"visibility", vis_ms}, {"gbuffer", gb_ms}, {"visibility+gbuffer", both_ms}, {"motion", mv_ms}};
      for (const auto& [pass, ms] : rows)
        *csv << "raster," << name << ',' << size.width << ',' << size.height << ',' << thread_count() << ",ms_" << pass
             << ',' << ms << '\n';
    }
  }
}

}  // namespace rtdr
