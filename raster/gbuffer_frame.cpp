#include "raster/gbuffer_frame.h"

#include "raster/backproject.h"
#include "raster/gbuffer.h"
#include "raster/view.h"
#include "raster/visibility.h"

namespace rtdr {

Frame render_gbuffer_frame(const Scene& scene, int frame_index, int width, int height) {
  const ScenePose pose = scene.pose(scene.time_of_frame(frame_index));
  const ScenePose prev_pose = scene.pose(scene.time_of_frame(frame_index - 1));
  const View view = make_view(scene, pose, width, height);
  const View prev_view = make_view(scene, prev_pose, width, height);

  const VisibilityBuffer vis = rasterize(scene, pose, view);
  Frame frame(width, height);
  write_gbuffer(resolve_gbuffer(scene, pose, view, vis), frame);
  // Motion vectors m(x_i) = x_{i-1} - x_i in pixels [TRMV21 Eq. 1].
  write_motion(backproject_motion(scene, prev_pose, prev_view, vis), frame);
  return frame;
}

}  // namespace rtdr
