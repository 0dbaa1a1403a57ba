#include "eval/frame_cache.h"

#include "core/error.h"
#include "core/exr_io.h"
#include "core/hash.h"

#include <cctype>
#include <cerrno>
#include <cstdio>
#include <filesystem>
#include <map>

namespace rtdr {
namespace fs = std::filesystem;
namespace {

constexpr const char* kStagingPrefix = ".rtdr-cache-staging-";

// The readable start of an entry's folder name: the scene's name with anything but letters, digits, '.', '-' and
// '_' replaced, cut at 48 characters.
std::string readable(const std::string& scene_name) {
  std::string s;
  for (const char c : scene_name.substr(0, 48))
    s += (std::isalnum(static_cast<unsigned char>(c)) || c == '.' || c == '-' || c == '_') ? c : '_';
  return s.empty() || s[0] == '.' ? "_" + s : s;  // never a hidden folder
}

// Every float of the frame finite, as filter checks its input (docs/reliability.md, promise 5); "" when so.
std::string non_finite(const Frame& frame) {
  std::vector<std::string> channels;
  for (const auto& [name, plane] : frame.float_channels()) channels.push_back(name);
  try {
    require_finite(frame, channels);
  } catch (const Error& e) {
    return e.what();
  }
  return "";
}

void warn(const std::string& message) { std::fprintf(stderr, "rtdr: warning: %s\n", message.c_str()); }

}  // namespace

FrameCache::FrameCache(std::string dir, const Scene& scene) : dir_(std::move(dir)), scene_(scene) {
  // What a dead run staged goes now, even when this run only reads (a StagingFolder removes it too when made).
  if (!dir_.empty()) StagingFolder::remove_stale(dir_, kStagingPrefix);
}

FrameCache::~FrameCache() = default;

std::string FrameCache::path(const Attributes& key) const {
  Fnv1a64 h;
  for (const auto& [name, value] : key)
    if (name != "rtdr.frame") h.text(name).text(value);
  const std::string folder = readable(key.at("rtdr.scene")) + "-" + key.at("rtdr.size") + "-spp" +
                             key.at("rtdr.spp") + (key.at("rtdr.gradients") == "1" ? "-gradients" : "") + "-" +
                             h.hex();
  char file[32];
  std::snprintf(file, sizeof file, "frame_%04d.exr", std::stoi(key.at("rtdr.frame")));
  return (fs::path(dir_) / folder / file).string();
}

std::unique_ptr<Frame> FrameCache::load(const Attributes& key) const {
  if (dir_.empty()) return nullptr;
  const std::string file = path(key);
  std::error_code ec;
  if (!fs::exists(file, ec)) return nullptr;
  auto frame = std::make_unique<Frame>();
  std::string why;
  try {
    *frame = read_exr(file);
    why = key_mismatch(*frame, key);  // another key of the same hash, or an entry of an older rtdr
    if (why.empty()) why = checksum_mismatch(*frame);  // changed after it was rendered
    if (why.empty()) why = non_finite(*frame);
  } catch (const Error& e) {
    why = e.what();  // not a readable frame: truncated, not an EXR, ...
  }
  if (why.empty()) return frame;
  warn("cache entry '" + file + "' is not the frame asked for (" + why + "): rendering it again");
  return nullptr;
}

void FrameCache::store(const Attributes& key, const Frame& frame) {
  if (dir_.empty() || read_only_) return;
  if (!staging_) {
    std::error_code ec;
    fs::create_directories(dir_, ec);
    try {
      staging_ = std::make_unique<StagingFolder>(dir_, kStagingPrefix);
    } catch (const SystemError& e) {
      // A cache we cannot write to is still read; a full disk or any other failure fails the run.
      if (e.code != EROFS && e.code != EACCES && e.code != EPERM) throw Error("frame cache '" + dir_ + "': " + e.what());
      read_only_ = true;
      warn("frame cache '" + dir_ + "' cannot be written (" + e.what() + "): frames rendered now are not stored");
      return;
    }
  }
  const std::string file = path(key);
  const std::string staged = (fs::path(staging_->path()) / fs::path(file).filename()).string();
  write_exr(staged, frame);
  std::error_code ec;
  fs::create_directories(fs::path(file).parent_path(), ec);
  fs::rename(staged, file, ec);  // one file system: the staging folder is inside the cache
  if (ec) {
    const std::string reason = ec.message();
    fs::remove(staged, ec);
    throw Error("frame cache: cannot store '" + file + "': " + reason);
  }
}

bool FrameCache::has(const Attributes& key) const { return load(key) != nullptr; }

Frame FrameCache::get(int frame_index, int width, int height, const RenderSettings& settings, bool* hit) {
  const Attributes key = render_key(scene_, frame_index, width, height, settings);
  if (std::unique_ptr<Frame> cached = load(key)) {
    if (hit) *hit = true;
    return std::move(*cached);
  }
  if (hit) *hit = false;
  Frame frame = render_frame(scene_, frame_index, width, height, settings);
  store(key, frame);
  return frame;
}

std::vector<Frame> FrameCache::gradient_frames(int first, int last, int width, int height,
                                               const RenderSettings& settings, const GradientParams& params) {
  const auto key = [&](int f) { return render_key(scene_, f, width, height, settings, &params); };
  std::map<int, Frame> held;  // by index: the frames found in the cache, then those rendered
  const auto cached = [&](int f) {
    std::unique_ptr<Frame> found = load(key(f));
    if (found) held.emplace(f, std::move(*found));
    return found != nullptr;
  };
  for (const GradientRun& run : gradient_runs(first, last, cached)) {
    for (int f = run.first; f <= run.last; ++f) {
      // Frame f continues frame f - 1: the run's own, or the cached one before the run (none before frame 0).
      const Frame* prev = f > 0 ? &held.at(f - 1) : nullptr;
      Frame frame = render_frame_with_gradients(scene_, f, width, height, settings, params, prev);
      store(key(f), frame);
      held.emplace(f, std::move(frame));
      if (f - 1 < first) held.erase(f - 1);  // a frame before the range, needed no more
    }
  }
  std::vector<Frame> frames;
  for (int f = first; f <= last; ++f) frames.push_back(std::move(held.at(f)));
  return frames;
}

std::vector<GradientRun> gradient_runs(int first, int last, const std::function<bool(int)>& cached) {
  std::vector<GradientRun> runs;
  for (int f = first; f <= last; ++f) {
    if (cached(f)) continue;
    if (!runs.empty() && runs.back().last == f - 1) {  // the run goes on
      runs.back().last = f;
      continue;
    }
    // A new run: frame f - 1 is cached, unless f is the first frame asked for; then go back to the latest frame
    // the cache holds, or to frame 0, and render forward from there.
    int start = f;
    if (f == first)
      while (start > 0 && !cached(start - 1)) --start;
    runs.push_back({start, f});
  }
  return runs;
}

}  // namespace rtdr
