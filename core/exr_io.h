// Multi-layer OpenEXR files <-> Frames, and the checks every pass runs on the frames it reads.
//
// One Frame is one EXR file: each channel "layer.channel" (docs/buffers.md) is an EXR channel of the same
// name, which is how multi-layer EXR names its layers (OpenEXR "Interpreting OpenEXR Images", layers).
// Float channels are stored as 32-bit FLOAT and uint channels as UINT, with ZIP compression, so a round
// trip is bit-exact (kInvalidId included). Reading also accepts HALF channels (what most engines write)
// and widens them to float.
#pragma once

#include "core/frame.h"

#include <string>
#include <vector>

namespace rtdr {

// Writes every channel of `frame`, and its attributes as string attributes of the header, to `path`, atomically (core/atomic_file.h): on failure nothing appears
// at `path` and rtdr::Error names the file.
void write_exr(const std::string& path, const Frame& frame);

// Reads a scanline or tiled EXR whose data window starts at (0, 0). FLOAT and HALF channels become float
// channels, UINT channels become uint channels; string attributes whose names start with "rtdr." become
// Frame::attributes. Sets Frame::source to `path`. Any problem (missing file, not a regular file (a FIFO is
// refused at once, core/regular_file.h), not an EXR, truncated, more pixels than the file can hold or memory can
// take (core/exr_checks.h), subsampled channels, an offset data window) throws a one-line rtdr::Error naming
// the file.
Frame read_exr(const std::string& path);

// Throws a one-line rtdr::Error naming the frame's source, the channel and the first pixel (in row order)
// holding a NaN or an infinity, among the float channels listed. Uint channels are always finite.
void require_finite(const Frame& frame, const std::vector<std::string>& channels);

// Throws a one-line rtdr::Error naming both sources and sizes when the frames differ in width or height.
void require_same_size(const Frame& a, const Frame& b);

}  // namespace rtdr
