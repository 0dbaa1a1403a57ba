// rtdr bench --stage filter: a denoising method (--method, default svgf) on rendered frames of each scene
// at --size, per pass: the median over --runs frames of a sequence, after at least 5 frames (or --warmup)
// that build the history, so the variance estimate is the temporal one of the steady state (SVGF17 Sec. 4.2
// switches from the 7x7 spatial estimate after 4 frames). Issue target: the whole SVGF, direct and indirect,
// at 1280x720 on 2 cores in at most 2 s.
#include "app/bench.h"
#include "core/parallel.h"
#include "filters/method.h"
#include "scenes/gltf_loader.h"
#include "trace/render_frame.h"

#include <algorithm>
#include <cstdio>
#include <map>

namespace rtdr {

void bench_filter(const BenchOptions& o, const Size size, std::ostream* csv) {
  for (const std::string& name : bench_scene_list(o.scenes)) {
    const Scene scene = load_scene(name);
    // A short sequence, rendered once (1 spp); the method then filters it frame after frame.
    const int warmup = std::max(5, o.warmup);
    std::vector<Frame> frames;
    for (int f = 0; f < warmup + o.runs; ++f) frames.push_back(render_frame(scene, f, size.width, size.height, {}));
    const std::unique_ptr<Method> method = make_method(o.method);
    std::map<std::string, std::vector<double>> times;
    for (size_t f = 0; f < frames.size(); ++f) {
      method->filter(frames[f]);
      if (int(f) < warmup) continue;  // history still building: not timed
      double total = 0.0;
      for (const auto& [pass, ms] : method->pass_times()) times[pass].push_back(ms), total += ms;
      times["total"].push_back(total);
    }
    std::printf("%s on %s at %dx%d, %d threads: median ms per frame over %d frames\n", o.method.c_str(), name.c_str(),
                size.width, size.height, thread_count(), o.runs);
    for (const auto& [pass, ms] : times) {
      const double median_ms = median(ms);
      std::printf("  %-10s %10.1f\n", pass.c_str(), median_ms);
      if (csv)
        *csv << "filter:" << o.method << ',' << name << ',' << size.width << ',' << size.height << ',' << thread_count()
             << ",ms_" << pass << ',' << median_ms << '\n';
    }
  }
}

}  // namespace rtdr
