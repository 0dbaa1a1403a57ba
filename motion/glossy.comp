// TRMV's glossy motion vector [TRMV21 Eq. 5], the Vulkan port of glossy_motion_pixel (motion/glossy.cpp), function
// for function: h_i mirrored in the reflector's plane now gives x_i = P_i(v_i); h_i and the plane carried back with
// their own instances' T^{-1} give the virtual image v and the specular point s^C; mu = P_{i-1}(v); the GGX lobe's
// footprint around s^C, projected, gives the columns a1, a2 of Sigma's square root; one Gaussian draw
// x^R_{i-1} = mu + a1 n1 + a2 n2, and m^R = x^R_{i-1} - x_i. Invalid ((0, 0), valid 0) without a surface or a
// secondary hit, where the eye sees no reflection of h in the plane (either frame), where v is behind a camera, or
// where the lobe or its footprint has no image-space ellipse. One invocation per pixel. The choices the paper
// leaves open are the golden pass's (motion/glossy.h).
//   in:  bindings 0-2 (s_i, roughness), n(s_i), h_i; 3-5 the reflector's and the hit's instance ids, rng.seed;
//        6 every instance's T^{-1}; 7 the two Views;
//   out: 8 (m^R, mu, a1, a2, b1, b2, valid, has_footprint): b1, b2 the same lobe's footprint seen by the current
//        camera. Layout: motion/glossy_shared.h.
// GPU only: every arithmetic result is `precise`, so no fma contraction or reordering changes the rounding; the
// C++ rounds after each operation in the same order, and glm's products are written out in glm's order (dot:
// (x + y) + z; normalize: v * (1 / sqrt(dot(v, v))); mat3 * vec3: (c0 x + c1 y) + c2 z; mat4 * vec4:
// raster/view.glsl). The random draw is integer hashing (core/sampler.glsl), bit for bit. The divisions and
// square roots are the device's, and so are asin, tan, atan, log, cos and sin (tests/gpu_motion_glossy_test.cpp
// derives the bound).
#version 450
#extension GL_GOOGLE_include_directive : require

#include "motion/glossy_shared.h"

#include "filters/svgf/planes_shared.h"
#include "raster/view.glsl"
#include "core/sampler.glsl"

// The workgroup's shape, per device: the SVGF ports' (planes_shared.h).
layout(local_size_x_id = kSvgfGroupSizeXConstant, local_size_y_id = kSvgfGroupSizeYConstant,
       local_size_x = kSvgfGroupSizeX, local_size_y = kSvgfGroupSizeY) in;

RTDR_INPUT_RGBA(0, reflector_roughness)
RTDR_INPUT_RGBA(1, reflector_normal)
RTDR_INPUT_RGBA(2, hit)
RTDR_INPUT_UINT(3, reflector_id)
RTDR_INPUT_UINT(4, hit_id)
RTDR_INPUT_UINT(5, rng_seed)
layout(std430, set = 0, binding = 6) readonly buffer Instances { ShadowInstanceMotion instances[]; };
layout(std430, set = 0, binding = 7) readonly buffer Views { ViewRecord views[2]; };
layout(std430, set = 0, binding = 8) writeonly buffer OutGlossy { GlossyMotionRecord out_glossy[]; };

layout(push_constant) uniform Push { GlossyMotionPush push; };

// GPU only: the push constants, copied once at the top of main(). lavapipe loads a push constant lane by lane at
// each use; the copy is loaded once.
GlossyMotionPush frame;

// views[] holds this frame's View, then the previous frame's.
const int kCurrentView = 0;
const int kPreviousView = 1;

