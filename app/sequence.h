// Reading a rendered sequence (DIR/frame_NNNN.exr, as `rtdr render` writes it) frame by frame, with the
// checks every filter input needs: the layers a method reads exist, hold no NaN or infinity, and every
// frame has the first frame's size.
#pragma once

#include "app/commands.h"
#include "core/frame.h"

#include <string>
#include <vector>

namespace rtdr {

struct SequenceFrame {
  int index;
  std::string path;
};

// The frames of DIR in index order, restricted to `range` when given ("" = all). Throws rtdr::Error when
// DIR is missing, holds no frame_NNNN.exr, or lacks a frame of the range.
std::vector<SequenceFrame> list_sequence(const std::string& dir, const std::string& range);

// Reads one frame and checks it as filter input against the first frame's size (first = nullptr for the
// first frame itself).
Frame read_filter_input(const std::string& path, const Frame* first);

}  // namespace rtdr
