// rtdr bench --stage gradients: what A-SVGF's gradient samples add to a 1-spp frame (trace/gradients.h), per
// shipped scene at --size: the median time of a plain frame (render_frame) and of the same frame with its
// gradient samples from the frame before (render_frame_with_gradients: selection, forward projection, merge,
// and the re-shading, which replaces a pixel's shading rather than adding one), and the ratio. Target: at most
// 10% over the plain frame. Also the share of pixels that are gradient samples (at most 1/9 with 3x3 strata).
#include "app/bench.h"
#include "core/parallel.h"
#include "scenes/gltf_loader.h"
#include "trace/gradients.h"

#include <malloc.h>

#include <cstdio>

namespace rtdr {

void bench_gradients(const BenchOptions& o, const Size size, std::ostream* csv) {
  // Each run builds a new frame of some 200 MB at 720p and drops the last one. By default glibc hands such blocks
  // back to the kernel and faults them in again, which costs more than the gradient samples and varies from run to
  // run by a factor of three. Keep freed memory in the process, so that both columns time the rendering.
  mallopt(M_MMAP_THRESHOLD, 1 << 30);
  mallopt(M_TRIM_THRESHOLD, 1 << 30);
  std::printf("%-14s %9s %10s %14s %7s %10s   (median of %d runs, %d threads, strata of %d)\n", "scene", "size",
              "plain ms", "gradients ms", "ratio", "gradients", o.runs, thread_count(), o.gradient.stratum_size);
  const RenderSettings settings;  // 1 spp, seed 0: what A-SVGF gets
  for (const std::string& name : bench_scene_list(o.scenes)) {
    const Scene scene = load_scene(name);
    const int f = int(scene.fps / 2);
    const Frame prev = render_frame_with_gradients(scene, f - 1, size.width, size.height, settings, o.gradient, nullptr);
    Frame plain;
    const double plain_ms =
        median_ms(o.warmup, o.runs, [&] { plain = render_frame(scene, f, size.width, size.height, settings); });
    Frame frame;
    const double gradient_ms = median_ms(o.warmup, o.runs, [&] {
      frame = render_frame_with_gradients(scene, f, size.width, size.height, settings, o.gradient, &prev);
    });
    const double share = gradient_sample_share(frame);
    const double ratio = gradient_ms / plain_ms;
    std::printf("%-14s %4dx%-4d %10.1f %14.1f %7.3f %9.2f%%\n", name.c_str(), size.width, size.height, plain_ms,
                gradient_ms, ratio, 100.0 * share);
    if (csv) {
      const std::string row = "gradients," + name + ',' + std::to_string(size.width) + ',' +
                              std::to_string(size.height) + ',' + std::to_string(thread_count()) + ',';
      *csv << row << "plain_ms," << plain_ms << '\n'
           << row << "gradients_ms," << gradient_ms << '\n'
           << row << "ratio," << ratio << '\n'
           << row << "gradient_share," << share << '\n';
    }
  }
}

}  // namespace rtdr