// glm::dot, glm::length, glm::normalize and glm::cross of vec3s, in glm's order.
float dot3(vec3 a, vec3 b) {
  precise float r = a.x * b.x + a.y * b.y + a.z * b.z;
  return r;
}
float length3(vec3 a) {
  precise float r = sqrt(dot3(a, a));
  return r;
}
vec3 normalize3(vec3 a) {
  precise float inverse_length = 1.0 / sqrt(dot3(a, a));  // glm::inversesqrt
  precise vec3 r = a * inverse_length;
  return r;
}
vec3 cross3(vec3 a, vec3 b) {
  precise vec3 r = vec3(a.y * b.z - b.y * a.z, a.z * b.x - b.z * a.x, a.x * b.y - b.x * a.y);
  return r;
}

// normal_to_previous * n, glm's mat3 * vec3.
vec3 transform_normal(uint k, vec3 n) {
  const vec4 m[3] = instances[k].normal_to_previous;
  precise vec3 r = m[0].xyz * n.x + m[1].xyz * n.y + m[2].xyz * n.z;
  return r;
}

// core/geometry.h's orthonormal_basis: a tangent t of the unit normal n (the bitangent is not needed here).
vec3 orthonormal_tangent(vec3 n) {
  const float sign = (floatBitsToUint(n.z) & 0x80000000u) != 0u ? -1.0 : 1.0;  // std::copysign(1, n.z)
  precise float a = -1.0 / (sign + n.z);
  precise float c = n.x * n.y * a;
  precise vec3 t = vec3(1.0 + sign * n.x * n.x * a, sign * c, -sign * n.x);
  return t;
}

// An instance id the shader may index instances[] with. GPU only: the golden pass takes every id below the
// instance count (instance_to_previous has one entry per instance); an id beyond it would read outside the buffer.
bool known_instance(uint id) { return id != RTDR_INVALID_ID && id < frame.instance_count; }

// A planar mirror seen from an eye: the virtual image of a point, and where the eye sees it on the plane.
struct MirrorImage {
  vec3 image;            // v = mirror[h, plane]
  vec3 specular_point;   // s^C: where the segment eye -> v crosses the plane
  vec3 normal;           // the plane's unit normal, turned to the eye's side
  vec3 incidence;        // the unit direction eye -> v
  float cos_incidence;   // cos i = |n . (v - eye)| / |v - eye|
  float distance;        // d = |v - s^C|, the lobe's length from the image to the plane
};

// Mirrors h across the plane through s with normal n, seen from `eye` [TRMV21 Eq. 5, mirror[.]]. False when the
// eye and h are not strictly on one side of the plane or when the line eye -> v is (nearly) parallel to it.
bool mirror_in_plane(vec3 eye, vec3 h, vec3 s, vec3 n_s, out MirrorImage m) {
  vec3 n = normalize3(n_s);
  precise vec3 eye_from_s = eye - s, h_from_s = h - s;
  float eye_height = dot3(n, eye_from_s);  // signed distances to the plane
  float h_height = dot3(n, h_from_s);
  precise float same_side = eye_height * h_height;
  if (!(same_side > 0.0)) return false;  // opposite sides, or on the plane: nothing is reflected
  if (eye_height < 0.0) n = -n, eye_height = -eye_height, h_height = -h_height;  // n towards the eye
  precise vec3 v = h - 2.0 * h_height * n;  // the virtual image, h_height behind the plane
  precise vec3 eye_to_v = v - eye;
  const float len = length3(eye_to_v);
  const float n_dot_line = dot3(n, eye_to_v);  // = -(eye_height + h_height) < 0
  precise float parallel = kGlossyParallelCosine * len;
  if (abs(n_dot_line) <= parallel) return false;  // grazing: parallel to the plane
  // The line eye + t (v - eye) is eye_height - t (eye_height + h_height) above the plane: 0 at this t, in (0, 1).
  precise float t = eye_height / (eye_height + h_height);
  precise vec3 specular_point = eye + t * eye_to_v;
  precise vec3 incidence = eye_to_v / len;
  precise float cos_incidence = -n_dot_line / len;
  precise float distance = (1.0 - t) * len;
  m = MirrorImage(v, specular_point, n, incidence, cos_incidence, distance);
  return true;
}

