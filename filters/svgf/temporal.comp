// Temporal accumulation [SVGF17 Sec. 4.1, 4.2], the Vulkan port of temporal_pixel (temporal.cpp), function for
// function: back-project along the motion vector, resample the history with consistency-tested 2x2 bilinear
// taps, else a 3x3 fallback, else a disocclusion; then the EMA of colour and moments with
// alpha_eff = max(alpha, 1/n). One invocation per pixel for both streams, direct and indirect: the consistency
// tests and tap weights depend on the G-buffers alone, so they are computed once and applied to both histories.
//   in:  bindings 0 noisy illumination (both streams); 1-4 current surface, depth gradient, mesh id, motion;
//        5 history illumination (both streams), 6-7 history moments (direct, indirect); 8-9 previous surface, mesh id.
//   out: bindings 10 illumination (C', 0) (both streams), 11-12 moments (mu1', mu2', n, 0) (direct, indirect).
//   A-SVGF (push.adaptive): bindings 13-14 (lambda_max, alpha_i, alpha_mu_i, 0) per pixel of the direct and the
//   indirect stream, as filters/asvgf/adaptive_alpha.comp makes them [ASVGF18 Eq. 15]: alpha_i and alpha_mu_i
//   replace alpha and alpha_mu, and with push.restart_history the history length falls to (1 - lambda) n_{i-1}
//   [ASVGF18 Sec. 4].
//   Layout: planes_shared.h and temporal_shared.h.
#version 450
#extension GL_GOOGLE_include_directive : require
#extension GL_EXT_control_flow_attributes : require

#include "core/color.glsl"
#include "filters/svgf/temporal_shared.h"

// The workgroup's shape, per device (planes_shared.h).
layout(local_size_x_id = kSvgfGroupSizeXConstant, local_size_y_id = kSvgfGroupSizeYConstant,
       local_size_x = kSvgfGroupSizeX, local_size_y = kSvgfGroupSizeY) in;

RTDR_INPUT_ILLUMINATION(0, noisy)
RTDR_INPUT_RGBA(1, cur_surface)
RTDR_INPUT_RG(2, cur_depth_grad)
RTDR_INPUT_UINT(3, cur_mesh)
RTDR_INPUT_RG(4, cur_motion)
RTDR_INPUT_ILLUMINATION(5, prev_illumination)
RTDR_INPUT_RGBA(6, prev_moments_direct)
RTDR_INPUT_RGBA(7, prev_moments_indirect)
RTDR_INPUT_RGBA(8, prev_surface)
RTDR_INPUT_UINT(9, prev_mesh)
RTDR_OUTPUT_ILLUMINATION(10, out_illumination)
layout(std430, set = 0, binding = 11) writeonly buffer OutMomentsDirect { vec4 out_moments_direct[]; };
layout(std430, set = 0, binding = 12) writeonly buffer OutMomentsIndirect { vec4 out_moments_indirect[]; };
layout(std430, set = 0, binding = 13) readonly buffer AdaptiveDirect { vec4 adaptive_direct[]; };
layout(std430, set = 0, binding = 14) readonly buffer AdaptiveIndirect { vec4 adaptive_indirect[]; };

layout(push_constant) uniform Push { TemporalPush push; };

// GPU only: the push constants, copied once at the top of main(). lavapipe loads a push constant lane by lane at
// each use; the copy is loaded once.
TemporalPush frame;

// The planes' accessors (Plane::at, inside): element y * width + x of the current or the previous frame.
int cur_index(int x, int y) { return y * int(frame.width) + x; }
int prev_index(ivec2 q) { return q.y * int(frame.prev_width) + q.x; }
bool prev_inside(ivec2 q) { return q.x >= 0 && q.y >= 0 && q.x < int(frame.prev_width) && q.y < int(frame.prev_height); }

