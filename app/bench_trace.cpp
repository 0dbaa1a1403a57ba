// rtdr bench --stage trace: the path tracer at 1 spp per shipped scene.
//   - the frame time of trace_layers at --size (G-buffer excluded), median of --runs, and of its tracing
//     loop alone (without the BVH build and the copy of the outputs into the frame's planes);
//   - the loop's rays per second, against a bare Embree loop that casts the very same rays (recorded from one
//     trace) with rtcIntersect1 / rtcOccluded1 and nothing else, in the same run: the ratio says how much
//     of the tracer's time is spent outside Embree (issue target: ratio >= 0.5);
//   - the memory of one frame's planes as written to EXR.
#include "app/bench.h"
#include "core/parallel.h"
#include "eval/run_memory.h"
#include "raster/gbuffer_frame.h"
#include "scenes/gltf_loader.h"
#include "trace/render_frame.h"
#include "core/sampler.h"

#include <cstdio>

namespace rtdr {
namespace {

// The rays one 1-spp trace of the frame casts, per row (so both loops split the work the same way).
std::vector<std::vector<LoggedRay>> record_rays(const Scene& scene, const FrameGeometry& g, const RenderSettings& settings,
                                                const EmbreeScene& embree, const LightSet& lights,
                                                const SurfaceTable& surfaces) {
  std::vector<std::vector<LoggedRay>> rows(size_t(g.vis.height));
  parallel_rows(g.vis.height, [&](int y) {
    TraceContext context{scene, g.pose, embree, lights, surfaces, settings.trace, &rows[size_t(y)]};
    for (int x = 0; x < g.vis.width; ++x) {
      const SurfaceSample s = g.vis.sample(x, y);
      if (s.valid()) trace_path(context, s, g.view.eye, pixel_seed(settings.seed, g.index, x, y), 0);
    }
  });
  return rows;
}

// Casts every recorded ray with Embree's own single-ray calls, as a minimal renderer would.
void cast_bare(const EmbreeScene& embree, const std::vector<std::vector<LoggedRay>>& rows) {
  parallel_rows(int(rows.size()), [&](int y) {
    for (const LoggedRay& r : rows[size_t(y)]) {
      if (r.any_hit)
        embree.occluded(r.ray, 0.0f, r.tfar);
      else
        embree.intersect(r.ray, 0.0f, r.tfar);
    }
  });
}

}  // namespace

void bench_trace(const BenchOptions& o, const Size size, std::ostream* csv) {
  const std::vector<std::string> scenes = bench_scene_list(o.scenes);
  const BenchTable table("scene", scenes,
                         {{"size", 9}, {"frame ms", 9}, {"loop ms", 9}, {"Mrays", 9}, {"tracer Mr/s", 12},
                          {"bare Mr/s", 12}, {"ratio", 7}, {"frame MB", 9}, {"layers", 8}});
  table.header(cell("(median of %d runs, %d threads)", o.runs, thread_count()));
  const RenderSettings settings;  // 1 spp, seed 0, one indirect bounce: what a denoiser gets
  for (const std::string& name : scenes) {
    const Scene scene = load_scene(name);
    BenchFrame b = bench_frame(scene, size);
    const FrameGeometry& g = b.geometry;
    Frame& frame = b.frame;
    // The frame time (BVH build, tracing, writing the layers) and, inside it, the tracing loop alone.
    std::vector<double> loop_seconds;
    TraceStats stats;
    double trace_ms = 0.0, bare_ms = 0.0;
    {  // the bar's line ends before the row is printed
      ProgressBar bar("bench trace " + name, 2 * calls_per_measurement(o));
      trace_ms = median_ms(
          o.warmup, o.runs,
          [&] {
            stats = trace_layers(scene, g, settings, frame);
            loop_seconds.push_back(stats.seconds);
          },
          &bar);
      const EmbreeScene embree(scene, g.pose);
      const LightSet lights(scene, g.pose);
      const SurfaceTable surfaces(scene, g.pose);
      const auto rays = record_rays(scene, g, settings, embree, lights, surfaces);
      bare_ms = median_ms(o.warmup, o.runs, [&] { cast_bare(embree, rays); }, &bar);
    }
    const double loop_ms = 1e3 * median(loop_seconds);

    // Both rates count the same rays: the tracing loop (shading, sampling, ray casts) against the casts alone.
    const double tracer_rate = double(stats.rays) / (1e-3 * loop_ms);
    const double bare_rate = double(stats.rays) / (1e-3 * bare_ms);
    const double mb = double(frame_bytes(frame)) / (1024.0 * 1024.0);
    const size_t layers = frame.float_channels().size() + frame.uint_channels().size();
    table.row(name, {cell("%dx%d", size.width, size.height), cell("%.2f", trace_ms), cell("%.2f", loop_ms),
                     cell("%.3f", 1e-6 * double(stats.rays)), cell("%.2f", 1e-6 * tracer_rate),
                     cell("%.2f", 1e-6 * bare_rate), cell("%.2f", tracer_rate / bare_rate), cell("%.1f", mb),
                     cell("%zu", layers)});
    if (csv) {
      const std::pair<const char*, double> rows[] = {{"ms_frame", trace_ms},           {"ms_trace_loop", loop_ms},    {"ms_bare_embree", bare_ms},
                                                     {"rays", double(stats.rays)},      {"tracer_rays_per_s", tracer_rate},
                                                     {"bare_rays_per_s", bare_rate},    {"ratio", tracer_rate / bare_rate},
                                                     {"frame_bytes", double(frame_bytes(frame))},
                                                     {"frame_planes", double(layers)}};
      for (const auto& [metric, value] : rows)
        *csv << "trace," << name << ',' << size.width << ',' << size.height << ',' << thread_count() << ',' << metric
             << ',' << value << '\n';
    }
  }
}

}  // namespace rtdr
