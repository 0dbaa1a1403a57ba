// Temporal accumulation [SVGF17 Sec. 4.1, 4.2], the Vulkan port of temporal_pixel (temporal.cpp), function for
// function: back-project along the motion vector, resample the history with consistency-tested 2x2 bilinear
// taps, else a 3x3 fallback, else a disocclusion; then the EMA of colour and moments with
// alpha_eff = max(alpha, 1/n). One invocation per pixel.
//   in:  bindings 0-12 (noisy colour, current G-buffer, history); out: bindings 13-16 (C', mu1', mu2', n).
//   Layout: temporal_shared.h.
#version 450
#extension GL_GOOGLE_include_directive : require

#include "filters/svgf/temporal_shared.h"

layout(local_size_x = kTemporalGroupSizeX, local_size_y = kTemporalGroupSizeY) in;

layout(std430, set = 0, binding = 0) readonly buffer Noisy { float noisy_rgb[]; };
layout(std430, set = 0, binding = 1) readonly buffer CurDepth { float cur_depth[]; };
layout(std430, set = 0, binding = 2) readonly buffer CurDepthGrad { float cur_depth_grad_xy[]; };
layout(std430, set = 0, binding = 3) readonly buffer CurNormal { float cur_normal_xyz[]; };
layout(std430, set = 0, binding = 4) readonly buffer CurMesh { uint cur_mesh[]; };
layout(std430, set = 0, binding = 5) readonly buffer CurMotion { float cur_motion_xy[]; };
layout(std430, set = 0, binding = 6) readonly buffer PrevColor { float prev_color_rgb[]; };
layout(std430, set = 0, binding = 7) readonly buffer PrevMoment1 { float prev_moment1[]; };
layout(std430, set = 0, binding = 8) readonly buffer PrevMoment2 { float prev_moment2[]; };
layout(std430, set = 0, binding = 9) readonly buffer PrevLength { float prev_length[]; };
layout(std430, set = 0, binding = 10) readonly buffer PrevDepth { float prev_depth[]; };
layout(std430, set = 0, binding = 11) readonly buffer PrevNormal { float prev_normal_xyz[]; };
layout(std430, set = 0, binding = 12) readonly buffer PrevMesh { uint prev_mesh[]; };
layout(std430, set = 0, binding = 13) writeonly buffer OutColor { float out_color_rgb[]; };
layout(std430, set = 0, binding = 14) writeonly buffer OutMoment1 { float out_moment1[]; };
layout(std430, set = 0, binding = 15) writeonly buffer OutMoment2 { float out_moment2[]; };
layout(std430, set = 0, binding = 16) writeonly buffer OutLength { float out_length[]; };

layout(push_constant) uniform Push { TemporalPush frame; };

// The planes' accessors (Plane::at, inside): element y * width + x of the current or the previous frame.
uint cur_index(int x, int y) { return uint(y) * frame.width + uint(x); }
uint prev_index(ivec2 q) { return uint(q.y) * frame.prev_width + uint(q.x); }
bool prev_inside(ivec2 q) { return q.x >= 0 && q.y >= 0 && q.x < int(frame.prev_width) && q.y < int(frame.prev_height); }
vec3 prev_color_at(ivec2 q) {
  const uint i = 3u * prev_index(q);
  return vec3(prev_color_rgb[i], prev_color_rgb[i + 1u], prev_color_rgb[i + 2u]);
}
vec3 prev_normal_at(ivec2 q) {
  const uint i = 3u * prev_index(q);
  return vec3(prev_normal_xyz[i], prev_normal_xyz[i + 1u], prev_normal_xyz[i + 2u]);
}

// core/color.h's luminance: R r + G g + B b, in that order.
float luminance(vec3 rgb) {
  // GPU only: `precise` keeps the two multiply-adds from fusing into fmas (C++ rounds each product).
  precise float l = RTDR_LUMINANCE_R * rgb.r + RTDR_LUMINANCE_G * rgb.g + RTDR_LUMINANCE_B * rgb.b;
  return l;
}

// The history values at p': weighted sums while the taps are gathered, the resampled history afterwards.
struct HistorySample {
  vec3 color;
  float moment1;
  float moment2;
  float len;  // C++: length (a GLSL method name: h.length would call .length())
};

// GPU only: every arithmetic on history samples is `precise`, so no fma changes C++'s rounding.
void add_tap(inout HistorySample h, ivec2 q, float w) {
  const uint i = prev_index(q);
  precise vec3 color = h.color + w * prev_color_at(q);
  precise float moment1 = h.moment1 + w * prev_moment1[i];
  precise float moment2 = h.moment2 + w * prev_moment2[i];
  precise float len = h.len + w * prev_length[i];
  h = HistorySample(color, moment1, moment2, len);
}

