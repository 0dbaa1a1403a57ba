// Rendered frames cached on disk, so reruns of an experiment are cheap: reference frames take minutes.
// A cache entry is keyed by everything the frame depends on: the scene file's bytes, the frame index, the
// size, the samples per pixel, the seed and the bounce count (and a version number bumped whenever the
// renderer's output changes meaning), and for A-SVGF's input every gradient parameter. Entries are EXR files
// written atomically, so an interrupted run never leaves a half-written entry behind.
#pragma once

#include "core/frame.h"
#include "scenes/scene.h"
#include "trace/gradients.h"
#include "trace/render_frame.h"

#include <string>
#include <vector>

namespace rtdr {

class FrameCache {
 public:
  // `dir` is created on first use; an empty `dir` disables caching.
  FrameCache(std::string dir, const Scene& scene);

  // The frame from the cache, or rendered (and stored) when it is not there. `hit` says which.
  Frame get(int frame_index, int width, int height, const RenderSettings& settings, bool* hit = nullptr);
  // Frames first..last rendered with gradient samples (trace/gradients.h), each from the one before. A frame not in
  // the cache needs its predecessor: from the cache when there, else rendered from the latest earlier frame that
  // is (or from frame 0), and stored too.
  std::vector<Frame> gradient_frames(int first, int last, int width, int height, const RenderSettings& settings,
                                     const GradientParams& params);
  // Where the entry for these inputs lives; with `gradients`, the entry of a frame with gradient samples.
  std::string path(int frame_index, int width, int height, const RenderSettings& settings,
                   const GradientParams* gradients = nullptr) const;

 private:
  void store(const std::string& file, const Frame& frame) const;

  std::string dir_;
  const Scene& scene_;
  uint64_t scene_hash_;
};

}  // namespace rtdr
