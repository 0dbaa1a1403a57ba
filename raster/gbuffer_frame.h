// One frame of the G-buffer sequence, as `rtdr render` writes it: rasterize the visibility buffer at the
// frame's time, resolve the G-buffer, and gather it into the named layers of docs/buffers.md. The motion
// layers come from the same geometry (write_motion_layers in motion/backproject.h).
#pragma once

#include "core/frame.h"
#include "raster/view.h"
#include "raster/visibility.h"
#include "scenes/scene.h"

namespace rtdr {

// The geometry of frame `index`: its time, its pose and the previous frame's (for motion vectors), both
// views, and the visibility buffer. Frame f is at t = f / fps; its motion vectors point to frame f - 1
// (for frame 0 that is t = -1/fps, where animations hold their first key).
struct FrameGeometry {
  int index = 0;
  ScenePose pose, prev_pose;
  View view, prev_view;
  VisibilityBuffer vis;
};

FrameGeometry rasterize_frame(const Scene& scene, int frame_index, int width, int height);

// Adds the G-buffer layers of `geometry` to `frame` (which has the same size).
void write_gbuffer_layers(const Scene& scene, const FrameGeometry& geometry, Frame& frame);

}  // namespace rtdr
