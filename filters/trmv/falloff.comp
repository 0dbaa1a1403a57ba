// TRMV's non-planar receiver falloff [TRMV21 Eq. 4], the Vulkan port of trmv_falloff_pixel
// (filters/trmv/falloff.cpp), function for function: x^V_{i-1} = pixel centre + m^V; s^V_{i-1} = the previous
// frame's position at the pixel containing x^V_{i-1}; s_i and n(s_i) carried back to frame i-1 (the previous
// position and geonormal at the pixel holding x_i + m, on the same mesh; falloff_carry); theta = angle(n(s_i),
// s_i -> s^V_{i-1}) (pi/2 for a static shadow); alpha^V = 1 - G(theta - pi/2; 0, sigma) (1 - alpha). No evidence
// (no surface, an invalid vector, x^V_{i-1} off the previous image or without a surface there, first frame):
// theta = pi/2, alpha^V = alpha. One invocation per pixel. The choices the paper leaves open are the golden pass's
// (filters/trmv/falloff.h).
//   in:  bindings 0 s_i, 1 n(s_i), 2 id.mesh, 3 the surface motion m, 4 m^V, 5 validity, 6 the previous position,
//        7 the previous geonormal, 8 the previous id.mesh;
//   out: 9 (theta, alpha^V). Layout: filters/svgf/planes_shared.h and filters/trmv/falloff_shared.h.
// GPU only: every arithmetic result is `precise`, so no fma contraction or reordering changes the rounding; the
// C++ rounds after each operation in the same order, and the dot products and lengths are written out in glm's
// order ((x + y) + z). acos and exp are the device's, not libm's (tests/gpu_trmv_falloff_test.cpp derives the bound).
#version 450
#extension GL_GOOGLE_include_directive : require

#include "filters/trmv/falloff_shared.h"

// The workgroup's shape, per device: the SVGF ports' (planes_shared.h).
layout(local_size_x_id = kSvgfGroupSizeXConstant, local_size_y_id = kSvgfGroupSizeYConstant,
       local_size_x = kSvgfGroupSizeX, local_size_y = kSvgfGroupSizeY) in;

RTDR_INPUT_RGBA(0, position)
RTDR_INPUT_RGBA(1, normal)
RTDR_INPUT_UINT(2, mesh)
RTDR_INPUT_RG(3, surface_motion)
RTDR_INPUT_RG(4, motion)
RTDR_INPUT_UINT(5, motion_valid)
RTDR_INPUT_RGBA(6, prev_position)
RTDR_INPUT_RGBA(7, prev_normal)
RTDR_INPUT_UINT(8, prev_mesh)
layout(std430, set = 0, binding = 9) writeonly buffer OutThetaAlpha { vec2 out_theta_alpha[]; };

layout(push_constant) uniform Push { TrmvFalloffPush push; };

// GPU only: the push constants, copied once at the top of main(). lavapipe loads a push constant lane by lane at
// each use; the copy is loaded once.
TrmvFalloffPush frame;

// The planes' accessors (Plane::at): element y * width + x of the current or the previous frame.
int cur_index(int x, int y) { return y * int(frame.width) + x; }
int prev_index(ivec2 q) { return q.y * int(frame.prev_width) + q.x; }

// One pixel of the pass's output (TrmvFalloffPixel).
struct TrmvFalloffPixel {
  float theta;    // radians; pi/2 where there is no evidence
  float alpha_v;  // alpha^V [TRMV21 Eq. 4]
};

// No Eq. 4 evidence: theta = pi/2, alpha^V = alpha (falloff.h).
TrmvFalloffPixel no_evidence(float alpha) { return TrmvFalloffPixel(kTrmvFalloffHalfPi, alpha); }

// glm::dot and glm::length of a vec3: (x + y) + z, then the square root.
float dot3(vec3 a, vec3 b) {
  precise float r = a.x * b.x + a.y * b.y + a.z * b.z;
  return r;
}
float length3(vec3 a) {
  precise float r = sqrt(dot3(a, a));
  return r;
}

// G(x; 0, sigma) = exp(-x^2 / (2 sigma^2)), peak 1 [TRMV21 Eq. 4].
float trmv_falloff_gaussian(float x, float sigma) {
  precise float g = exp(-(x * x) / (2.0 * sigma * sigma));
  return g;
}

// alpha^V = 1 - G(theta - pi/2; 0, sigma) (1 - alpha) [TRMV21 Eq. 4].
float trmv_falloff_alpha(float theta, float alpha, float sigma) {
  precise float x = theta - kTrmvFalloffHalfPi;
  precise float alpha_v = 1.0 - trmv_falloff_gaussian(x, sigma) * (1.0 - alpha);
  return alpha_v;
}