// One stream's history values at p': weighted sums while the taps are gathered, the resampled history afterwards.
struct HistorySample {
  vec3 color;
  float moment1;
  float moment2;
  float len;  // C++: length (a GLSL method name: h.length would call .length())
};
// Both streams': 0 direct, 1 indirect.
struct Histories {
  HistorySample stream[2];
};
const HistorySample kNoHistory = HistorySample(vec3(0.0), 0.0, 0.0, 0.0);
const Histories kNoHistories = Histories(HistorySample[2](kNoHistory, kNoHistory));

// GPU only: every arithmetic on history samples is `precise`, so no fma changes C++'s rounding.
HistorySample add_tap(HistorySample h, vec4 color, vec4 moments, float w) {
  precise vec3 c = h.color + w * color.rgb;
  precise float moment1 = h.moment1 + w * moments.x;
  precise float moment2 = h.moment2 + w * moments.y;
  precise float len = h.len + w * moments.z;
  return HistorySample(c, moment1, moment2, len);
}
void add_taps(inout Histories h, ivec2 q, float w) {
  const int i = prev_index(q);
  const Illumination c = prev_illumination(i);
  h.stream[0] = add_tap(h.stream[0], c.stream[0], prev_moments_direct(i), w);
  h.stream[1] = add_tap(h.stream[1], c.stream[1], prev_moments_indirect(i), w);
}

HistorySample scaled(HistorySample h, float s) {
  precise vec3 color = s * h.color;
  precise float moment1 = s * h.moment1, moment2 = s * h.moment2, len = s * h.len;
  return HistorySample(color, moment1, moment2, len);
}
Histories scaled(Histories h, float s) { return Histories(HistorySample[2](scaled(h.stream[0], s), scaled(h.stream[1], s))); }

// What the consistency test needs to know about p, read once per pixel.
struct Centre {
  uint mesh;    // id.mesh(p)
  float z;      // z(p)
  vec2 grad_z;  // grad z(p)
  vec3 n;       // n(p)
};

// The consistency test of one history tap (temporal.h): q inside the previous image, same mesh id, depth and
// normal within the thresholds [SVGF17 Sec. 4.1].
bool temporal_tap_consistent(Centre c, ivec2 q, vec2 p_prev) {
  // The tap's centre relative to p', in pixels.
  precise vec2 offset = vec2(q) + 0.5 - p_prev;
  // The tap must exist in the previous frame.
  const bool in_image = prev_inside(q);
  if (!in_image) return false;
  const int iq = prev_index(q);
  // Mesh ids compare exactly; a tap with no surface (kInvalidId) never matches a covered pixel.
  const bool same_mesh = prev_mesh(iq).x == c.mesh;
  // Depth: |z - z'| <= temporal_depth_relative max(z, z') + |grad z(p) . (q - p')|  (temporal.h).
  const vec4 s_prev = prev_surface(iq);
  const float z_prev = s_prev.w;
  const float dz = abs(c.z - z_prev);
  // GPU only: glm::dot written out ((x x) + (y y)) and `precise`.
  precise float predicted = c.grad_z.x * offset.x + c.grad_z.y * offset.y;
  precise float dz_max = frame.temporal_depth_relative * max(c.z, z_prev) + abs(predicted);
  const bool depth_ok = dz <= dz_max;
  // Normal: n(p) . n'(q) >= temporal_normal_cosine (svgf_params.h).
  const vec3 n_prev = s_prev.xyz;
  precise float cos_n = c.n.x * n_prev.x + c.n.y * n_prev.y + c.n.z * n_prev.z;
  const bool normal_ok = cos_n >= frame.temporal_normal_cosine;
  return same_mesh && depth_ok && normal_ok;
}

