// Shadow motion vectors [TRMV21 Eq. 3]. The equation, the choice of x_i and the validity rules are in
// motion/shadow.h.
#include "motion/shadow.h"

#include "core/error.h"
#include "core/parallel.h"
#include "motion/shadow_splat.h"

#include <cmath>
#include <string>

namespace rtdr {
namespace {

// Where the line p(t) = l + t (b - l) meets the plane through s with normal n: t = n.(s - l) / n.(b - l).
// False when the line is (nearly) parallel to the plane, or when the plane is not beyond the blocker (t <= 1).
bool intersect_shadow_line(const glm::vec3& l, const glm::vec3& b, const glm::vec3& s, const glm::vec3& n,
                           glm::vec3& point) {
  const glm::vec3 lb = b - l;
  const float n_dot_lb = glm::dot(n, lb);
  if (std::abs(n_dot_lb) <= kShadowParallelCosine * glm::length(lb)) return false;  // parallel to the plane
  const float t = glm::dot(n, s - l) / n_dot_lb;
  if (!(t > 1.0f)) return false;  // the receiver is not beyond the blocker, seen from the light
  point = l + t * lb;
  return true;
}

glm::vec3 transform_point(const glm::mat4& m, const glm::vec3& p) { return glm::vec3(m * glm::vec4(p, 1.0f)); }

// A normal carried by the point transform m: the inverse transpose of its linear part.
glm::vec3 transform_normal(const glm::mat4& m, const glm::vec3& n) {
  return glm::normalize(glm::transpose(glm::inverse(glm::mat3(m))) * n);
}

// The receiver's face normal at `pose`, from the triangle's world-space corners (unit, either orientation).
glm::vec3 face_normal(const Scene& scene, const ScenePose& pose, uint32_t instance, uint32_t triangle) {
  const Mesh& mesh = scene.meshes[size_t(scene.instances[instance].mesh)];
  const glm::uvec3& tri = mesh.triangles[triangle];
  const glm::mat4& m = pose.instance_to_world[instance];
  const glm::vec3 p0 = transform_point(m, mesh.positions[tri[0]]);
  const glm::vec3 p1 = transform_point(m, mesh.positions[tri[1]]);
  const glm::vec3 p2 = transform_point(m, mesh.positions[tri[2]]);
  return glm::normalize(glm::cross(p1 - p0, p2 - p0));
}

}  // namespace

std::vector<glm::mat4> instance_to_previous(const ScenePose& pose, const ScenePose& prev_pose) {
  std::vector<glm::mat4> out(pose.instance_to_world.size());
  for (size_t k = 0; k < out.size(); ++k)
    out[k] = prev_pose.instance_to_world[k] * glm::inverse(pose.instance_to_world[k]);  // M_k(t_{i-1}) M_k(t_i)^{-1}
  return out;
}

ShadowMotion shadow_motion_pixel(const ShadowRay& r, const std::vector<glm::mat4>& to_previous, const View& view,
                                 const View& prev_view) {
  ShadowMotion out;
  if (r.receiver_instance == kInvalidId || r.blocker_instance == kInvalidId || r.light_instance == kInvalidId)
    return out;  // no surface, or the shadow ray reached the light: the pixel is not in shadow
  // s^_i: the current shadow point, where the shadow ray's own line meets the receiver's plane (motion/shadow.h).
  glm::vec3 s_hat;
  if (!intersect_shadow_line(r.light, r.blocker, r.receiver, r.receiver_normal, s_hat)) return out;

  // T^{-1} l_i, T^{-1} b_i and T^{-1} plane(s_i), each with its own instance's motion [TRMV21 Eq. 3].
  const glm::mat4& T_light = to_previous[r.light_instance];
  const glm::mat4& T_blocker = to_previous[r.blocker_instance];
  const glm::mat4& T_receiver = to_previous[r.receiver_instance];
  const glm::vec3 l_prev = transform_point(T_light, r.light);
  const glm::vec3 b_prev = transform_point(T_blocker, r.blocker);
  const glm::vec3 s_prev = transform_point(T_receiver, r.receiver);
  const glm::vec3 n_prev = transform_normal(T_receiver, r.receiver_normal);
  // intersect[T^{-1} l_i -> T^{-1} b_i ; T^{-1} plane(s_i)]: the shadow point in the previous frame.
  glm::vec3 s_hat_prev;
  if (!intersect_shadow_line(l_prev, b_prev, s_prev, n_prev, s_hat_prev)) return out;

  // x^V_{i-1} = P_{i-1}(...), and m^V = x^V_{i-1} - x_i with x_i = P_i(s^_i) [TRMV21 Eq. 3].
  const glm::vec3 x_prev = prev_view.project(s_hat_prev);  // (x, y, depth)
  if (x_prev.z < prev_view.znear) return out;  // behind the previous camera: no previous screen position
  const glm::vec3 x_cur = view.project(s_hat);
  out.motion = glm::vec2(x_prev) - glm::vec2(x_cur);
  out.valid = true;
  return out;
}

std::vector<ShadowRay> shadow_rays(const Scene& scene, const FrameGeometry& g, const Frame& frame) {
  const VisibilityBuffer& vis = g.vis;
  if (frame.width() != vis.width || frame.height() != vis.height)
    throw Error("shadow_rays: a " + std::to_string(frame.width()) + "x" + std::to_string(frame.height()) +
                " frame for a " + std::to_string(vis.width) + "x" + std::to_string(vis.height) + " geometry");
  const std::vector<glm::vec3> light = frame.get_vec3("path.light");
  const std::vector<glm::vec3> blocker = frame.get_vec3("path.blocker");
  const UIntPlane& light_id = frame.uint_channel("path.light.instance");
  const UIntPlane& blocker_id = frame.uint_channel("path.blocker.instance");
  std::vector<ShadowRay> rays(light.size());
  parallel_rows(vis.height, [&](int y) {
    for (int x = 0; x < vis.width; ++x) {
      const size_t i = vis.index(x, y);
      const SurfaceSample s = vis.sample(x, y);
      if (!s.valid()) continue;
      ShadowRay& r = rays[i];
      r.light = light[i], r.light_instance = light_id.data[i];
      r.blocker = blocker[i], r.blocker_instance = blocker_id.data[i];
      r.receiver = world_point(scene, g.pose, s);
      r.receiver_normal = face_normal(scene, g.pose, s.instance, s.triangle);
      r.receiver_instance = s.instance;
    }
  });
  return rays;
}

std::vector<ShadowMotion> shadow_motion(const Scene& scene, const FrameGeometry& g, const Frame& frame) {
  const std::vector<ShadowRay> rays = shadow_rays(scene, g, frame);
  const std::vector<glm::mat4> to_previous = instance_to_previous(g.pose, g.prev_pose);
  std::vector<ShadowMotion> out(rays.size());
  parallel_rows(g.vis.height, [&](int y) {
    for (int x = 0; x < g.vis.width; ++x) {
      const size_t i = g.vis.index(x, y);
      out[i] = shadow_motion_pixel(rays[i], to_previous, g.view, g.prev_view);
    }
  });
  return out;
}

void write_shadow_motion_layers(const Scene& scene, const FrameGeometry& g, Frame& frame) {
  const std::vector<ShadowMotion> m = shadow_motion(scene, g, frame);
  std::vector<glm::vec2> motion(m.size());
  UIntPlane& valid = frame.add_uint("motion.shadow.valid");
  for (size_t i = 0; i < m.size(); ++i) motion[i] = m[i].motion, valid.data[i] = m[i].valid ? 1u : 0u;
  frame.set_vec2("motion.shadow", motion);
  const std::vector<SplatMotion> splat =
      splat_shadow_motion(m, frame.get_vec2("motion"), g.vis.depth, g.vis.width, g.vis.height, kShadowSplatSize);
  std::vector<glm::vec2> splat_motion(splat.size());
  UIntPlane& landed = frame.add_uint("motion.shadow_splat.valid");
  for (size_t i = 0; i < splat.size(); ++i) splat_motion[i] = splat[i].motion, landed.data[i] = splat[i].landed ? 1u : 0u;
  frame.set_vec2("motion.shadow_splat", splat_motion);
}

}  // namespace rtdr
