// Rendered frames cached on disk, so reruns of an experiment are cheap: reference frames take minutes.
//
// An entry is one rendered frame, found by its render key (trace/render_key.h): the scene's content, the frame,
// the size, every render setting, and for A-SVGF's input every gradient parameter. Its path is
//   <cache>/<scene>-<W>x<H>-spp<N>-<hash>/frame_<index>.exr
// where <hash> is the FNV-1a of the whole key but the frame index (every attribute, whatever its length), and the
// readable part before it is for people only: it may be cut short, the hash never is. The entry's header holds
// its full key and the checksum of its planes, and a frame is used only when both match what was asked and every
// float in it is finite; any other entry (another key that shares the hash, a changed or truncated file, a NaN)
// is rendered again, with a warning, and replaced.
//
// Writes are staged: each frame is written into a hidden, locked staging folder inside the cache
// (<cache>/.rtdr-cache-staging-*, core/atomic_file.h StagingFolder) and renamed into place, so an entry appears
// whole or not at all, even when the run is killed; a later run removes what a dead one left. A read-only cache is
// read, and what it lacks is rendered without being stored (one warning). A write that fails otherwise (a full
// disk) fails the run with the reason and leaves no partial entry.
//
// The cache is also the contract with a cluster (docs/scaling.md): `rtdr eval --plan` (eval/render_plan.h) lists the
// frames `has` finds missing, in the jobs `gradient_runs` cuts, and workers move frames of `rtdr render` into their
// entries' paths.
#pragma once

#include "core/atomic_file.h"
#include "core/frame.h"
#include "scenes/scene.h"
#include "trace/gradients.h"
#include "trace/render_frame.h"
#include "trace/render_key.h"

#include <functional>
#include <memory>
#include <string>
#include <vector>

namespace rtdr {

// One run of a gradient sequence to render: frames first..last, each from the one before; frame first - 1 is in
// the cache (or first is 0).
struct GradientRun {
  int first, last;
};

// The runs to render for frames first..last of a gradient sequence, given which frames the cache holds
// (`cached(f)`, asked at most once per frame): the longest runs of frames it lacks, where the run holding `first`
// starts after the latest earlier frame it holds (or at frame 0), since frame f needs frame f - 1. What
// FrameCache::gradient_frames renders, and the dependent jobs of a plan.
std::vector<GradientRun> gradient_runs(int first, int last, const std::function<bool(int)>& cached);

class FrameCache {
 public:
  // `dir` is created on first use; an empty `dir` disables caching.
  FrameCache(std::string dir, const Scene& scene);
  ~FrameCache();

  // The frame from the cache, or rendered (and stored) when it is not there. `hit` says which.
  Frame get(int frame_index, int width, int height, const RenderSettings& settings, bool* hit = nullptr);
  // Frames first..last rendered with gradient samples (trace/gradients.h), each from the one before. A frame not in
  // the cache needs its predecessor: from the cache when there, else rendered from the latest earlier frame that
  // is (or from frame 0), and stored too.
  std::vector<Frame> gradient_frames(int first, int last, int width, int height, const RenderSettings& settings,
                                     const GradientParams& params);
  // Where the entry of the frame with this render key lives (trace/render_key.h render_key).
  std::string path(const Attributes& key) const;
  // Whether the entry of `key` is there and valid: what `get` would return without rendering (a warning when it
  // is there but not valid, as `get` gives).
  bool has(const Attributes& key) const;

 private:
  // The entry of `key` when it is there and valid; otherwise nullptr, after a warning when it was there but not
  // valid.
  std::unique_ptr<Frame> load(const Attributes& key) const;
  void store(const Attributes& key, const Frame& frame);

  std::string dir_;
  const Scene& scene_;
  std::unique_ptr<StagingFolder> staging_;  // made on the first store
  bool read_only_ = false;                  // the first store found the cache read-only
};

}  // namespace rtdr
