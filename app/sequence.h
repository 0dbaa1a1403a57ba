// Reading a rendered sequence (DIR/frame_NNNN.exr, as `rtdr render` writes it) frame by frame, with the
// checks every filter input needs: the layers a method reads exist, hold no NaN or infinity, and every
// frame has the first frame's size.
#pragma once

#include "app/commands.h"
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
// only the first frame's size and source, for core/exr_io.h's require_same_size.
struct SequenceShape {
  Frame first;
};

// Reads one frame as the input of a method that reads `channels`, the channels it may leave out filled with their
// defaults (filters/method.h fill_input_defaults), without checking the rest: for a frame read_filter_input has
// checked already.
Frame read_method_input(const std::string& path, const InputChannels& channels);

// Reads one frame and checks it as the input of a method that reads `channels` (Method::inputs()): each is
// present (or, in channels.defaults, filled with its default), of its type, and finite, and the frame's size is
// `shape`'s (the first frame read sets `shape`).
// Throws a one-line rtdr::Error naming the file(s).
Frame read_filter_input(const std::string& path, SequenceShape& shape, const InputChannels& channels);

// Each layer of `channels` that `frame` lacks in part or whole, one line each, naming the channels it lacks and, for
// a layer `rtdr render` writes only when asked, the flag that writes it (filters/method.h missing_layer_fix).
// Channels with a default are not missing. read_filter_input throws the first; input_problems lists them all.
std::vector<std::string> missing_layers(const Frame& frame, const InputChannels& channels);

// Everything wrong with one frame as the input of a method that reads `channels`, one line each, for rtdr check:
// each layer that lacks channels, with the channels it lacks (a channel with a default may be absent); each channel of the wrong type; each channel that
// holds NaN or infinity, with how many pixels and the first; a size other than `first`'s (when given); and, for
// `gradient_header`, a missing rtdr.gradient.stratum_size attribute. Empty when the frame is fine. Unlike
// read_filter_input it does not stop at the first problem.
std::vector<std::string> input_problems(const Frame& frame, const InputChannels& channels, const Frame* first,
                                        bool gradient_header);

// Checks a frame before it is written: every float channel is finite. Otherwise throws a one-line rtdr::Error
// naming `what` (the frame), the channel, the pass that wrote it (`pass_of(channel)`) and the pixel.
void require_finite_output(const Frame& frame, const std::string& what,
                           const std::function<std::string(const std::string& channel)>& pass_of);

}  // namespace rtdr