// The lobe's footprint in the image [TRMV21 Sec. 4.2, "tracking the endpoints of major and minor axes"]: the
// cone of half-angle sigma_theta from v around v -> s^C cuts the plane in an ellipse around s^C; each semi-axis's
// endpoints are projected and halved with views[view]. a1 (in the plane of incidence) and a2 (perpendicular),
// pixels. False when the lobe is too wide to meet the plane in an ellipse, or an endpoint is behind that camera.
bool footprint_axes(MirrorImage m, float sigma_theta, int view, out vec2 a1, out vec2 a2) {
  // sigma_theta < pi/2 - i, the angle between the cone's axis and the plane (motion/glossy.h). std::clamp.
  const float c = m.cos_incidence < 0.0 ? 0.0 : (1.0 < m.cos_incidence ? 1.0 : m.cos_incidence);
  const float axis_to_plane = asin(c);  // pi/2 - i
  if (!(sigma_theta < axis_to_plane)) return false;
  // t1: the plane of incidence's trace on the mirror (the incidence direction with its normal part removed).
  precise vec3 t1 = m.incidence - dot3(m.normal, m.incidence) * m.normal;
  if (length3(t1) < kGlossyNormalIncidence) t1 = orthonormal_tangent(m.normal);  // a circle: any tangent
  t1 = normalize3(t1);
  const vec3 t2 = cross3(m.normal, t1);
  // Semi-axes on the plane: d tan(sigma_theta) across, stretched by 1 / cos i along the plane of incidence.
  precise float r_across = m.distance * tan(sigma_theta);
  precise float r_along = r_across / m.cos_incidence;
  precise vec3 semi_along = r_along * t1, semi_across = r_across * t2;
  vec2 axes[2];
  for (int k = 0; k < 2; ++k) {
    const vec3 semi_axis = k == 0 ? semi_along : semi_across;
    precise vec3 end_plus = m.specular_point + semi_axis, end_minus = m.specular_point - semi_axis;
    const vec3 plus = project(views[view], end_plus);  // (x, y, depth)
    const vec3 minus = project(views[view], end_minus);
    const float znear = views[view].znear;
    if (plus.z < znear || minus.z < znear) return false;  // the footprint reaches behind the camera
    precise vec2 axis = 0.5 * (plus.xy - minus.xy);
    axes[k] = axis;
  }
  a1 = axes[0], a2 = axes[1];
  return true;
}

// scenes/scene.h's ggx_alpha: std::max(kMinGgxAlpha, roughness^2).
float ggx_alpha(float roughness) {
  precise float alpha = roughness * roughness;
  return frame.min_ggx_alpha < alpha ? alpha : frame.min_ggx_alpha;
}

// sigma_theta = 2 atan(1.458 alpha): the reflected direction's angular standard deviation (motion/glossy.h).
float glossy_lobe_angle(float alpha) {
  precise float sigma_theta = 2.0 * atan(kGgxLobeTanPerAlpha * alpha);
  return sigma_theta;
}

// (n1, n2): Box-Muller on Sampler(hash_combine(seed, kGlossyStream), 0).next_2d(), the first pair of sample 0.
vec2 glossy_normal_pair(uint seed) {
  const vec2 u = sample_pair_at(hash_combine(seed, kGlossyStream), 0u, 0u);
  precise float radius = sqrt(-2.0 * log(1.0 - u.x));  // 1 - u.x in (0, 1]: the log is finite
  precise float phi = 2.0 * kGlossyPi * u.y;
  // GPU only: phi in [pi, 2 pi) moved to [-pi, 0), where Vulkan bounds sin and cos; the difference of the two
  // floats is exact (Sterbenz), and 2 pi as a float is 1.75e-7 above 2 pi (the test's bound counts it).
  precise float phi_reduced = phi - 2.0 * kGlossyPi;
  const float angle = phi < kGlossyPi ? phi : phi_reduced;
  precise vec2 n = vec2(radius * cos(angle), radius * sin(angle));
  return n;
}

