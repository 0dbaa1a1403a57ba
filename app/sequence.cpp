#include "app/sequence.h"

#include "core/error.h"
#include "core/exr_io.h"
#include "filters/input_check.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <filesystem>

namespace rtdr {

std::string frame_name(int index, const char* ext) {
  char name[32];
  std::snprintf(name, sizeof name, "frame_%04d.%s", index, ext);
  return name;
}

std::string frame_path(const std::string& dir, int index, const char* ext) {
  return (std::filesystem::path(dir) / frame_name(index, ext)).string();
}

std::vector<SequenceFrame> list_sequence(const std::string& dir, const std::string& range) {
  std::error_code ec;
  if (!std::filesystem::is_directory(dir, ec)) throw Error("--in '" + dir + "' is not a directory");
  std::vector<SequenceFrame> frames;
  for (const auto& entry : std::filesystem::directory_iterator(dir, ec)) {
    const std::string name = entry.path().filename().string();
    // frame_NNNN.exr: the index is the digits between "frame_" and ".exr".
    if (name.size() <= 10 || name.rfind("frame_", 0) != 0 || entry.path().extension() != ".exr") continue;
    int index = -1;
    const auto [end, err] = std::from_chars(name.data() + 6, name.data() + name.size() - 4, index);
    if (err == std::errc() && end == name.data() + name.size() - 4) frames.push_back({index, entry.path().string()});
  }
  std::sort(frames.begin(), frames.end(), [](const SequenceFrame& a, const SequenceFrame& b) {
    return a.index != b.index ? a.index < b.index : a.path < b.path;  // ties by name: the same error every run
  });
  if (frames.empty()) throw Error("--in '" + dir + "' holds no frame_NNNN.exr (write some with rtdr render)");
  for (size_t i = 1; i < frames.size(); ++i)
    if (frames[i].index == frames[i - 1].index)
      throw Error("--in '" + dir + "' holds frame " + std::to_string(frames[i].index) + " twice: '" +
                  frames[i - 1].path + "' and '" + frames[i].path + "'");
  if (range.empty()) return frames;
  const FrameRange r = parse_frames(range);
  std::vector<SequenceFrame> selected;
  for (const SequenceFrame& f : frames)
    if (f.index >= r.first && f.index <= r.last) selected.push_back(f);
  if (int(selected.size()) != r.last - r.first + 1)
    throw Error("--in '" + dir + "' lacks frames of --frames " + range + " (it has " + std::to_string(frames.size()) + " frames from " +
                std::to_string(frames.front().index) + ")");
  return selected;
}

Frame read_method_input(const std::string& path, const InputChannels& channels) {
  Frame frame = read_exr(path);
  fill_input_defaults(frame, channels);  // what the input may leave out (emission, indirect), filled in
  return frame;
}

std::vector<std::string> sequence_input_problems(const Frame& frame, const InputChannels& channels, const Frame* first) {
  std::vector<std::string> problems;
  if (first && (frame.width() != first->width() || frame.height() != first->height()))
    problems.push_back("size " + std::to_string(frame.width()) + "x" + std::to_string(frame.height()) + ", but " +
                       first->source + " is " + std::to_string(first->width()) + "x" + std::to_string(first->height()) +
                       ": the frames of a sequence must have the same size");
  for (std::string& p : input_problems(frame, channels)) problems.push_back(std::move(p));  // filters/input_check.h
  return problems;
}

Frame read_filter_input(const std::string& path, SequenceShape& shape, const InputChannels& channels) {
  Frame frame = read_method_input(path, channels);
  const std::vector<std::string> problems =
      sequence_input_problems(frame, channels, shape.first.source.empty() ? nullptr : &shape.first);
  if (!problems.empty()) throw Error(path + ": " + problems.front());
  if (shape.first.source.empty()) {
    shape.first = Frame(frame.width(), frame.height());
    shape.first.source = path;
  }
  return frame;
}

void require_finite_output(const Frame& frame, const std::string& what,
                           const std::function<std::string(const std::string& channel)>& pass_of) {
  for (const auto& [name, plane] : frame.float_channels())
    for (int y = 0; y < plane.height; ++y)
      for (int x = 0; x < plane.width; ++x)
        if (!std::isfinite(plane.at(x, y)))
          throw Error(what + ": pass " + pass_of(name) + " wrote " + (std::isnan(plane.at(x, y)) ? "NaN" : "Inf") +
                      " to '" + name + "' at pixel (" + std::to_string(x) + ", " + std::to_string(y) +
                      "); nothing was written");
}

}  // namespace rtdr