// The 2x2 bilinear resampling of the history at p' [SVGF17 Sec. 4.1]. A tap that fails the consistency test
// is discarded and the consistent taps' weights are renormalised to sum to 1. False when no consistent tap
// carries any weight.
bool resample_bilinear(Centre c, vec2 p_prev, out Histories result) {
  result = kNoHistories;
  // Pixel centres sit at integer + 0.5, so the four centres around p' start at floor(p' - 0.5).
  precise vec2 s = p_prev - 0.5;
  const ivec2 q00 = ivec2(floor(s));
  // Where p' lies inside the square of those four centres: the bilinear interpolation parameters.
  precise vec2 f = s - floor(s);
  precise float sum_good = 0.0;
  Histories h = kNoHistories;
  [[unroll]] for (int k = 0; k < 4; ++k) {
    const ivec2 d = ivec2(k & 1, k >> 1);  // (0, 0), (1, 0), (0, 1), (1, 1)
    // Bilinear weight: (1 - f) towards the near centre, f towards the far one, on each axis.
    precise float w = (d.x != 0 ? f.x : 1.0 - f.x) * (d.y != 0 ? f.y : 1.0 - f.y);
    const bool ok = temporal_tap_consistent(c, q00 + d, p_prev);
    sum_good += ok ? w : 0.0;
    if (ok) add_taps(h, q00 + d, w);
  }
  if (!(sum_good > 0.0)) return false;
  // sum_k w_k h_k / sum_k w_k over the consistent taps.
  result = scaled(h, 1.0 / sum_good);
  return true;
}

// The 3x3 fallback [SVGF17 Sec. 4.1]: the pixel whose square holds p' and its 8 neighbours, the consistent
// ones averaged with equal weights. False when none is consistent.
bool resample_3x3(Centre c, vec2 p_prev, out Histories result) {
  result = kNoHistories;
  // The pixel containing p', i.e. the one whose centre is nearest to p'.
  const ivec2 q_c = ivec2(floor(p_prev));
  Histories h = kNoHistories;
  int count = 0;
  for (int dy = -1; dy <= 1; ++dy)
    for (int dx = -1; dx <= 1; ++dx) {
      if (!temporal_tap_consistent(c, q_c + ivec2(dx, dy), p_prev)) continue;
      add_taps(h, q_c + ivec2(dx, dy), 1.0);
      ++count;
    }
  if (count == 0) return false;
  result = scaled(h, 1.0 / float(count));
  return true;
}

