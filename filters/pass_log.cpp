// The log of a frame's passes: see pass_log.h.
#include "filters/pass_log.h"

#include "core/error.h"
#include "filters/asvgf/gradient_image.h"

#include <algorithm>

namespace rtdr {
namespace {

// "a, b, c".
std::string joined(const std::vector<std::string>& names) {
  std::string list;
  for (const std::string& n : names) list += (list.empty() ? "" : ", ") + n;
  return list;
}

}  // namespace

PassRun& PassRun::writes(const LayerDecl& layer, const FloatPlane& plane, int stratum_size) {
  layers_.push_back({&layer, &plane, stratum_size});
  return *this;
}

PassRun& PassRun::writes(const LayerDecl& layer, const RgbPlane& plane) {
  layers_.push_back({&layer, &plane, 0});
  return *this;
}

PassRun& PassRun::writes(const LayerDecl& layer, FloatPlane&& plane) {
  return writes(layer, std::get<FloatPlane>(kept_.emplace_back(std::move(plane))));
}

PassRun& PassRun::writes(const LayerDecl& layer, RgbPlane&& plane) {
  return writes(layer, std::get<RgbPlane>(kept_.emplace_back(std::move(plane))));
}

PassRun& PassRun::pixel(Pixel pixel) {
  pixel_ = std::move(pixel);
  return *this;
}

std::vector<std::pair<const LayerDecl*, std::string>> PassRun::written() const {
  std::vector<std::pair<const LayerDecl*, std::string>> names;
  for (const Layer& l : layers_) names.emplace_back(l.layer, layer_name(*l.layer, stream_, level_));
  return names;
}

void PassLog::begin(int width, int height) {
  width_ = width;
  height_ = height;
  runs_.clear();
}

PassRun& PassLog::add(const PassDecl& pass, std::string_view stream, int level) {
  return runs_.emplace_back(pass, stream, level);
}

void PassLog::dump(Frame& dump) const {
  if (dump.width() != width_ || dump.height() != height_) dump = Frame(width_, height_);
  for (const PassRun& run : runs_)
    for (const PassRun::Layer& l : run.layers_) {
      if (const FloatPlane* const* scalar = std::get_if<const FloatPlane*>(&l.plane)) {
        if (l.stratum_size > 0)
          dump_layer(&dump, *l.layer, run.stream(), run.level(),
                     replicate_strata(**scalar, l.stratum_size, width_, height_));
        else
          dump_layer(&dump, *l.layer, run.stream(), run.level(), **scalar);
      } else {
        dump_layer(&dump, *l.layer, run.stream(), run.level(), *std::get<const RgbPlane*>(l.plane));
      }
    }
}

std::vector<std::string> PassLog::passes() const {
  std::vector<std::string> names;
  for (const PassRun& run : runs_)
    if (std::find(names.begin(), names.end(), run.pass().name) == names.end()) names.emplace_back(run.pass().name);
  return names;
}

Probe PassLog::probe(std::string_view pass, std::string_view stream, int level, int x, int y) const {
  if (width_ == 0) throw Error("probe: no frame has been filtered yet");
  if (x < 0 || y < 0 || x >= width_ || y >= height_)
    throw Error("--pixel " + std::to_string(x) + "," + std::to_string(y) + " is outside the " +
                std::to_string(width_) + "x" + std::to_string(height_) + " frame");
  // The runs of the pass, and among them the stream's (a pass over the whole frame answers for any stream).
  std::vector<const PassRun*> runs, on_stream;
  for (const PassRun& run : runs_)
    if (run.pass().name == pass && run.probed()) runs.push_back(&run);
  if (runs.empty())
    throw Error("--pass '" + std::string(pass) + "' did not run on this frame (passes that ran: " + joined(passes()) +
                ")");
  std::vector<std::string> streams;
  for (const PassRun* run : runs) {
    if (run->stream().empty() || run->stream() == stream) on_stream.push_back(run);
    if (!run->stream().empty() && std::find(streams.begin(), streams.end(), run->stream()) == streams.end())
      streams.push_back(run->stream());
  }
  if (on_stream.empty())
    throw Error("--stream '" + std::string(stream) + "': pass " + std::string(pass) + " ran on " + joined(streams));
  const bool levelled = on_stream.front()->level() >= 0;
  for (const PassRun* run : on_stream)
    if (!levelled || run->level() == level) {
      Probe probe;
      run->pixel_(x, y, &probe);
      return probe;
    }
  throw Error("--level " + std::to_string(level) + " is not one of the " + std::to_string(on_stream.size()) +
              " levels run");
}

}  // namespace rtdr
