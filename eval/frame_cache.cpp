#include "eval/frame_cache.h"

#include "core/error.h"
#include "core/exr_io.h"

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>

namespace rtdr {
namespace {

// Bump when the meaning of rendered layers changes, so old cache entries are not reused.
constexpr int kCacheVersion = 1;

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

std::string FrameCache::path(int frame_index, int width, int height, const RenderSettings& s) const {
  char name[160];
  std::snprintf(name, sizeof name, "%s-%016llx-v%d/%dx%d-spp%d-seed%u-b%d/frame_%04d.exr", scene_.name.c_str(),
                (unsigned long long)scene_hash_, kCacheVersion, width, height, s.spp, s.seed, s.trace.max_bounces,
                frame_index);
  return (std::filesystem::path(dir_) / name).string();
}

Frame FrameCache::get(int frame_index, int width, int height, const RenderSettings& settings, bool* hit) {
  const std::string file = dir_.empty() ? std::string() : path(frame_index, width, height, settings);
  if (!file.empty() && std::filesystem::exists(file)) {
    if (hit) *hit = true;
    return read_exr(file);
  }
  if (hit) *hit = false;
  Frame frame = render_frame(scene_, frame_index, width, height, settings);
  if (!file.empty()) {
    std::error_code ec;
    std::filesystem::create_directories(std::filesystem::path(file).parent_path(), ec);
    write_exr(file, frame);
  }
  return frame;
}

}  // namespace rtdr
