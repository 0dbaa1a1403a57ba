// Forward projection of a surface sample [ASVGF18 Sec. 3.1, 3.3]. Conventions in motion/forward_project.h.
#include "motion/forward_project.h"

#include <cmath>

namespace rtdr {

ForwardProjection forward_project(const Scene& scene, const ScenePose& cur_pose, const View& cur_view,
                                  const VisibilityBuffer& cur_vis, const SurfaceSample& prev_sample,
                                  float depth_tolerance) {
  ForwardProjection f;
  // The same point on the same triangle, where its instance is now [ASVGF18 Sec. 3.1].
  const glm::vec3 world = world_point(scene, cur_pose, prev_sample);
  // Its screen position and depth in the current frame.
  const glm::vec3 projected = cur_view.project(world);
  f.screen = glm::vec2(projected);
  f.depth = projected.z;
  if (!(f.depth >= cur_view.znear)) return f;  // behind the camera (or NaN): no screen position
  // Off screen, tested as floats first (false for NaN too): a sample far off screen, or a previous frame's
  // barycentrics of 1e30 read from a file, would put floor() beyond the range of an int.
  if (!(f.screen.x >= 0.0f && f.screen.y >= 0.0f && f.screen.x < float(cur_vis.width) &&
        f.screen.y < float(cur_vis.height)))
    return f;
  // The pixel whose square [x, x+1) x [y, y+1) contains it.
  const int x = int(std::floor(f.screen.x)), y = int(std::floor(f.screen.y));
  if (x < 0 || y < 0 || x >= cur_vis.width || y >= cur_vis.height) return f;
  f.on_screen = true;
  f.pixel = {x, y};
  // Occlusion against the current depth buffer [ASVGF18 Sec. 3.3]: something visibly nearer covers the pixel.
  const float visible_depth = cur_vis.depth[cur_vis.index(x, y)];
  f.occluded = visible_depth > 0.0f && visible_depth < f.depth * (1.0f - depth_tolerance);
  return f;
}

}  // namespace rtdr
