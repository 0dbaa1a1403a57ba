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

// DIR/frame_NNNN.<ext>, the name every command reads and writes frames under.
std::string frame_path(const std::string& dir, int index, const char* ext);

// Creates an --out directory (and its parents); throws rtdr::Error when that is impossible.
void make_output_dir(const std::string& dir);

// The size of a sequence and the file that set it: every frame must match the first. `first` holds no planes,
// only the first frame's size and source, for core/exr_io.h's require_same_size.
struct SequenceShape {
  Frame first;
};

// Reads one frame and checks it as filter input: its layers are finite, and its size is `shape`'s (the first
// frame read sets `shape`). Throws a one-line rtdr::Error naming the file(s).
Frame read_filter_input(const std::string& path, SequenceShape& shape);

}  // namespace rtdr