// The history of pixel (x, y): bilinear at p', else the 3x3 fallback; false means a disocclusion.
bool backproject_history(int x, int y, Centre c, out Histories result) {
  result = kNoHistories;
  const bool first_frame = frame.has_history == 0u;
  if (first_frame) return false;
  // p' = pixel centre + motion: where this pixel's surface point was in the previous frame, in pixels
  // [TRMV21 Eq. 1, the motion vector of SVGF17 Sec. 4.1].
  precise vec2 p_prev = vec2(float(x) + 0.5, float(y) + 0.5) + cur_motion(cur_index(x, y)).xy;
  // More than a pixel outside the previous image no tap of either filter can be inside (false for a NaN p'
  // too). Testing this first keeps floor(p') within int range.
  const float w = float(frame.prev_width), h = float(frame.prev_height);
  const bool near = p_prev.x > -1.0 && p_prev.y > -1.0 && p_prev.x < w + 1.0 && p_prev.y < h + 1.0;
  if (!near) return false;
  const bool bilinear = resample_bilinear(c, p_prev, result);
  return bilinear || resample_3x3(c, p_prev, result);
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

// One stream's temporal weights: SVGF's constant alpha and alpha_mu, or A-SVGF's alpha_i and alpha_mu_i with the
// lambda they were made from (TemporalAdaptive, temporal.h).
struct Weights {
  float lambda;
  float alpha;
  float alpha_mu;
};

// The exponential moving averages of colour and moments [SVGF17 Sec. 4.1, 4.2] with the history-length ramp, with
// the weights alpha (colour) and alpha_mu (moments): the table's, or A-SVGF's alpha_i and alpha_mu_i.
TemporalPixel accumulate(vec3 C, float l, HistorySample h, Weights weights) {
  // n_i = n_{i-1} + 1, capped at n_max when the table sets one (max_history > 0).
  precise float n = h.len + 1.0;
  if (frame.max_history > 0u) n = min(n, float(frame.max_history));
  // alpha_eff = max(alpha, 1/n): a running mean while 1/n > alpha, then the paper's EMA (a deviation, temporal.h).
  const float alpha = max(weights.alpha, 1.0 / n);
  const float alpha_mu = max(weights.alpha_mu, 1.0 / n);
  // C'_i = alpha C_i + (1 - alpha) C'_{i-1}  [SVGF17 Sec. 4.1, unnumbered equation], A-SVGF's [ASVGF18 Eq. 1]
  precise vec3 color = alpha * C + (1.0 - alpha) * h.color;
  // mu1'_i = alpha_mu l + (1 - alpha_mu) mu1'_{i-1}  [SVGF17 Sec. 4.2, accumulated like the colour]
  precise float moment1 = alpha_mu * l + (1.0 - alpha_mu) * h.moment1;
  // mu2'_i = alpha_mu l^2 + (1 - alpha_mu) mu2'_{i-1}  [SVGF17 Sec. 4.2]
  precise float moment2 = alpha_mu * (l * l) + (1.0 - alpha_mu) * h.moment2;
  return TemporalPixel(color, moment1, moment2, n);
}

// One stream's result from its noisy colour C and its back-projected history (found: not a disocclusion), with
// its weights.
TemporalPixel temporal_stream(vec3 C, bool found, HistorySample h, Weights weights) {
  // l: the luminance of the noisy colour; l and l^2 are its first two raw moments [SVGF17 Sec. 4.2].
  const float l = luminance(C);
  if (!found) return disocclusion(C, l);
  // n_{i-1}: the weighted mean of the taps' n rounded to whole frames, floor(x + 0.5) (temporal.cpp says why).
  precise float rounded = floor(h.len + 0.5);
  h.len = rounded;
  // A-SVGF: a dropped history restarts, n_{i-1} <- (1 - lambda) n_{i-1} [ASVGF18 Sec. 4] (temporal.h).
  if (frame.restart_history != 0u) {
    precise float restarted = h.len * (1.0 - weights.lambda);
    h.len = restarted;
  }
  return accumulate(C, l, h, weights);
}

void write(int i, TemporalPixel direct, TemporalPixel indirect) {
  out_illumination(i, Illumination(vec4[2](vec4(direct.color, 0.0), vec4(indirect.color, 0.0))));
  out_moments_direct[i] = vec4(direct.moment1, direct.moment2, direct.len, 0.0);
  out_moments_indirect[i] = vec4(indirect.moment1, indirect.moment2, indirect.len, 0.0);
}

void main() {
  frame = push;  // the push constants, read once (see above)
  // This invocation's pixel; the last tiles overhang the frame.
  const ivec2 pixel = ivec2(gl_GlobalInvocationID.xy);
  if (pixel.x >= int(frame.width) || pixel.y >= int(frame.height)) return;
  const int i = cur_index(pixel.x, pixel.y);
  const vec4 s = cur_surface(i);
  const Centre c = Centre(cur_mesh(i).x, s.w, cur_depth_grad(i).xy, s.xyz);
  // No surface: colour, moments and length 0.
  const TemporalPixel none = TemporalPixel(vec3(0.0), 0.0, 0.0, 0.0);
  if (!has_surface(s)) {
    write(i, none, none);
    return;
  }
  Histories h;
  const bool found = backproject_history(pixel.x, pixel.y, c, h);
  const Illumination C = noisy(i);
  // Per stream: A-SVGF's (lambda_max, alpha_i, alpha_mu_i) [ASVGF18 Eq. 15], or SVGF's constant weights.
  const Weights constant = Weights(0.0, frame.alpha, frame.alpha_moments);
  const bool adaptive = frame.adaptive != 0u;
  const vec4 a_d = adaptive ? adaptive_direct[i] : vec4(0.0), a_i = adaptive ? adaptive_indirect[i] : vec4(0.0);
  const Weights direct = adaptive ? Weights(a_d.x, a_d.y, a_d.z) : constant;
  const Weights indirect = adaptive ? Weights(a_i.x, a_i.y, a_i.z) : constant;
  write(i, temporal_stream(C.stream[0].rgb, found, h.stream[0], direct),
        temporal_stream(C.stream[1].rgb, found, h.stream[1], indirect));
}