// theta, the angle between n(s_i) and s_i -> s^V_{i-1}, in [0, pi]; pi/2 for the degenerate static shadow.
float trmv_falloff_theta(vec3 s_i, vec3 n_s_i, vec3 s_v_prev) {
  precise vec3 d = s_v_prev - s_i;  // the direction s_i -> s^V_{i-1} [TRMV21 Sec. 4.1]
  const float len = length3(d);
  // A static shadow: no direction; it lies on the plane as far as anyone can tell (falloff.h).
  precise float same_point = kTrmvFalloffSamePointRelative * (1.0 + length3(s_i));
  if (len < same_point) return kTrmvFalloffHalfPi;
  // cos theta = n(s_i) . d / (|n(s_i)| |d|), clamped into [-1, 1] against rounding before acos (std::clamp's
  // comparisons, which pass a NaN through as C++ does).
  precise float c = dot3(n_s_i, d) / (length3(n_s_i) * len);
  const float cos_theta = c < -1.0 ? -1.0 : (1.0 < c ? 1.0 : c);
  return acos(cos_theta);
}

// trmv_falloff_carry_back: s_i and n(s_i) as the previous frame shows them at the pixel holding x_i + m, when it
// shows the same mesh; false (s, n untouched) otherwise.
bool trmv_falloff_carry_back(int x, int y, inout vec3 s, inout vec3 n) {
  const int i = cur_index(x, y);
  precise vec2 x_prev = vec2(float(x) + 0.5, float(y) + 0.5) + surface_motion(i).xy;
  if (!(x_prev.x >= 0.0 && x_prev.y >= 0.0 && x_prev.x < float(frame.prev_width) &&
        x_prev.y < float(frame.prev_height)))
    return false;
  const int iq = prev_index(ivec2(floor(x_prev)));
  if (prev_mesh(iq).x != mesh(i).x) return false;  // another surface there: not carried
  s = prev_position(iq).xyz;
  n = prev_normal(iq).xyz;
  return true;
}

// The golden per-pixel function, trmv_falloff_pixel.
TrmvFalloffPixel trmv_falloff_pixel(int x, int y) {
  const int i = cur_index(x, y);
  const bool covered = mesh(i).x != RTDR_INVALID_ID;
  const bool valid = frame.has_valid == 0u || motion_valid(i).x != 0u;
  if (!covered || !valid || frame.has_prev == 0u) return no_evidence(frame.alpha);
  // x^V_{i-1} = x_i + m^V: where the shadow point was in the previous frame [TRMV21 Eq. 3].
  precise vec2 x_v = vec2(float(x) + 0.5, float(y) + 0.5) + motion(i).xy;
  // The pixel containing x^V_{i-1}; the range test first keeps floor() within int range (false for NaN too).
  const bool near = x_v.x >= 0.0 && x_v.y >= 0.0 && x_v.x < float(frame.prev_width) &&
                    x_v.y < float(frame.prev_height);
  if (!near) return no_evidence(frame.alpha);
  const ivec2 q = ivec2(floor(x_v));
  if (prev_mesh(prev_index(q)).x == RTDR_INVALID_ID) return no_evidence(frame.alpha);
  // s^V_{i-1}: "the shading point of pixel x^V_{i-1}" in the previous frame [TRMV21 Sec. 4.1]; the receiver carried
  // back to that frame (falloff_carry), else the current one.
  vec3 s_i = position(i).xyz, n_s_i = normal(i).xyz;
  if (frame.falloff_carry != 0u) trmv_falloff_carry_back(x, y, s_i, n_s_i);
  const float theta = trmv_falloff_theta(s_i, n_s_i, prev_position(prev_index(q)).xyz);
  return TrmvFalloffPixel(theta, trmv_falloff_alpha(theta, frame.alpha, frame.falloff_sigma));
}

// trmv_falloff_pass: trmv_falloff_pixel at every pixel.
void main() {
  frame = push;  // the push constants, read once (see above)
  // This invocation's pixel; the last tiles overhang the frame.
  const ivec2 pixel = ivec2(gl_GlobalInvocationID.xy);
  if (pixel.x >= int(frame.width) || pixel.y >= int(frame.height)) return;
  const TrmvFalloffPixel p = trmv_falloff_pixel(pixel.x, pixel.y);
  out_theta_alpha[cur_index(pixel.x, pixel.y)] = vec2(p.theta, p.alpha_v);
}
