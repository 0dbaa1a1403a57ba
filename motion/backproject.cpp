// Back-projected motion vectors [TRMV21 Eq. 1]. Conventions and sign in motion/backproject.h.
#include "motion/backproject.h"

#include "core/error.h"
#include "core/parallel.h"

#include <string>

namespace rtdr {

glm::vec2 backproject_pixel(const Scene& scene, const ScenePose& prev_pose, const View& prev_view,
                            const SurfaceSample& sample, glm::vec2 pixel_centre) {
  // T^{-1} P_i^{-1} x_i: the sample's point where its instance was in the previous frame.
  const glm::vec3 prev_world = world_point(scene, prev_pose, sample);
  // P_{i-1}: project it with the previous camera [TRMV21 Eq. 1].
  const glm::vec3 prev_screen = prev_view.project(prev_world);  // (x, y, depth)
  if (prev_screen.z < prev_view.znear) return glm::vec2(kMotionBehindCamera);  // no previous screen position
  // m(x_i) = x_{i-1} - x_i  [TRMV21 Sec. 3, after Eq. 1]
  return glm::vec2(prev_screen) - pixel_centre;
}

std::vector<glm::vec2> backproject_motion(const Scene& scene, const ScenePose& prev_pose, const View& prev_view,
                                          const VisibilityBuffer& cur_vis) {
  std::vector<glm::vec2> motion(size_t(cur_vis.width) * size_t(cur_vis.height), glm::vec2(0.0f));
  parallel_rows(cur_vis.height, [&](int y) {
    for (int x = 0; x < cur_vis.width; ++x) {
      const SurfaceSample s = cur_vis.sample(x, y);
      if (!s.valid()) continue;  // no surface: motion stays (0, 0)
      const glm::vec2 centre(float(x) + 0.5f, float(y) + 0.5f);
      motion[cur_vis.index(x, y)] = backproject_pixel(scene, prev_pose, prev_view, s, centre);
    }
  });
  return motion;
}

void write_motion(const std::vector<glm::vec2>& motion, Frame& frame) {
  if (motion.size() != size_t(frame.width()) * size_t(frame.height()))
    throw Error("write_motion: " + std::to_string(motion.size()) + " motion vectors for a " +
                std::to_string(frame.width()) + "x" + std::to_string(frame.height()) + " frame");
  frame.set_vec2("motion", motion);
}

void write_motion_layers(const Scene& scene, const FrameGeometry& g, Frame& frame) {
  write_motion(backproject_motion(scene, g.prev_pose, g.prev_view, g.vis), frame);
}

}  // namespace rtdr
