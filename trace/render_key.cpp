// The render key of a frame: see render_key.h.
#include "trace/render_key.h"

#include "trace/gradients.h"

#include <embree3/rtcore_config.h>

#include <cstdio>

namespace rtdr {
namespace {

// Attributes that are recorded but not part of the key.
bool keyed(const std::string& name) {
  return name.rfind("rtdr.", 0) == 0 && name != "rtdr.build" && name != "rtdr.cpu" && name != "rtdr.checksum";
}

// A float written so that reading it back gives the same float (9 significant digits).
std::string exact(float value) {
  char s[32];
  std::snprintf(s, sizeof s, "%.9g", double(value));
  return s;
}

}  // namespace

Attributes render_key(const Scene& scene, int frame_index, int width, int height, const RenderSettings& settings,
                      const GradientParams* gradients) {
  Attributes key = {
      {"rtdr.renderer", std::to_string(kRendererVersion)},
      {"rtdr.scene", scene.name},
      {"rtdr.scene.hash", scene.content_hash},
      {"rtdr.frame", std::to_string(frame_index)},
      {"rtdr.size", std::to_string(width) + "x" + std::to_string(height)},
      {"rtdr.spp", std::to_string(settings.spp)},
      {"rtdr.seed", std::to_string(settings.seed)},
      {"rtdr.max_bounces", std::to_string(settings.trace.max_bounces)},
      {"rtdr.regularized_roughness", exact(settings.trace.regularized_roughness)},
      {"rtdr.shading_samples", std::to_string(settings.trace.shading_samples)},
      {"rtdr.gradients", gradients ? "1" : "0"},
  };
  if (gradients) {
    const std::vector<ParamInfo> table = gradient_param_table();
    const std::vector<double> values = param_values(*gradients);
    for (size_t k = 0; k < table.size(); ++k)
      key["rtdr.gradient." + table[k].name] = std::to_string(int64_t(values[k]));  // every row is an int
  }
  return key;
}

Attributes render_provenance() {
  // The processor features the renderer's results may depend on: Embree picks its traversal kernels by them, and
  // libm its code paths.
  std::string cpu;
#if defined(__x86_64__) || defined(__i386__)
  cpu = "x86_64";
  __builtin_cpu_init();
  if (__builtin_cpu_supports("sse4.2")) cpu += " sse4.2";
  if (__builtin_cpu_supports("avx")) cpu += " avx";
  if (__builtin_cpu_supports("avx2")) cpu += " avx2";
  if (__builtin_cpu_supports("fma")) cpu += " fma";
  if (__builtin_cpu_supports("avx512f")) cpu += " avx512f";
#else
  cpu = "unknown";
#endif
  return {{"rtdr.build", std::string("rtdr, ") + RTDR_BUILD_DESCRIPTION + ", Embree " + RTC_VERSION_STRING},
          {"rtdr.cpu", cpu}};
}

void stamp_render_header(Frame& frame, const Attributes& key) {
  frame.attributes = key;
  for (const auto& [name, value] : render_provenance()) frame.attributes[name] = value;
  frame.attributes["rtdr.checksum"] = frame_checksum(frame);
}

std::string key_mismatch(const Frame& frame, const Attributes& key, const std::set<std::string>& ignore) {
  for (const auto& [name, value] : key) {
    if (ignore.count(name)) continue;
    const auto it = frame.attributes.find(name);
    if (it == frame.attributes.end()) return name + " is missing";
    if (it->second != value) return name + " is " + it->second + ", not " + value;
  }
  for (const auto& [name, value] : frame.attributes)
    if (keyed(name) && !ignore.count(name) && !key.count(name)) return name + " = " + value + " is not expected";
  return "";
}

std::string checksum_mismatch(const Frame& frame) {
  const auto it = frame.attributes.find("rtdr.checksum");
  if (it == frame.attributes.end()) return "rtdr.checksum is missing";
  const std::string actual = frame_checksum(frame);
  return actual == it->second ? "" : "its planes changed since it was rendered: checksum " + actual + ", not " +
                                         it->second;
}

}  // namespace rtdr
