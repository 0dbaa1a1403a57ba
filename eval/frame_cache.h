// Rendered frames cached on disk, so reruns of an experiment are cheap: reference frames take minutes.
// A cache entry is keyed by everything the frame depends on: the scene file's bytes, the frame index, the
// size, the samples per pixel, the seed and the bounce count (and a version number bumped whenever the
// renderer's output changes meaning). Entries are EXR files written atomically, so an interrupted run
// never leaves a half-written entry behind.
#pragma once

#include "core/frame.h"
#include "scenes/scene.h"
#include "trace/render_frame.h"

#include <string>

namespace rtdr {

class FrameCache {
 public:
  // `dir` is created on first use; an empty `dir` disables caching.
  FrameCache(std::string dir, const Scene& scene);

  // The frame from the cache, or rendered (and stored) when it is not there. `hit` says which.
  Frame get(int frame_index, int width, int height, const RenderSettings& settings, bool* hit = nullptr);
  // Where the entry for these inputs lives.
  std::string path(int frame_index, int width, int height, const RenderSettings& settings) const;

 private:
  std::string dir_;
  const Scene& scene_;
  uint64_t scene_hash_;
};

}  // namespace rtdr
