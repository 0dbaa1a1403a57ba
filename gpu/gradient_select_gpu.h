// The Vulkan ports of A-SVGF's gradient samples' integer steps [ASVGF18 Sec. 3.3] (trace/gradients.h, steps 2 and 5),
// run on the same inputs as the golden functions:
//   select_gradient_sources_vulkan  trace/gradient_select.comp, select_gradient_source at every stratum of frame i-1
//     in:  frame i-1 (PreviousFrame: id.instance, whether each pixel was a gradient sample, its direct and
//          indirect luminance), the gradient parameters (stratum_size, selection, seed_chains), the global seed and
//          frame i's index
//     out: per stratum of frame i-1 (ceil(W / s) x ceil(H / s), row-major) the selected source pixel j, or
//          kInvalidId
//   gradient_winners_vulkan         trace/gradient_merge.comp, gradient_winners
//     in:  the candidates (source j, target pixel jbar), as steps 3-4 leave them: forward projection and its
//          discard tests need the scene's geometry and run on the host (gradient_samples)
//     out: per stratum of frame i, the winning candidate's index and its j, or kInvalidId
// Both are integer work: bit-identical to the golden functions on every device (tests/gpu_gradient_select_test.cpp).
// The bindings: trace/gradient_select_shared.h, trace/gradient_merge_shared.h.
#pragma once

#include "gpu/vulkan_context.h"
#include "trace/gradients.h"

#include <cstdint>
#include <vector>

namespace rtdr {

// Step 2 [ASVGF18 Sec. 3.3]: select_gradient_source(prev, sx, sy, params, global_seed, frame_index) at every
// stratum (sx, sy) of frame i-1, at index sy ceil(W / s) + sx. Throws rtdr::Error for parameters out of range or
// planes of `prev` of another size than its visibility buffer. Writes the dispatch's device time in milliseconds
// to *ms (see ComputeBatch::total_time).
std::vector<uint32_t> select_gradient_sources_vulkan(VulkanContext& context, const PreviousFrame& prev,
                                                     const GradientParams& params, uint32_t global_seed,
                                                     int frame_index, double* ms = nullptr);

// What step 5 keeps, per stratum of frame i (row-major).
struct GradientWinners {
  std::vector<uint32_t> candidate;  // the index in the candidate list of the one that stays (gradient_winners)
  std::vector<uint32_t> source;     // its source pixel j; kInvalidId in both where no candidate lands
};

// Step 5 [ASVGF18 Sec. 3.3]: gradient_winners(candidates, s, ceil(width / s), ceil(height / s)) on the device, for
// a frame i of width x height pixels, with each winner's j beside it. Throws rtdr::Error for s < 1, a target outside
// the frame, or more candidates than one dispatch covers (64 x 65535). Writes the two dispatches' device time in
// milliseconds to *ms.
GradientWinners gradient_winners_vulkan(VulkanContext& context, const std::vector<GradientCandidate>& candidates,
                                        int width, int height, int stratum_size, double* ms = nullptr);

}  // namespace rtdr
