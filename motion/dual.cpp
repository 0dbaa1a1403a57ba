// Dual motion vectors [TRMV21 Eq. 6]. The equation and the choices are in motion/dual.h.
#include "motion/dual.h"

#include "core/error.h"
#include "core/parallel.h"
#include "motion/forward_project.h"

#include <cmath>
#include <string>

namespace rtdr {

DualMotion dual_motion_pixel(const Scene& scene, const FrameGeometry& g, const VisibilityBuffer& prev_vis, int x,
                             int y, glm::vec2 surface_motion) {
  DualMotion out;
  out.motion = surface_motion;  // x^O = y wherever Eq. 6 does not apply
  const SurfaceSample s = g.vis.sample(x, y);
  if (!s.valid()) return out;

  // y = x_i + m: where this pixel's surface point was in frame i-1 [TRMV21 Eq. 1].
  const glm::vec2 x_i = glm::vec2(float(x), float(y)) + 0.5f;
  const glm::vec2 y_prev = x_i + surface_motion;
  const int qx = int(std::floor(y_prev.x)), qy = int(std::floor(y_prev.y));
  if (qx < 0 || qy < 0 || qx >= prev_vis.width || qy >= prev_vis.height) return out;  // came in at the border

  // Disoccluded: in frame i-1 something nearer stood at y (motion/dual.h, the depth test).
  const float depth_prev = g.prev_view.project(world_point(scene, g.prev_pose, s)).z;
  const size_t q = prev_vis.index(qx, qy);
  const float visible_depth = prev_vis.depth[q];
  if (!(visible_depth > 0.0f && visible_depth < depth_prev * (1.0f - kForwardProjectionDepthTolerance))) return out;

  // The occluder's point at y: y' where it was, z = P_i T(y) P_{i-1}^{-1} y where it is now [TRMV21 Eq. 6].
  const SurfaceSample occluder = prev_vis.sample(qx, qy);
  const glm::vec2 y_occluder = glm::vec2(g.prev_view.project(world_point(scene, g.prev_pose, occluder)));
  const ForwardProjection z = forward_project(scene, g.pose, g.view, g.vis, occluder);
  if (z.depth < g.view.znear) return out;  // the occluder left through the near plane: no z
  // x^O_{i-1} = y + (x_i - z), with the occluder's motion v = z - y' taken at its own point.
  const glm::vec2 v = z.screen - y_occluder;
  out.motion = (y_prev - v) - x_i;
  out.disoccluded = true;
  return out;
}

VisibilityBuffer previous_visibility(const Scene& scene, const FrameGeometry& g) {
  return rasterize(scene, g.prev_pose, g.prev_view);
}

std::vector<DualMotion> dual_motion(const Scene& scene, const FrameGeometry& g,
                                    const std::vector<glm::vec2>& surface_motion) {
  const size_t pixels = size_t(g.vis.width) * size_t(g.vis.height);
  if (surface_motion.size() != pixels)
    throw Error("dual_motion: " + std::to_string(surface_motion.size()) + " motion vectors for a " +
                std::to_string(g.vis.width) + "x" + std::to_string(g.vis.height) + " frame");
  const VisibilityBuffer prev_vis = previous_visibility(scene, g);  // one extra raster pass per frame
  std::vector<DualMotion> out(pixels);
  parallel_rows(g.vis.height, [&](int y) {
    for (int x = 0; x < g.vis.width; ++x) {
      const size_t i = g.vis.index(x, y);
      out[i] = dual_motion_pixel(scene, g, prev_vis, x, y, surface_motion[i]);
    }
  });
  return out;
}

void write_dual_motion_layers(const Scene& scene, const FrameGeometry& g, Frame& frame) {
  const std::vector<DualMotion> m = dual_motion(scene, g, frame.get_vec2("motion"));
  std::vector<glm::vec2> motion(m.size());
  UIntPlane& valid = frame.add_uint("motion.dual.valid");
  for (size_t i = 0; i < m.size(); ++i) motion[i] = m[i].motion, valid.data[i] = m[i].disoccluded ? 1u : 0u;
  frame.set_vec2("motion.dual", motion);
}

}  // namespace rtdr
