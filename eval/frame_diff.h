// How far one frame is from another, channel by channel: the error report `rtdr compare` prints for a shader
// port against the golden passes, over every output and intermediate buffer they both write (docs/buffers.md).
//
// For each float channel, the largest absolute difference |test - reference| and the largest relative one,
// |test - reference| / max(|reference|, rel_floor), each with the pixel where it is reached and the two values
// there. The floor keeps a near-zero reference from turning a tiny difference into a huge ratio; the port tests
// use 1e-2 for colours (tests/gpu_svgf_test.cpp). Equal values differ by 0, infinities included; a NaN on either
// side differs by infinity, so it is always the worst pixel.
#pragma once

#include "core/frame.h"

#include <string>
#include <vector>

namespace rtdr {

// The worst pixel of one channel by one measure: the error there, where (first in row order among equals), and
// the two values. x = y = -1 while no pixel differs.
struct PixelError {
  double error = 0.0;
  int x = -1, y = -1;
  float test = 0.0f, reference = 0.0f;
};

struct ChannelDiff {
  std::string channel;
  PixelError abs;  // |test - reference|
  PixelError rel;  // |test - reference| / max(|reference|, rel_floor)
};

// The difference between test and reference values, and relative to max(|reference|, rel_floor), as above.
double abs_difference(float test, float reference);
double rel_difference(float test, float reference, double rel_floor);

// Every float channel of `reference` against the same channel of `test`, in name order. Throws rtdr::Error when
// the frames' sizes differ, when a float channel is in one frame and not in the other (naming it), or when
// rel_floor is not positive. Uint channels (ids) are not compared.
std::vector<ChannelDiff> diff_channels(const Frame& test, const Frame& reference, double rel_floor);

// Replaces `worst` by `candidate` when the candidate's error is larger (so the first wins a tie), and says whether
// it did: for the worst pixel over several frames.
bool keep_worst(PixelError& worst, const PixelError& candidate);

}  // namespace rtdr
