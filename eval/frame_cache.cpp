#include "eval/frame_cache.h"

#include "core/error.h"
#include "core/exr_io.h"

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <optional>
#include <sstream>

namespace rtdr {
namespace {

// Bump when the meaning of rendered layers changes, so old cache entries are not reused.
// 2: frames gained TRMV's shadow motion (motion.shadow, motion.shadow_splat); direct.shading, when rendered, is in
// the key ("-shading64"). 3: the energy-preserving dielectric (trace/brdf.h) and double-sided emitters.
// 4: frames gained the dual motion vector (motion.dual, motion/dual.h) and the cones' samples (path.incoming, path.pdf).
constexpr int kCacheVersion = 4;

// FNV-1a, 64 bits (Fowler, Noll, Vo): a small, well-spread hash of the scene file's bytes.
uint64_t fnv1a(const std::string& bytes) {
  uint64_t h = 0xcbf29ce484222325ULL;
  for (unsigned char c : bytes) h = (h ^ c) * 0x100000001b3ULL;
  return h;
}

std::string read_bytes(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw Error("cannot read scene file '" + path + "' for the frame cache");
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

}  // namespace

FrameCache::FrameCache(std::string dir, const Scene& scene)
    : dir_(std::move(dir)), scene_(scene), scene_hash_(fnv1a(read_bytes(scene.source))) {}

std::string FrameCache::path(int frame_index, int width, int height, const RenderSettings& s,
                             const GradientParams* gradients) const {
  // Gradient frames differ from plain ones at their gradient pixels: their own directory, named by every
  // parameter, e.g. "-gradients-stratum_size3-selection0-seed_reuse1-seed_chains1-light_cdf0".
  std::string key_suffix;
  if (gradients) {
    key_suffix = "-gradients";
    const std::vector<ParamInfo> table = gradient_param_table();
    const std::vector<double> values = param_values(*gradients);
    for (size_t k = 0; k < table.size(); ++k) key_suffix += "-" + table[k].name + std::to_string(int64_t(values[k]));
  }
  char name[160];
  std::snprintf(name, sizeof name, "%s-%016llx-v%d/%dx%d-spp%d-seed%u-b%d", scene_.name.c_str(),
                (unsigned long long)scene_hash_, kCacheVersion, width, height, s.spp, s.seed, s.trace.max_bounces);
  if (s.trace.shading_samples > 0) key_suffix = "-shading" + std::to_string(s.trace.shading_samples) + key_suffix;
  char file[32];
  std::snprintf(file, sizeof file, "frame_%04d.exr", frame_index);
  return (std::filesystem::path(dir_) / (name + key_suffix) / file).string();
}

void FrameCache::store(const std::string& file, const Frame& frame) const {
  if (file.empty()) return;
  std::error_code ec;
  std::filesystem::create_directories(std::filesystem::path(file).parent_path(), ec);
  write_exr(file, frame);
}

Frame FrameCache::get(int frame_index, int width, int height, const RenderSettings& settings, bool* hit) {
  const std::string file = dir_.empty() ? std::string() : path(frame_index, width, height, settings);
  if (!file.empty() && std::filesystem::exists(file)) {
    if (hit) *hit = true;
    return read_exr(file);
  }
  if (hit) *hit = false;
  Frame frame = render_frame(scene_, frame_index, width, height, settings);
  store(file, frame);
  return frame;
}

std::vector<Frame> FrameCache::gradient_frames(int first, int last, int width, int height,
                                               const RenderSettings& settings, const GradientParams& params) {
  const auto file = [&](int f) { return dir_.empty() ? std::string() : path(f, width, height, settings, &params); };
  const auto cached = [&](int f) { return !dir_.empty() && std::filesystem::exists(file(f)); };
  const auto render = [&](int f, const Frame* prev) {
    Frame frame = render_frame_with_gradients(scene_, f, width, height, settings, params, prev);
    store(file(f), frame);
    return frame;
  };
  std::vector<Frame> frames;
  std::optional<Frame> prev;  // frame f - 1, once known
  for (int f = first; f <= last; ++f) {
    const bool hit = cached(f);
    if (!hit && !prev && f > 0) {
      // Frame f needs f - 1: go back to the latest cached frame (or to the start) and render forward.
      int from = f - 1;
      while (from >= 0 && !cached(from)) --from;
      if (from >= 0) prev = read_exr(file(from));
      for (int g = from + 1; g < f; ++g) prev = render(g, prev ? &*prev : nullptr);
    }
    frames.push_back(hit ? read_exr(file(f)) : render(f, prev ? &*prev : nullptr));
    prev = frames.back();
  }
  return frames;
}

}  // namespace rtdr
