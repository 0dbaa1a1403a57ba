// Reading a rendered sequence (DIR/frame_NNNN.exr, as `rtdr render` writes it) frame by frame, with the
// checks every filter input needs: the layers a method reads exist, hold no NaN or infinity, and every
// frame has the first frame's size.
#pragma once

#include "app/commands.h"
#include "core/error.h"
#include "core/frame.h"
#include "filters/method.h"

#include <functional>
#include <string>
#include <vector>

namespace rtdr {

struct SequenceFrame {
  int index;
  std::string path;
};

// The frames of DIR in index order, restricted to `range` when given ("" = all). Throws rtdr::Error when
// DIR is missing, holds no frame_NNNN.exr, lacks a frame of the range, or names one index twice
// (frame_001.exr beside frame_0001.exr).
std::vector<SequenceFrame> list_sequence(const std::string& dir, const std::string& range);

// frame_NNNN.<ext>, the name every command reads and writes frames under, and DIR/frame_NNNN.<ext>.
std::string frame_name(int index, const char* ext);
std::string frame_path(const std::string& dir, int index, const char* ext);

// The size of a sequence and the file that set it: every frame must match the first. `first` holds no planes,
// only the first frame's size and source, for the size rule of sequence_input_problems.
struct SequenceShape {
  Frame first;
};

// Reads one frame as the input of a method that reads `channels`, the channels it may leave out filled with their
// defaults (filters/method.h fill_input_defaults), without checking the rest: for a frame read_filter_input has
// checked already.
Frame read_method_input(const std::string& path, const InputChannels& channels);

// Everything wrong with one frame of a sequence as the input of a method that reads `channels`, one line each:
// a size other than `first`'s (when given), then every problem filters/input_check.h finds. Empty when the frame
// is fine. rtdr check prints them all; read_filter_input refuses the first: both are this one list.
std::vector<std::string> sequence_input_problems(const Frame& frame, const InputChannels& channels, const Frame* first);

// Reads one frame and checks it as the input of a method that reads `channels` (Method::inputs()): a channel it
// may leave out is filled with its default, and the first of sequence_input_problems (against the first frame
// read, which sets `shape`) throws a one-line rtdr::Error "<path>: <problem>".
Frame read_filter_input(const std::string& path, SequenceShape& shape, const InputChannels& channels);

// Runs `step` (the filtering of frame `f`) and returns what it returns; an rtdr::Error it throws is said to be
// about that frame: "<path>: <message>", unless the message names the file already.
template <class Step>
auto about_frame(const SequenceFrame& f, Step&& step) {
  try {
    return step();
  } catch (const Error& e) {
    const std::string message = e.what();
    if (message.find(f.path) != std::string::npos) throw;
    throw Error(f.path + ": " + message);
  }
}

// Checks a frame before it is written: every float channel is finite. Otherwise throws a one-line rtdr::Error
// naming `what` (the frame), the channel, the pass that wrote it (`pass_of(channel)`) and the pixel.
void require_finite_output(const Frame& frame, const std::string& what,
                           const std::function<std::string(const std::string& channel)>& pass_of);

}  // namespace rtdr