HistorySample scaled(HistorySample h, float s) {
  precise vec3 color = s * h.color;
  precise float moment1 = s * h.moment1, moment2 = s * h.moment2, len = s * h.len;
  return HistorySample(color, moment1, moment2, len);
}

// The consistency test of one history tap (temporal.h): q inside the previous image, same mesh id, depth and
// normal within the thresholds [SVGF17 Sec. 4.1].
bool temporal_tap_consistent(int x, int y, ivec2 q, vec2 p_prev) {
  // The tap's centre relative to p', in pixels.
  precise vec2 offset = vec2(q) + 0.5 - p_prev;
  // The tap must exist in the previous frame.
  const bool in_image = prev_inside(q);
  if (!in_image) return false;
  const uint p = cur_index(x, y), iq = prev_index(q);
  // Mesh ids compare exactly; a tap with no surface (kInvalidId) never matches a covered pixel.
  const bool same_mesh = prev_mesh[iq] == cur_mesh[p];
  // Depth: |z - z'| <= temporal_depth_relative max(z, z') + |grad z(p) . (q - p')|  (temporal.h).
  const float z = cur_depth[p];
  const float z_prev = prev_depth[iq];
  const float dz = abs(z - z_prev);
  const vec2 grad_z = vec2(cur_depth_grad_xy[2u * p], cur_depth_grad_xy[2u * p + 1u]);
  // GPU only: glm::dot written out ((x x) + (y y)) and `precise`.
  precise float predicted = grad_z.x * offset.x + grad_z.y * offset.y;
  precise float dz_max = frame.temporal_depth_relative * max(z, z_prev) + abs(predicted);
  const bool depth_ok = dz <= dz_max;
  // Normal: n(p) . n'(q) >= temporal_normal_cosine (svgf_params.h).
  const vec3 n = vec3(cur_normal_xyz[3u * p], cur_normal_xyz[3u * p + 1u], cur_normal_xyz[3u * p + 2u]);
  const vec3 n_prev = prev_normal_at(q);
  precise float cos_n = n.x * n_prev.x + n.y * n_prev.y + n.z * n_prev.z;
  const bool normal_ok = cos_n >= frame.temporal_normal_cosine;
  return same_mesh && depth_ok && normal_ok;
}

// The 2x2 bilinear resampling of the history at p' [SVGF17 Sec. 4.1]. A tap that fails the consistency test
// is discarded and the consistent taps' weights are renormalised to sum to 1. False when no consistent tap
// carries any weight.
bool resample_bilinear(int x, int y, vec2 p_prev, out HistorySample result) {
  result = HistorySample(vec3(0.0), 0.0, 0.0, 0.0);
  // Pixel centres sit at integer + 0.5, so the four centres around p' start at floor(p' - 0.5).
  precise vec2 s = p_prev - 0.5;
  const ivec2 q00 = ivec2(floor(s));
  // Where p' lies inside the square of those four centres: the bilinear interpolation parameters.
  precise vec2 f = s - floor(s);
  precise float sum_good = 0.0;
  HistorySample h = HistorySample(vec3(0.0), 0.0, 0.0, 0.0);
  for (int k = 0; k < 4; ++k) {
    const ivec2 d = ivec2(k & 1, k >> 1);  // (0, 0), (1, 0), (0, 1), (1, 1)
    // Bilinear weight: (1 - f) towards the near centre, f towards the far one, on each axis.
    precise float w = (d.x != 0 ? f.x : 1.0 - f.x) * (d.y != 0 ? f.y : 1.0 - f.y);
    const bool ok = temporal_tap_consistent(x, y, q00 + d, p_prev);
    sum_good += ok ? w : 0.0;
    if (ok) add_tap(h, q00 + d, w);
  }
  if (!(sum_good > 0.0)) return false;
  // sum_k w_k h_k / sum_k w_k over the consistent taps.
  result = scaled(h, 1.0 / sum_good);
  return true;
}

// The 3x3 fallback [SVGF17 Sec. 4.1]: the pixel whose square holds p' and its 8 neighbours, the consistent
// ones averaged with equal weights. False when none is consistent.
bool resample_3x3(int x, int y, vec2 p_prev, out HistorySample result) {
  result = HistorySample(vec3(0.0), 0.0, 0.0, 0.0);
  // The pixel containing p', i.e. the one whose centre is nearest to p'.
  const ivec2 c = ivec2(floor(p_prev));
  HistorySample h = HistorySample(vec3(0.0), 0.0, 0.0, 0.0);
  int count = 0;
  for (int dy = -1; dy <= 1; ++dy)
    for (int dx = -1; dx <= 1; ++dx) {
      if (!temporal_tap_consistent(x, y, c + ivec2(dx, dy), p_prev)) continue;
      add_tap(h, c + ivec2(dx, dy), 1.0);
      ++count;
    }
  if (count == 0) return false;
  result = scaled(h, 1.0 / float(count));
  return true;
}

