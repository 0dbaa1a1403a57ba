#include "app/sequence.h"

#include "core/error.h"
#include "core/exr_io.h"

#include <algorithm>
#include <charconv>
#include <cstdio>
#include <filesystem>

namespace rtdr {

std::string frame_path(const std::string& dir, int index, const char* ext) {
  char name[32];
  std::snprintf(name, sizeof name, "frame_%04d.%s", index, ext);
  return (std::filesystem::path(dir) / name).string();
}

void make_output_dir(const std::string& dir) {
  std::error_code ec;
  std::filesystem::create_directories(dir, ec);
  if (ec || !std::filesystem::is_directory(dir))
    throw Error("--out '" + dir + "' is not a directory that can be created (" + ec.message() + ")");
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
  std::sort(frames.begin(), frames.end(), [](const SequenceFrame& a, const SequenceFrame& b) { return a.index < b.index; });
  if (frames.empty()) throw Error("--in '" + dir + "' holds no frame_NNNN.exr (write some with rtdr render)");
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

Frame read_filter_input(const std::string& path, SequenceShape& shape) {
  Frame frame = read_exr(path);
  if (shape.first.source.empty()) {
    shape.first = Frame(frame.width(), frame.height());
    shape.first.source = path;
  } else {
    require_same_size(shape.first, frame);  // names both files
  }
  // Every float layer a method reads must be finite; ids are checked by their own readers.
  require_finite(frame, {"direct.R", "direct.G", "direct.B", "indirect.R", "indirect.G", "indirect.B", "albedo.R",
                         "albedo.G", "albedo.B", "emission.R", "emission.G", "emission.B", "depth.Z", "depth.dX",
                         "depth.dY", "normal.X", "normal.Y", "normal.Z", "motion.X", "motion.Y"});
  return frame;
}

}  // namespace rtdr
