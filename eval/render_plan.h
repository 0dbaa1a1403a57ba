// The plan of a run's renders: what `rtdr eval --plan FILE` writes instead of running. It lists, without rendering
// anything, every frame the same `rtdr eval` would render because its cache lacks it (or holds it invalid), as jobs
// that any machine sharing the cache can run: tools/farm.py on a Dask cluster, or a batch scheduler
// (docs/scaling.md).
//
// A job is one `rtdr render` command line. Frames that do not depend on each other are one job each; the frames of
// A-SVGF's gradient input do (frame f continues frame f - 1), and a run of them is one job, cut exactly where the
// cache itself would render (eval/frame_cache.h gradient_runs). Every setting of a frame's render key
// (trace/render_key.h) is on the job's command line, so the frames it writes carry the key the eval looks up: a
// frame moved to its job's entry is the cache's own frame (eval/frame_cache.h).
#pragma once

#include "eval/experiment.h"

#include <cstdint>
#include <string>
#include <vector>

namespace rtdr {

struct RenderJob {
  std::string what;                  // which sequence, for people: "reference", "input", "input with gradients"
  std::vector<std::string> argv;     // `rtdr render ...`: everything but `--out DIR`, which whoever runs it appends
  int first = 0, last = 0;           // the frames it renders, in order
  std::vector<std::string> entries;  // the cache entry of each of them: absolute paths, first to last
  bool dependent = false;            // a run of gradient frames, each rendered from the one before
  // With `dependent` and first > 0: the entry of frame first - 1, which the cache holds and the run continues;
  // it goes into DIR as frame_<first-1>.exr before the command runs (rtdr render --gradients reads it there).
  std::string previous;
  std::string cache;   // the cache's folder, absolute: where a runner stages the job's frames (one file system)
  int64_t pixels = 0;  // width x height
  int spp = 0;
  // The cost estimate: pixels x spp x frames.
  int64_t cost() const { return pixels * spp * (last - first + 1); }
};

// The jobs of `config`'s run: references first, then inputs, in frame order. argv[0] of every job is `rtdr`, which
// should be an absolute path (the running rtdr's); the entries lie under the absolute path of config.cache_dir.
// Throws rtdr::Error where run_eval would refuse the config before rendering (check_eval_config), for a scene that
// does not load, and without a cache (an empty cache_dir).
std::vector<RenderJob> plan_renders(const EvalConfig& config, const std::string& rtdr);

// One job as one line of JSON (no newline): {"job", "what", "frames": [first, last], "dependent", "argv",
// "entries", "previous" (null when none), "cache", "pixels", "spp", "cost"}. `index` numbers the job in its plan.
// Throws rtdr::Error for a path that is not UTF-8 (JSON holds no other strings).
std::string plan_line(const RenderJob& job, int index);

}  // namespace rtdr