// The golden per-pixel function, glossy_motion_pixel, on GlossyRayLayers::at(i).
GlossyMotionRecord glossy_motion_pixel(int i) {
  GlossyMotionRecord result = GlossyMotionRecord(vec2(0.0), vec2(0.0), vec2(0.0), vec2(0.0), vec2(0.0), vec2(0.0), 0u,
                                                 0u, uint[2](0u, 0u));
  const uint hit_instance = hit_id(i).x, reflector_instance = reflector_id(i).x;
  if (!known_instance(reflector_instance) || !known_instance(hit_instance))
    return result;  // no surface, or its BSDF ray escaped: nothing is reflected
  const vec4 s_roughness = reflector_roughness(i);
  const vec3 s = s_roughness.xyz, n = reflector_normal(i).xyz, h = hit(i).xyz;
  // x_i = P_i(v_i), the current virtual image of h_i in the current plane of s_i (motion/glossy.h says why).
  MirrorImage now;
  if (!mirror_in_plane(frame.eye.xyz, h, s, n, now)) return result;
  const vec3 x_cur = project(views[kCurrentView], now.image);  // (x, y, depth)
  if (x_cur.z < views[kCurrentView].znear) return result;
  const float sigma_theta = glossy_lobe_angle(ggx_alpha(s_roughness.w));
  // The lobe's footprint in this frame's image: steps (2)-(4) with v_i and P_i (the glossy filter's kernel).
  vec2 b1, b2;
  if (footprint_axes(now, sigma_theta, kCurrentView, b1, b2)) result.b1 = b1, result.b2 = b2, result.has_footprint = 1u;

  // (1) T^{-1} h_i and T^{-1} plane(s_i), each with its own instance's motion [TRMV21 Eq. 5].
  const vec3 h_prev = transform_point(instances[hit_instance].to_previous, h);
  const vec3 s_prev = transform_point(instances[reflector_instance].to_previous, s);
  const vec3 n_prev = transform_normal(reflector_instance, n);
  // (2) mirror[T^{-1} h_i, T^{-1} plane(s_i)]: the virtual image v, and the specular point s^C on the segment
  // eye_{i-1} -> v.
  MirrorImage before;
  if (!mirror_in_plane(frame.prev_eye.xyz, h_prev, s_prev, n_prev, before)) return result;
  // (3) mu = P_{i-1}(v), the footprint's centre [TRMV21 Eq. 5].
  const vec3 mu = project(views[kPreviousView], before.image);
  if (mu.z < views[kPreviousView].znear) return result;  // behind the previous camera: no previous screen position
  // (4) Sigma: the GGX lobe of s_i's roughness, sigma_theta = 2 atan(1.458 alpha), traced from v to the plane.
  vec2 a1, a2;
  if (!footprint_axes(before, sigma_theta, kPreviousView, a1, a2)) return result;

  // (5) x^R_{i-1} = sample(mu, Sigma) = mu + a1 n1 + a2 n2, and m^R = x^R_{i-1} - x_i [TRMV21 Eq. 5].
  precise vec2 mu_i = mu.xy - x_cur.xy;
  const vec2 n12 = glossy_normal_pair(rng_seed(i).x);
  precise vec2 motion = mu_i + (a1 * n12.x + a2 * n12.y);  // glm's mat2 * vec2
  result.motion = motion, result.mu = mu_i, result.a1 = a1, result.a2 = a2, result.valid = 1u;
  return result;
}

// glossy_motion: glossy_motion_pixel at every pixel.
void main() {
  frame = push;  // the push constants, read once (see above)
  // This invocation's pixel; the last tiles overhang the frame.
  const ivec2 pixel = ivec2(gl_GlobalInvocationID.xy);
  if (pixel.x >= int(frame.width) || pixel.y >= int(frame.height)) return;
  const int i = pixel.y * int(frame.width) + pixel.x;
  out_glossy[i] = glossy_motion_pixel(i);
}
