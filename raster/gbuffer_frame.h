// One frame of the G-buffer sequence, as `rtdr render` writes it: rasterize the visibility buffer at the
// frame's time, resolve the G-buffer, back-project motion vectors to the previous frame [TRMV21 Eq. 1],
// and gather everything into the named layers of docs/buffers.md.
#pragma once

#include "core/frame.h"
#include "scenes/scene.h"

namespace rtdr {

// Frame `frame_index` is at t = frame_index / fps; its motion vectors point to frame_index - 1 (for
// frame 0 that is t = -1/fps, where animations hold their first key).
Frame render_gbuffer_frame(const Scene& scene, int frame_index, int width, int height);

}  // namespace rtdr
