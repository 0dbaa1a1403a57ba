// rtdr bench --stage filter: a denoising method (--method, default svgf) on rendered frames of each scene
// at --size, per pass, on each back end of --backend (cpu, vulkan, or cpu,vulkan in one run): the median over
// --runs frames of a sequence, after at least 5 frames (or --warmup) that build the history, so the variance
// estimate is the temporal one of the steady state (SVGF17 Sec. 4.2 switches from the 7x7 spatial estimate after
// 4 frames). The method's parameters are rtdr filter's (--atrous-levels 4, --kernel-size 3, ...), and reports name
// it as a spec of rtdr eval ("svgf:kernel_size=3"). CPU pass times are wall times; Vulkan pass times are device
// timestamps, and "transfer" is the host's packing of the inputs and unpacking of the outputs (not part of
// "total"). With two back ends, each pass's speed-up is cpu ms / vulkan ms. Targets: the whole SVGF, direct and
// indirect, at 1280x720 on 2 cores in at most 2 s (cpu); the Vulkan ports at least 5x faster than the cpu passes on
// lavapipe.
#include "app/backend.h"
#include "app/bench.h"
#include "core/parallel.h"
#include "gpu/vulkan_method.h"
#include "scenes/gltf_loader.h"
#include "trace/gradients.h"
#include "trace/render_frame.h"

#include <algorithm>
#include <cstdio>
#include <map>
#include <set>

