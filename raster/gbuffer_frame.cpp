#include "raster/gbuffer_frame.h"

#include "raster/gbuffer.h"

namespace rtdr {

FrameGeometry rasterize_frame(const Scene& scene, int frame_index, int width, int height) {
  FrameGeometry g;
  g.index = frame_index;
  g.pose = scene.pose(scene.time_of_frame(frame_index));
  g.prev_pose = scene.pose(scene.time_of_frame(frame_index - 1));
  g.view = make_view(scene, g.pose, width, height);
  g.prev_view = make_view(scene, g.prev_pose, width, height);
  g.vis = rasterize(scene, g.pose, g.view);
  return g;
}

void write_gbuffer_layers(const Scene& scene, const FrameGeometry& g, Frame& frame) {
  write_gbuffer(resolve_gbuffer(scene, g.pose, g.view, g.vis), frame);
}

}  // namespace rtdr
