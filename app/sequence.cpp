#include "app/sequence.h"

#include "core/error.h"
#include "core/exr_io.h"

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

Frame read_filter_input(const std::string& path, SequenceShape& shape, const InputChannels& channels) {
  Frame frame = read_method_input(path, channels);
  if (shape.first.source.empty()) {
    shape.first = Frame(frame.width(), frame.height());
    shape.first.source = path;
  } else {
    require_same_size(shape.first, frame);  // names both files
  }
  const std::vector<std::string> missing = missing_layers(frame, channels);
  if (!missing.empty()) throw Error(path + ": " + missing.front());  // with the fix, where rtdr render has one
  require_finite(frame, channels.floats);                             // present, float and finite
  for (const std::string& name : channels.uints) frame.uint_channel(name);  // present and uint
  return frame;
}

std::vector<std::string> missing_layers(const Frame& frame, const InputChannels& channels) {
  // Missing channels, grouped by layer (the name before the last '.', as docs/buffers.md names layers).
  std::vector<std::pair<std::string, std::vector<std::string>>> missing;  // layer, its missing channels, in order
  std::vector<std::string> names = channels.floats;
  names.insert(names.end(), channels.uints.begin(), channels.uints.end());
  for (const std::string& name : names) {
    if (frame.has(name) || channels.defaults.count(name)) continue;  // a default: fill_input_defaults
    const std::string layer = name.substr(0, name.rfind('.'));
    if (missing.empty() || missing.back().first != layer) missing.push_back({layer, {}});
    missing.back().second.push_back(name);
  }
  std::vector<std::string> problems;
  for (const auto& [layer, lacking] : missing) {
    std::string list;
    for (const std::string& n : lacking) list += (list.empty() ? "" : ", ") + n;
    bool partly = false;  // some channel of the layer is there
    for (const auto& [n, plane] : frame.float_channels()) partly = partly || n.rfind(layer + ".", 0) == 0;
    for (const auto& [n, plane] : frame.uint_channels()) partly = partly || n.rfind(layer + ".", 0) == 0;
    const std::string fix = missing_layer_fix(layer);
    problems.push_back((partly ? "layer '" + layer + "' lacks " + list : "missing layer '" + layer + "' (" + list + ")") +
                       (fix.empty() ? "" : ": " + fix));
  }
  return problems;
}

std::vector<std::string> input_problems(const Frame& frame, const InputChannels& channels, const Frame* first,
                                        bool gradient_header) {
  std::vector<std::string> problems;
  if (first && (frame.width() != first->width() || frame.height() != first->height()))
    problems.push_back("size " + std::to_string(frame.width()) + "x" + std::to_string(frame.height()) + ", but " +
                       first->source + " is " + std::to_string(first->width()) + "x" + std::to_string(first->height()));
  const auto check = [&](const std::string& name, bool want_float) {
    const bool is_float = frame.float_channels().count(name) > 0, is_uint = frame.uint_channels().count(name) > 0;
    if (!is_float && !is_uint) return;  // missing: missing_layers said so
    if (is_float != want_float) {
      problems.push_back("channel '" + name + "' is " + (is_float ? "float" : "uint") + ", but the method reads it as " +
                         (want_float ? "float" : "uint"));
    } else if (want_float) {
      const FloatPlane& plane = frame.float_channel(name);
      size_t bad = 0, first_bad = 0;
      for (size_t i = 0; i < plane.data.size(); ++i)
        if (!std::isfinite(plane.data[i]) && bad++ == 0) first_bad = i;
      if (bad)
        problems.push_back("channel '" + name + "' holds NaN or infinity at " + std::to_string(bad) +
                           " pixels, the first at (" + std::to_string(first_bad % size_t(plane.width)) + ", " +
                           std::to_string(first_bad / size_t(plane.width)) + ")");
    }
  };
  for (const std::string& name : channels.floats) check(name, true);
  for (const std::string& name : channels.uints) check(name, false);
  for (std::string& missing : missing_layers(frame, channels)) problems.push_back(std::move(missing));
  if (gradient_header && !frame.attributes.count("rtdr.gradient.stratum_size"))
    problems.push_back("no header attribute rtdr.gradient.stratum_size: not rendered with gradient samples "
                       "(rtdr render --gradients)");
  return problems;
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