// The history of pixel (x, y): bilinear at p', else the 3x3 fallback; false means a disocclusion.
bool backproject_history(int x, int y, out HistorySample result) {
  result = HistorySample(vec3(0.0), 0.0, 0.0, 0.0);
  const bool first_frame = frame.has_history == 0u;
  if (first_frame) return false;
  // p' = pixel centre + motion: where this pixel's surface point was in the previous frame, in pixels
  // [TRMV21 Eq. 1, the motion vector of SVGF17 Sec. 4.1].
  const uint p = cur_index(x, y);
  precise vec2 p_prev = vec2(float(x) + 0.5, float(y) + 0.5) + vec2(cur_motion_xy[2u * p], cur_motion_xy[2u * p + 1u]);
  // More than a pixel outside the previous image no tap of either filter can be inside (false for a NaN p'
  // too). Testing this first keeps floor(p') within int range.
  const float w = float(frame.prev_width), h = float(frame.prev_height);
  const bool near = p_prev.x > -1.0 && p_prev.y > -1.0 && p_prev.x < w + 1.0 && p_prev.y < h + 1.0;
  if (!near) return false;
  const bool bilinear = resample_bilinear(x, y, p_prev, result);
  return bilinear || resample_3x3(x, y, p_prev, result);
}

struct TemporalPixel {
  vec3 color;
  float moment1;
  float moment2;
  float len;  // C++: length (a GLSL method name: h.length would call .length())
};

// Disocclusion [SVGF17 Sec. 4.1]: the history is discarded, C'_i = C_i; the moments restart from this
// sample and the history length from 1.
TemporalPixel disocclusion(vec3 C, float l) {
  precise float l2 = l * l;
  return TemporalPixel(C, l, l2, 1.0);
}

// The exponential moving averages of colour and moments [SVGF17 Sec. 4.1, 4.2] with the history-length ramp.
TemporalPixel accumulate(vec3 C, float l, HistorySample h) {
  // n_i = n_{i-1} + 1, capped at n_max when the table sets one (max_history > 0).
  precise float n = h.len + 1.0;
  if (frame.max_history > 0u) n = min(n, float(frame.max_history));
  // alpha_eff = max(alpha, 1/n): a running mean while 1/n > alpha, then the paper's EMA (a deviation, temporal.h).
  const float alpha = max(frame.alpha, 1.0 / n);
  const float alpha_mu = max(frame.alpha_moments, 1.0 / n);
  // C'_i = alpha C_i + (1 - alpha) C'_{i-1}  [SVGF17 Sec. 4.1, unnumbered equation]
  precise vec3 color = alpha * C + (1.0 - alpha) * h.color;
  // mu1'_i = alpha_mu l + (1 - alpha_mu) mu1'_{i-1}  [SVGF17 Sec. 4.2, accumulated like the colour]
  precise float moment1 = alpha_mu * l + (1.0 - alpha_mu) * h.moment1;
  // mu2'_i = alpha_mu l^2 + (1 - alpha_mu) mu2'_{i-1}  [SVGF17 Sec. 4.2]
  precise float moment2 = alpha_mu * (l * l) + (1.0 - alpha_mu) * h.moment2;
  return TemporalPixel(color, moment1, moment2, n);
}

TemporalPixel temporal_pixel(int x, int y) {
  const uint p = cur_index(x, y);
  const bool covered = cur_mesh[p] != kTemporalInvalidId;
  if (!covered) return TemporalPixel(vec3(0.0), 0.0, 0.0, 0.0);  // no surface: colour, moments and length 0
  const vec3 C = vec3(noisy_rgb[3u * p], noisy_rgb[3u * p + 1u], noisy_rgb[3u * p + 2u]);
  // l: the luminance of the noisy colour; l and l^2 are its first two raw moments [SVGF17 Sec. 4.2].
  const float l = luminance(C);
  HistorySample h;
  const bool found = backproject_history(x, y, h);
  if (!found) return disocclusion(C, l);
  // n_{i-1}: the weighted mean of the taps' n rounded to whole frames, floor(x + 0.5) (temporal.cpp says why).
  precise float rounded = floor(h.len + 0.5);
  h.len = rounded;
  return accumulate(C, l, h);
}

void main() {
  // This invocation's pixel; the last tiles overhang the frame.
  const uvec2 pixel = gl_GlobalInvocationID.xy;
  if (pixel.x >= frame.width || pixel.y >= frame.height) return;
  const TemporalPixel t = temporal_pixel(int(pixel.x), int(pixel.y));
  const uint i = cur_index(int(pixel.x), int(pixel.y));
  out_color_rgb[3u * i] = t.color.r;
  out_color_rgb[3u * i + 1u] = t.color.g;
  out_color_rgb[3u * i + 2u] = t.color.b;
  out_moment1[i] = t.moment1;
  out_moment2[i] = t.moment2;
  out_length[i] = t.len;
}
