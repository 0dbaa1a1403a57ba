// What each pass of a method did to the last frame, in the order it ran: which pass (its declaration,
// filters/passes.h), on which stream and level, the layers it wrote, and how to recompute any of its pixels with a
// probe attached (its golden per-pixel function on exactly the inputs it saw). A method logs each pass where it runs
// it (Method::log_pass), and every tool reads the log the same way, naming no pass: `rtdr filter --dump-passes`
// writes every logged layer (PassLog::dump), `rtdr probe` re-runs a logged pass at a pixel (PassLog::probe).
//
//   time_pass("variance", [&] { s.variance = variance_pass(s.temporal, surface_, p); });
//   log_pass(kVariancePass, name)
//       .writes(kVariance, s.variance)
//       .pixel([this, &s](int x, int y, Probe* probe) { variance_pixel(s.temporal, surface_, p, x, y, probe); });
//
// A logged plane is pointed to, not copied: it must stay where it is until the next frame's log replaces this one
// (the method's members, which hold what the probe needs anyway). A plane made for the log alone (the variance pass's
// filter.<s>.variance.spatial, which only the dump shows) is moved into it instead.
#pragma once

#include "core/frame.h"
#include "filters/image.h"
#include "filters/passes.h"
#include "filters/probe.h"

#include <deque>
#include <functional>
#include <string>
#include <string_view>
#include <variant>
#include <vector>

namespace rtdr {

// One run of one pass: the pass, its stream ("" for a pass over the whole frame) and level (-1 without levels).
class PassRun {
 public:
  using Pixel = std::function<void(int x, int y, Probe* probe)>;

  PassRun(const PassDecl& pass, std::string_view stream, int level)
      : pass_(&pass), stream_(stream), level_(level) {}

  // The pass wrote `plane` as `layer` (one of its declaration's layers). With `stratum_size` > 0 the plane holds
  // one value per stratum of s x s pixels (A-SVGF's gradient passes), and its dump repeats each over its stratum.
  PassRun& writes(const LayerDecl& layer, const FloatPlane& plane, int stratum_size = 0);
  PassRun& writes(const LayerDecl& layer, const RgbPlane& plane);
  // The same for a plane the log keeps (moved in).
  PassRun& writes(const LayerDecl& layer, FloatPlane&& plane);
  PassRun& writes(const LayerDecl& layer, RgbPlane&& plane);
  // How to recompute pixel (x, y) with `probe` attached: the pass's golden per-pixel function.
  PassRun& pixel(Pixel pixel);

  const PassDecl& pass() const { return *pass_; }
  const std::string& stream() const { return stream_; }
  int level() const { return level_; }
  bool probed() const { return bool(pixel_); }
  // The layers it wrote, in order: each one's declaration, and its name in the dump (layer_name, filters/passes.h).
  std::vector<std::pair<const LayerDecl*, std::string>> written() const;

 private:
  friend class PassLog;
  struct Layer {
    const LayerDecl* layer;
    std::variant<const FloatPlane*, const RgbPlane*> plane;
    int stratum_size;
  };
  const PassDecl* pass_;
  std::string stream_;
  int level_;
  std::vector<Layer> layers_;
  std::deque<std::variant<FloatPlane, RgbPlane>> kept_;  // the planes moved in (a deque: they never move again)
  Pixel pixel_;
};

class PassLog {
 public:
  // Forgets the last frame's runs; `width` x `height` is the new frame's size.
  void begin(int width, int height);
  // Logs a run of `pass` and returns it, for its layers and its pixel function. Runs stay where they are.
  PassRun& add(const PassDecl& pass, std::string_view stream = {}, int level = -1);

  // Every layer of every run into `dump` (made the frame's size when it is not).
  void dump(Frame& dump) const;
  // Recomputes pixel (x, y) of the run of `pass` on `stream` at `level` with a probe attached. Throws rtdr::Error,
  // naming what did run, for a pixel outside the frame, a pass that did not run on this frame (or runs on no stream,
  // or on another), a stream it did not run on, or a level it did not reach.
  Probe probe(std::string_view pass, std::string_view stream, int level, int x, int y) const;
  // The passes that ran, in order, each once.
  std::vector<std::string> passes() const;
  const std::deque<PassRun>& runs() const { return runs_; }

 private:
  int width_ = 0, height_ = 0;
  std::deque<PassRun> runs_;
};

}  // namespace rtdr
