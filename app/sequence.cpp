#include "app/sequence.h"

#include "core/error.h"
#include "core/exr_io.h"

#include <algorithm>
#include <charconv>
#include <filesystem>

namespace rtdr {

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
  if (shape.first_file.empty()) {
    shape = {frame.width(), frame.height(), path};
  } else if (frame.width() != shape.width || frame.height() != shape.height) {
    throw Error(path + " is " + std::to_string(frame.width()) + "x" + std::to_string(frame.height()) + " but " +
                shape.first_file + " is " + std::to_string(shape.width) + "x" + std::to_string(shape.height) +
                "; every frame of a sequence must have one size");
  }
  // Every float layer a method reads must be finite; ids are checked by their own readers.
  require_finite(frame, {"direct.R", "direct.G", "direct.B", "indirect.R", "indirect.G", "indirect.B", "albedo.R",
                         "albedo.G", "albedo.B", "emission.R", "emission.G", "emission.B", "depth.Z", "depth.dX",
                         "depth.dY", "normal.X", "normal.Y", "normal.Z", "motion.X", "motion.Y"});
  return frame;
}

}  // namespace rtdr
