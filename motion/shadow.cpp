// Shadow motion vectors [TRMV21 Eq. 3]. The equation, the choice of x_i and the validity rules are in
// motion/shadow.h.
#include "motion/shadow.h"

#include "core/error.h"
#include "core/parallel.h"

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

}  // namespace

InstanceMotion instance_motion(const glm::mat4& to_previous) {
  // A normal is carried by the inverse transpose of the point transform's linear part.
  return {to_previous, glm::transpose(glm::inverse(glm::mat3(to_previous)))};
}

std::vector<InstanceMotion> instance_to_previous(const ScenePose& pose, const ScenePose& prev_pose) {
  std::vector<InstanceMotion> out(pose.instance_to_world.size());
  for (size_t k = 0; k < out.size(); ++k)  // M_k(t_{i-1}) M_k(t_i)^{-1}
    out[k] = instance_motion(prev_pose.instance_to_world[k] * glm::inverse(pose.instance_to_world[k]));
  return out;
}

ShadowMotion shadow_motion_pixel(const ShadowRay& r, const std::vector<InstanceMotion>& to_previous, const View& view,
                                 const View& prev_view) {
  ShadowMotion out;
  if (r.receiver_instance == kInvalidId || r.blocker_instance == kInvalidId || r.light_instance == kInvalidId)
    return out;  // no surface, or the shadow ray reached the light: the pixel is not in shadow
  // s^_i: the current shadow point, where the shadow ray's own line meets the receiver's plane (motion/shadow.h).
  glm::vec3 s_hat;
  if (!intersect_shadow_line(r.light, r.blocker, r.receiver, r.receiver_normal, s_hat)) return out;

  // T^{-1} l_i, T^{-1} b_i and T^{-1} plane(s_i), each with its own instance's motion [TRMV21 Eq. 3].
  const InstanceMotion& T_receiver = to_previous[r.receiver_instance];
  const glm::vec3 l_prev = transform_point(to_previous[r.light_instance].to_previous, r.light);
  const glm::vec3 b_prev = transform_point(to_previous[r.blocker_instance].to_previous, r.blocker);
  const glm::vec3 s_prev = transform_point(T_receiver.to_previous, r.receiver);
  const glm::vec3 n_prev = T_receiver.normal_to_previous * r.receiver_normal;  // unit or not: only its direction counts
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

ShadowRayLayers::ShadowRayLayers(const Frame& frame)
    : light_id_(&frame.uint_channel("path.light.instance")), blocker_id_(&frame.uint_channel("path.blocker.instance")),
      receiver_id_(&frame.uint_channel("id.instance")) {
  static const char* const kAxes[3] = {"X", "Y", "Z"};
  for (int a = 0; a < 3; ++a) {
    light_[a] = &frame.float_channel(std::string("path.light.") + kAxes[a]);
    blocker_[a] = &frame.float_channel(std::string("path.blocker.") + kAxes[a]);
    position_[a] = &frame.float_channel(std::string("position.") + kAxes[a]);  // s_i (raster/gbuffer.cpp)
    normal_[a] = &frame.float_channel(std::string("geonormal.") + kAxes[a]);   // its face normal
  }
}

ShadowRay ShadowRayLayers::at(size_t i) const {
  ShadowRay r;
  if (blocker_id_->data[i] == kInvalidId) return r;  // lit, or no surface: no shadow, no vector
  const auto vec3_at = [i](const FloatPlane* const (&p)[3]) {
    return glm::vec3(p[0]->data[i], p[1]->data[i], p[2]->data[i]);
  };
  r.light = vec3_at(light_), r.blocker = vec3_at(blocker_);
  r.receiver = vec3_at(position_), r.receiver_normal = vec3_at(normal_);
  r.light_instance = light_id_->data[i], r.blocker_instance = blocker_id_->data[i];
  r.receiver_instance = receiver_id_->data[i];
  return r;
}

std::vector<ShadowMotion> shadow_motion(const FrameGeometry& g, const Frame& frame) {
  const ShadowRayLayers rays(frame);
  const std::vector<InstanceMotion> to_previous = instance_to_previous(g.pose, g.prev_pose);
  return motion_per_pixel<ShadowMotion>("shadow_motion", g, frame, [&](size_t i) {
    return shadow_motion_pixel(rays.at(i), to_previous, g.view, g.prev_view);
  });
}

void write_shadow_motion_layers(const FrameGeometry& g, Frame& frame) {
  const std::vector<ShadowMotion> m = shadow_motion(g, frame);
  write_motion_and_validity(frame, "motion.shadow", m);
}

}  // namespace rtdr
