// TRMV's shadow motion vector [TRMV21 Eq. 3], the Vulkan port of shadow_motion_pixel (motion/shadow.cpp),
// function for function: the shadow ray's line l_i -> b_i meets the receiver's plane at s^_i; the same line and
// plane carried back with their own instances' motion T^{-1} meet at s^_{i-1}; m^V = P_{i-1}(s^_{i-1}) - P_i(s^_i).
// Invalid (m^V = (0, 0)) without a blocked shadow ray, for a line parallel to the plane, a receiver not beyond the
// blocker (t <= 1), in either frame, or a previous point before the previous camera's znear. One invocation per
// pixel. The choices the paper leaves open are the golden pass's (motion/shadow.h).
//   in:  bindings 0-3 l_i, b_i, s_i, n(s_i); 4-6 the light's, the blocker's and the receiver's instance ids;
//        7 every instance's T^{-1}; 8 the two Views;
//   out: 9 (m^V.x, m^V.y, valid, 0). Layout: motion/shadow_shared.h.
// GPU only: every arithmetic result is `precise`, so no fma contraction or reordering changes the rounding; the
// C++ rounds after each operation in the same order, and glm's products are written out in glm's order (dot:
// (x + y) + z; mat3 * vec3: (c0 x + c1 y) + c2 z; mat4 * vec4 and View::project: raster/view.glsl). Only the
// divisions and the square root are the device's (tests/gpu_motion_shadow_test.cpp derives the bound).
#version 450
#extension GL_GOOGLE_include_directive : require

#include "motion/shadow_shared.h"

#include "filters/svgf/planes_shared.h"
#include "raster/view.glsl"

// The workgroup's shape, per device: the SVGF ports' (planes_shared.h).
layout(local_size_x_id = kSvgfGroupSizeXConstant, local_size_y_id = kSvgfGroupSizeYConstant,
       local_size_x = kSvgfGroupSizeX, local_size_y = kSvgfGroupSizeY) in;

RTDR_INPUT_RGBA(0, light)
RTDR_INPUT_RGBA(1, blocker)
RTDR_INPUT_RGBA(2, position)
RTDR_INPUT_RGBA(3, geonormal)
RTDR_INPUT_UINT(4, light_id)
RTDR_INPUT_UINT(5, blocker_id)
RTDR_INPUT_UINT(6, receiver_id)
layout(std430, set = 0, binding = 7) readonly buffer Instances { ShadowInstanceMotion instances[]; };
layout(std430, set = 0, binding = 8) readonly buffer Views { ViewRecord views[2]; };
layout(std430, set = 0, binding = 9) writeonly buffer OutShadow { vec4 out_shadow[]; };

layout(push_constant) uniform Push { ShadowMotionPush push; };

// GPU only: the push constants, copied once at the top of main(). lavapipe loads a push constant lane by lane at
// each use; the copy is loaded once.
ShadowMotionPush frame;

// views[] holds this frame's View, then the previous frame's.
const int kCurrentView = 0;
const int kPreviousView = 1;

// glm::dot and glm::length of a vec3: (x + y) + z, then the square root.
float dot3(vec3 a, vec3 b) {
  precise float r = a.x * b.x + a.y * b.y + a.z * b.z;
  return r;
}
float length3(vec3 a) {
  precise float r = sqrt(dot3(a, a));
  return r;
}

// normal_to_previous * n, glm's mat3 * vec3.
vec3 transform_normal(uint k, vec3 n) {
  const vec4 m[3] = instances[k].normal_to_previous;
  precise vec3 r = m[0].xyz * n.x + m[1].xyz * n.y + m[2].xyz * n.z;
  return r;
}

// Where the line p(t) = l + t (b - l) meets the plane through s with normal n: t = n.(s - l) / n.(b - l).
// False when the line is (nearly) parallel to the plane, or when the plane is not beyond the blocker (t <= 1).
bool intersect_shadow_line(vec3 l, vec3 b, vec3 s, vec3 n, out vec3 point) {
  precise vec3 lb = b - l;
  const float n_dot_lb = dot3(n, lb);
  precise float parallel = kShadowParallelCosine * length3(lb);
  if (abs(n_dot_lb) <= parallel) return false;  // parallel to the plane
  precise vec3 sl = s - l;
  precise float t = dot3(n, sl) / n_dot_lb;
  if (!(t > 1.0)) return false;  // the receiver is not beyond the blocker, seen from the light
  precise vec3 p = l + t * lb;
  point = p;
  return true;
}

// An instance id the shader may index instances[] with. GPU only: the golden pass takes every id below the
// instance count (instance_to_previous has one entry per instance); an id beyond it would read outside the buffer.
bool known_instance(uint id) { return id != RTDR_INVALID_ID && id < frame.instance_count; }

// The golden per-pixel function, shadow_motion_pixel, on ShadowRayLayers::at(i): (m^V, valid).
vec3 shadow_motion_pixel(int i) {
  const vec3 invalid = vec3(0.0);
  const uint blocker_instance = blocker_id(i).x;
  if (blocker_instance == RTDR_INVALID_ID) return invalid;  // lit, or no surface: no shadow, no vector
  const uint light_instance = light_id(i).x, receiver_instance = receiver_id(i).x;
  if (!known_instance(receiver_instance) || !known_instance(blocker_instance) || !known_instance(light_instance))
    return invalid;  // no surface, or the shadow ray reached the light: the pixel is not in shadow
  const vec3 l = light(i).xyz, b = blocker(i).xyz, s = position(i).xyz, n = geonormal(i).xyz;
  // s^_i: the current shadow point, where the shadow ray's own line meets the receiver's plane (motion/shadow.h).
  vec3 s_hat;
  if (!intersect_shadow_line(l, b, s, n, s_hat)) return invalid;

  // T^{-1} l_i, T^{-1} b_i and T^{-1} plane(s_i), each with its own instance's motion [TRMV21 Eq. 3].
  const vec3 l_prev = transform_point(instances[light_instance].to_previous, l);
  const vec3 b_prev = transform_point(instances[blocker_instance].to_previous, b);
  const vec3 s_prev = transform_point(instances[receiver_instance].to_previous, s);
  const vec3 n_prev = transform_normal(receiver_instance, n);
  // intersect[T^{-1} l_i -> T^{-1} b_i ; T^{-1} plane(s_i)]: the shadow point in the previous frame.
  vec3 s_hat_prev;
  if (!intersect_shadow_line(l_prev, b_prev, s_prev, n_prev, s_hat_prev)) return invalid;

  // x^V_{i-1} = P_{i-1}(...), and m^V = x^V_{i-1} - x_i with x_i = P_i(s^_i) [TRMV21 Eq. 3].
  const vec3 x_prev = project(views[kPreviousView], s_hat_prev);  // (x, y, depth)
  if (x_prev.z < views[kPreviousView].znear) return invalid;  // behind the previous camera
  const vec3 x_cur = project(views[kCurrentView], s_hat);
  precise vec2 motion = x_prev.xy - x_cur.xy;
  return vec3(motion, 1.0);
}

// shadow_motion: shadow_motion_pixel at every pixel.
void main() {
  frame = push;  // the push constants, read once (see above)
  // This invocation's pixel; the last tiles overhang the frame.
  const ivec2 pixel = ivec2(gl_GlobalInvocationID.xy);
  if (pixel.x >= int(frame.width) || pixel.y >= int(frame.height)) return;
  const int i = pixel.y * int(frame.width) + pixel.x;
  out_shadow[i] = vec4(shadow_motion_pixel(i), 0.0);
}
