// Glossy reflection motion vectors [TRMV21 Eq. 5]. The equation, the lobe width, the choice of x_i and the
// validity rules are in motion/glossy.h.
#include "motion/glossy.h"

#include "core/error.h"
#include "core/geometry.h"
#include "core/parallel.h"
#include "core/sampler.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <string>

namespace rtdr {
namespace {

// A planar mirror seen from an eye: the virtual image of a point, and where the eye sees it on the plane.
struct MirrorImage {
  glm::vec3 image{0.0f};           // v = mirror[h, plane]
  glm::vec3 specular_point{0.0f};  // s^C: where the segment eye -> v crosses the plane
  glm::vec3 normal{0.0f};          // the plane's unit normal, turned to the eye's side
  glm::vec3 incidence{0.0f};       // the unit direction eye -> v
  float cos_incidence = 0.0f;      // cos i = |n . (v - eye)| / |v - eye|
  float distance = 0.0f;           // d = |v - s^C|, the lobe's length from the image to the plane
};

// Mirrors h across the plane through s with normal n, seen from `eye` [TRMV21 Eq. 5, mirror[.]]. False when the
// eye and h are not strictly on one side of the plane (the eye sees no reflection of h in it) or when the line
// eye -> v is (nearly) parallel to the plane.
bool mirror_in_plane(const glm::vec3& eye, const glm::vec3& h, const glm::vec3& s, glm::vec3 n, MirrorImage& out) {
  n = glm::normalize(n);
  float eye_height = glm::dot(n, eye - s);  // signed distances to the plane
  float h_height = glm::dot(n, h - s);
  if (!(eye_height * h_height > 0.0f)) return false;  // opposite sides, or on the plane: nothing is reflected
  if (eye_height < 0.0f) n = -n, eye_height = -eye_height, h_height = -h_height;  // n towards the eye
  const glm::vec3 v = h - 2.0f * h_height * n;  // the virtual image, h_height behind the plane
  const glm::vec3 eye_to_v = v - eye;
  const float length = glm::length(eye_to_v);
  const float n_dot_line = glm::dot(n, eye_to_v);  // = -(eye_height + h_height) < 0
  if (std::abs(n_dot_line) <= kGlossyParallelCosine * length) return false;  // grazing: parallel to the plane
  // The line eye + t (v - eye) is eye_height - t (eye_height + h_height) above the plane: 0 at this t, in (0, 1).
  const float t = eye_height / (eye_height + h_height);
  out.image = v;
  out.specular_point = eye + t * eye_to_v;
  out.normal = n;
  out.incidence = eye_to_v / length;
  out.cos_incidence = -n_dot_line / length;
  out.distance = (1.0f - t) * length;
  return true;
}

// The lobe's footprint in the image [TRMV21 Sec. 4.2, "tracking the endpoints of major and minor axes"]: the cone
// of half-angle sigma_theta from v around v -> s^C cuts the plane in an ellipse around s^C; each semi-axis's two
// endpoints are projected and halved. Columns a1 (in the plane of incidence) and a2 (perpendicular to it), in
// pixels. False when the lobe is too wide to meet the plane in an ellipse, or an endpoint is behind the camera.
bool footprint_axes(const MirrorImage& m, float sigma_theta, const View& view, glm::mat2& axes) {
  // The cone meets the plane in a bounded ellipse only while it stays above the plane's horizon: its axis makes
  // the angle pi/2 - i with the plane, so sigma_theta < pi/2 - i. A wider lobe has no footprint (motion/glossy.h).
  const float axis_to_plane = std::asin(std::clamp(m.cos_incidence, 0.0f, 1.0f));  // pi/2 - i
  if (!(sigma_theta < axis_to_plane)) return false;
  // t1: the plane of incidence's trace on the mirror (the incidence direction with its normal part removed).
  glm::vec3 t1 = m.incidence - glm::dot(m.normal, m.incidence) * m.normal;
  if (glm::length(t1) < kGlossyNormalIncidence) {  // normal incidence: the ellipse is a circle, any tangent will do
    glm::vec3 unused;
    orthonormal_basis(m.normal, t1, unused);
  }
  t1 = glm::normalize(t1);
  const glm::vec3 t2 = glm::cross(m.normal, t1);
  // Semi-axes on the plane: d tan(sigma_theta) across, stretched by 1 / cos i along the plane of incidence.
  const float r_across = m.distance * std::tan(sigma_theta);
  const float r_along = r_across / m.cos_incidence;
  const glm::vec3 semi_axes[2] = {r_along * t1, r_across * t2};
  for (int k = 0; k < 2; ++k) {
    const glm::vec3 plus = view.project(m.specular_point + semi_axes[k]);  // (x, y, depth)
    const glm::vec3 minus = view.project(m.specular_point - semi_axes[k]);
    if (plus.z < view.znear || minus.z < view.znear) return false;  // the footprint reaches behind the camera
    axes[k] = 0.5f * (glm::vec2(plus) - glm::vec2(minus));         // column k
  }
  return true;
}

glm::vec3 transform_point(const glm::mat4& m, const glm::vec3& p) { return glm::vec3(m * glm::vec4(p, 1.0f)); }

}  // namespace

float glossy_lobe_angle(float alpha) { return 2.0f * std::atan(kGgxLobeTanPerAlpha * alpha); }

glm::vec2 glossy_normal_pair(uint32_t seed) {
  // Two uniform numbers of a sequence of Eq. 5's own, then Box-Muller (Box and Muller 1958).
  const glm::vec2 u = Sampler(hash_combine(seed, kGlossyStream), 0).next_2d();
  const float radius = std::sqrt(-2.0f * std::log(1.0f - u.x));  // 1 - u.x in (0, 1]: the log is finite
  const float phi = 2.0f * std::numbers::pi_v<float> * u.y;
  return {radius * std::cos(phi), radius * std::sin(phi)};
}

GlossyMotion glossy_motion_pixel(const GlossyRay& r, const std::vector<InstanceMotion>& to_previous, const View& view,
                                 const View& prev_view) {
  GlossyMotion out;
  if (r.reflector_instance == kInvalidId || r.hit_instance == kInvalidId)
    return out;  // no surface, or its BSDF ray escaped: nothing is reflected
  // x_i = P_i(v_i), the current virtual image of h_i in the current plane of s_i (motion/glossy.h says why).
  MirrorImage now;
  if (!mirror_in_plane(view.eye, r.hit, r.reflector, r.reflector_normal, now)) return out;
  const glm::vec3 x_cur = view.project(now.image);  // (x, y, depth)
  if (x_cur.z < view.znear) return out;
  const float sigma_theta = glossy_lobe_angle(ggx_alpha(r.roughness));
  // The lobe's footprint in this frame's image: steps (2)-(4) with v_i and P_i (the glossy filter's kernel).
  glm::mat2 axes_now;
  if (footprint_axes(now, sigma_theta, view, axes_now)) {
    out.footprint_axes = axes_now;
    out.footprint = axes_now * glm::transpose(axes_now);  // b1 b1^T + b2 b2^T
    out.has_footprint = true;
  }

  // (1) T^{-1} h_i and T^{-1} plane(s_i), each with its own instance's motion [TRMV21 Eq. 5].
  const InstanceMotion& T_reflector = to_previous[r.reflector_instance];
  const glm::vec3 h_prev = transform_point(to_previous[r.hit_instance].to_previous, r.hit);
  const glm::vec3 s_prev = transform_point(T_reflector.to_previous, r.reflector);
  const glm::vec3 n_prev = T_reflector.normal_to_previous * r.reflector_normal;
  // (2) mirror[T^{-1} h_i, T^{-1} plane(s_i)]: the virtual image v, and the specular point s^C on the segment
  // eye_{i-1} -> v.
  MirrorImage before;
  if (!mirror_in_plane(prev_view.eye, h_prev, s_prev, n_prev, before)) return out;
  // (3) mu = P_{i-1}(v), the footprint's centre [TRMV21 Eq. 5].
  const glm::vec3 mu = prev_view.project(before.image);
  if (mu.z < prev_view.znear) return out;  // behind the previous camera: no previous screen position
  // (4) Sigma: the GGX lobe of s_i's roughness, sigma_theta = 2 atan(1.458 alpha), traced from v to the plane.
  glm::mat2 axes;
  if (!footprint_axes(before, sigma_theta, prev_view, axes)) return out;

  // (5) x^R_{i-1} = sample(mu, Sigma) = mu + a1 n1 + a2 n2, and m^R = x^R_{i-1} - x_i [TRMV21 Eq. 5].
  out.mu = glm::vec2(mu) - glm::vec2(x_cur);
  out.axes = axes;
  out.Sigma = axes * glm::transpose(axes);  // a1 a1^T + a2 a2^T
  out.motion = out.mu + axes * glossy_normal_pair(r.seed);
  out.valid = true;
  return out;
}

GlossyRayLayers::GlossyRayLayers(const Frame& frame)
    : roughness_(&frame.float_channel("material.roughness")),
      secondary_id_(&frame.uint_channel("path.secondary.instance")), reflector_id_(&frame.uint_channel("id.instance")),
      seed_(&frame.uint_channel("rng.seed")) {
  static const char* const kAxes[3] = {"X", "Y", "Z"};
  for (int a = 0; a < 3; ++a) {
    secondary_[a] = &frame.float_channel(std::string("path.secondary.") + kAxes[a]);  // h_i
    position_[a] = &frame.float_channel(std::string("position.") + kAxes[a]);        // s_i (raster/gbuffer.cpp)
    normal_[a] = &frame.float_channel(std::string("geonormal.") + kAxes[a]);         // its face normal
  }
}

GlossyRay GlossyRayLayers::at(size_t i) const {
  GlossyRay r;
  if (secondary_id_->data[i] == kInvalidId) return r;  // escaped, or no surface: nothing reflected, no vector
  const auto vec3_at = [i](const FloatPlane* const (&p)[3]) {
    return glm::vec3(p[0]->data[i], p[1]->data[i], p[2]->data[i]);
  };
  r.reflector = vec3_at(position_), r.reflector_normal = vec3_at(normal_), r.hit = vec3_at(secondary_);
  r.roughness = roughness_->data[i];
  r.seed = seed_->data[i];
  r.reflector_instance = reflector_id_->data[i], r.hit_instance = secondary_id_->data[i];
  return r;
}

std::vector<GlossyMotion> glossy_motion(const FrameGeometry& g, const Frame& frame) {
  const GlossyRayLayers rays(frame);
  const std::vector<InstanceMotion> to_previous = instance_to_previous(g.pose, g.prev_pose);
  return motion_per_pixel<GlossyMotion>("glossy_motion", g, frame, [&](size_t i) {
    return glossy_motion_pixel(rays.at(i), to_previous, g.view, g.prev_view);
  });
}

void write_glossy_motion_layers(const FrameGeometry& g, Frame& frame) {
  const std::vector<GlossyMotion> m = glossy_motion(g, frame);
  write_motion_and_validity(frame, "motion.glossy", m);
  // mu alone, the lobe's centre: the glossy vector without Eq. 5's draw (TrmvParams::glossy_draw).
  std::vector<glm::vec2> mean(m.size());
  for (size_t i = 0; i < m.size(); ++i) mean[i] = m[i].valid ? m[i].mu : glm::vec2(0.0f);
  frame.set_vec2("motion.glossy_mean", mean);
  // Sigma_i, symmetric: three entries, pixels^2.
  FloatPlane& xx = frame.add_float("glossy.footprint.XX");
  FloatPlane& xy = frame.add_float("glossy.footprint.XY");
  FloatPlane& yy = frame.add_float("glossy.footprint.YY");
  UIntPlane& has = frame.add_uint("glossy.footprint.valid");
  for (size_t i = 0; i < m.size(); ++i) {
    if (!m[i].has_footprint) continue;  // 0, and valid 0
    xx.data[i] = m[i].footprint[0][0], xy.data[i] = m[i].footprint[1][0], yy.data[i] = m[i].footprint[1][1];
    has.data[i] = 1u;
  }
}

}  // namespace rtdr
