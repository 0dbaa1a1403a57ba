// What a method requires of each input frame, written once: `rtdr filter`, `probe` and `compare` refuse a frame
// with the first problem found here (app/sequence.h read_filter_input), and `rtdr check` prints every one of them
// (app/cmd_check.cpp), so check says "ok" exactly where the method runs.
//
// The rules, for a method that reads `channels` (Method::inputs()):
// - every channel it reads is present (one it may leave out, in channels.defaults, takes its default), of its
//   type (an id stored as float is refused), and, for floats, finite;
// - when it reads gradient samples (gradient.source: asvgf, a-eaw), the header says the stratum size they were
//   made with (rtdr.gradient.stratum_size, 1 to 64: frame_stratum_size, filters/asvgf/gradient_image.h), and no
//   stratum holds two samples (trace/gradients.h keeps at most one per stratum; the reconstruction reads one).
// The size of a frame against the sequence's first is the sequence's rule (app/sequence.h).
#pragma once

#include "core/frame.h"
#include "filters/method.h"

#include <string>
#include <vector>

namespace rtdr {

// Every problem of `frame` as the input of a method that reads `channels`, one line each, in this order: the
// channels of the wrong type or not finite (with how many pixels and the first), the layers that lack channels,
// then the gradient samples' header and strata. Without the frame's name: the caller puts the file first.
// Empty when the frame is fine.
std::vector<std::string> input_problems(const Frame& frame, const InputChannels& channels);

// The strata of s x s pixels of `source` (gradient.source) that hold more than one gradient sample: empty when
// none does, else one line naming the first, its pixels and its samples, and how many more strata do.
std::vector<std::string> gradient_strata_problems(const UIntPlane& source, int s);

}  // namespace rtdr
