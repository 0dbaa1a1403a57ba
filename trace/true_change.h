// The true temporal change of a frame's shading, to measure A-SVGF's gradient estimate against [ASVGF18 Eq. 2].
//
// A-SVGF estimates delta = f_i(G~) - f_{i-1}(G) from one re-shaded sample per stratum (trace/gradients.h). Here
// every pixel's surface sample G_i (frame i's visibility buffer) is shaded a second time, under frame i-1's scene
// pose, lights and eye, with the same spp and the same seeds as the frame itself:
//   truth.prev_direct, truth.prev_indirect = f_{i-1}(G_i), demodulated like direct and indirect
// so that direct - truth.prev_direct is the change the lighting made to that surface point between the two frames,
// with the noise of spp samples and, the seeds being shared, none at all where nothing changed. Rendered at a
// reference's spp (rtdr render --spp N --true-change), it is what lambda [ASVGF18 Eq. 14] should have measured.
//
// Choices: the point is G_i moved with its instance to t_{i-1} (a surface sample names a point independent of
// pose); frame 0 is compared with the pose at t = -1 / fps.
#pragma once

#include "core/frame.h"
#include "scenes/scene.h"
#include "trace/render_frame.h"

namespace rtdr {

// render_frame() with the truth.prev_* layers added, its header the render key plus rtdr.true_change = 1.
Frame render_true_change_frame(const Scene& scene, int frame_index, int width, int height,
                               const RenderSettings& settings, TraceStats* stats = nullptr);

}  // namespace rtdr