namespace rtdr {

namespace {

// Median ms per pass (and "total", total_ms: the passes' sum without "transfer") of `method` over frames[warmup..]. For the
// Vulkan pipeline, also the median of each of a frame's commands, in order, into *commands (left alone for other
// methods); each frame's batch is submitted `submits` times and the last one timed (--submits).
std::map<std::string, double> time_passes(Method& method, const std::vector<Frame>& frames, int warmup, int submits,
                                          std::vector<std::pair<std::string, double>>* commands, ProgressBar& bar) {
  std::map<std::string, std::vector<double>> times;
  std::vector<std::pair<std::string, std::vector<double>>> command_times;
  VulkanMethod* gpu = dynamic_cast<VulkanMethod*>(&method);
  if (gpu) gpu->set_submits(submits);
  for (size_t f = 0; f < frames.size(); ++f) {
    method.filter(frames[f]);
    bar.advance();
    if (int(f) < warmup) continue;  // history still building: not timed
    if (gpu) {
      const auto& last = gpu->command_times();
      command_times.resize(last.size());
      for (size_t c = 0; c < last.size(); ++c) {
        command_times[c].first = last[c].first;
        command_times[c].second.push_back(last[c].second);
      }
    }
    for (const auto& [pass, ms] : method.pass_times()) times[pass].push_back(ms);
    times["total"].push_back(total_ms(method.pass_times()));
  }
  std::map<std::string, double> medians;
  for (const auto& [pass, ms] : times) medians[pass] = median(ms);
  if (gpu) {
    commands->clear();
    for (const auto& [label, ms] : command_times) commands->emplace_back(label, median(ms));
  }
  return medians;
}

// The rows of the table: the method's passes in the order it runs them, then anything else a back end reports
// (the ports' "transfer"), then "total" last.
std::vector<std::string> pass_order(const Method& method,
                                    const std::map<std::string, std::map<std::string, double>>& medians) {
  std::set<std::string> reported;
  for (const auto& [backend, times] : medians)
    for (const auto& [pass, ms] : times) reported.insert(pass);
  std::vector<std::string> order;
  for (const std::string& pass : method.probe_passes())
    if (reported.erase(pass)) order.push_back(pass);
  const bool total = reported.erase("total") > 0;
  order.insert(order.end(), reported.begin(), reported.end());
  if (total) order.push_back("total");
  return order;
}

}  // namespace

void bench_filter(const BenchOptions& o, const Size size, std::ostream* csv) {
  const std::vector<std::string> backends = parse_backends(o.backend);
  // The method as a spec of rtdr eval: its name and the SVGF parameters that differ from the method's defaults (a
  // spec names SVGF's table only; the other tables' flags still reach the method).
  const std::string changed = changed_params(o.params.svgf, method_defaults(o.method).svgf);
  const std::string spec = o.method + (changed.empty() ? "" : ":" + changed);
  for (const std::string& name : bench_scene_list(o.scenes)) {
    const Scene scene = load_scene(name);
    // A short sequence, rendered once (1 spp); each back end then filters it frame after frame.
    const int warmup = std::max(5, o.warmup);
    std::vector<Frame> frames;
    // With gradient samples (trace/gradients.h) when the method reads them (asvgf), each frame from the one before.
    // And with TRMV's shading term when it reads that (trmv).
    const std::unique_ptr<Method> method = make_method(o.method, o.params);
    const bool gradients = method->reads_gradient_samples();
    RenderSettings settings;
    if (method->reads_shading_term()) settings.trace.shading_samples = kTrmvShadingSamples;
    std::map<std::string, std::map<std::string, double>> medians;  // backend -> pass -> ms
    std::vector<std::pair<std::string, double>> commands;           // the Vulkan frame's commands, in order
    std::string devices;
    {  // the bar counts the frames rendered, then filtered on each back end; its line ends before the table
      ProgressBar bar("bench filter " + name, uint64_t(warmup + o.runs) * (1 + backends.size()));
      for (int f = 0; f < warmup + o.runs; ++f) {
        frames.push_back(gradients ? render_frame_with_gradients(scene, f, size.width, size.height, settings, {},
                                                                 frames.empty() ? nullptr : &frames.back())
                                   : render_frame(scene, f, size.width, size.height, settings));
        bar.advance();
      }
      for (const std::string& backend : backends) {
        const BackendMethod m = make_backend_method(backend, o.method, o.params);
        if (m.context)
          devices += ", vulkan device " + m.context->device_name() + " (" + m.context->memory_summary() + ", " +
                     shader_inputs_name(m.context->shader_inputs()) + "-buffer inputs, " +
                     illumination_records_name(m.context->illumination_records()) + " illumination records)";
        medians[backend] = time_passes(*m.method, frames, warmup, o.submits, &commands, bar);
      }
    }
    std::printf("%s on %s at %dx%d, %d threads%s: median ms per frame over %d frames\n", spec.c_str(), name.c_str(),
                size.width, size.height, thread_count(), devices.c_str(), o.runs);
    std::printf("  %-16s", "pass");
    for (const std::string& backend : backends) std::printf(" %10s", backend.c_str());
    const bool compare = medians.count("cpu") && medians.count("vulkan");
    if (compare) std::printf(" %10s", "cpu/vulkan");
    std::printf("\n");
    for (const std::string& pass : pass_order(*method, medians)) {
      std::printf("  %-16s", pass.c_str());
      for (const std::string& backend : backends) {
        const auto it = medians[backend].find(pass);
        if (it == medians[backend].end()) {
          std::printf(" %10s", "-");
          continue;
        }
        std::printf(" %10.3f", it->second);
        if (csv)
          *csv << "filter:" << spec << ':' << backend << ',' << name << ',' << size.width << ',' << size.height
               << ',' << thread_count() << ",ms_" << pass << ',' << it->second << '\n';
      }
      if (compare && medians["cpu"].count(pass) && medians["vulkan"].count(pass) && medians["vulkan"][pass] > 0.0) {
        const double speedup = medians["cpu"][pass] / medians["vulkan"][pass];
        std::printf(" %9.1fx", speedup);
        if (csv)
          *csv << "filter:" << spec << ":cpu/vulkan," << name << ',' << size.width << ',' << size.height << ','
               << thread_count() << ",speedup_" << pass << ',' << speedup << '\n';
      }
      std::printf("\n");
    }
    if (!commands.empty()) {
      std::printf("  vulkan, command by command (median ms):");
      for (const auto& [label, ms] : commands) std::printf(" %s %.3f", label.c_str(), ms);
      std::printf("\n");
    }
    std::fflush(stdout);
  }
}

}  // namespace rtdr
