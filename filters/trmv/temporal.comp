// TRMV's temporal blend [TRMV21 Eq. 2] with the neighbourhood clamp of the history [TRMV21 Sec. 5], the Vulkan port
// of trmv_temporal_pixel (filters/trmv/temporal.cpp), function for function: fetch the history bilinearly at
// x_{i-1} = pixel centre + m (taps off the previous image or without a surface dropped, the rest renormalised), or
// take the re-shaded one; clamp it per channel to mu +- gamma sigma of c~ over the (2r+1)^2 window; blend
// cbar_i = alpha c~_i + (1 - alpha) cbar*_{i-1}. No history: alpha = 1, cbar_i = c~_i. One invocation per pixel.
// The choices the paper leaves open are the golden pass's (filters/trmv/temporal.h).
//   in:  bindings 0 c~_i, 1 id.mesh, 2 motion, 3 validity, 4 re-shaded history, 5 cbar_{i-1}, 6 the previous
//        id.mesh, 7 the alpha plane (theta, alpha^V); out: 8 (cbar_i, alpha), 9 (the fetched history, the alpha
//        plane's value) and 10 the clamped history.
//   Layout: filters/svgf/planes_shared.h and filters/trmv/temporal_shared.h.
// GPU only: every arithmetic result is `precise`, so no fma contraction or reordering changes the rounding; the
// C++ rounds after each operation in the same order (tests/gpu_trmv_temporal_test.cpp derives the bound).
#version 450
#extension GL_GOOGLE_include_directive : require
#extension GL_EXT_control_flow_attributes : require

#include "filters/trmv/temporal_shared.h"

// The workgroup's shape, per device: the SVGF ports' (planes_shared.h).
layout(local_size_x_id = kSvgfGroupSizeXConstant, local_size_y_id = kSvgfGroupSizeYConstant,
       local_size_x = kSvgfGroupSizeX, local_size_y = kSvgfGroupSizeY) in;

RTDR_INPUT_RGBA(0, filtered)
RTDR_INPUT_UINT(1, mesh)
RTDR_INPUT_RG(2, motion)
RTDR_INPUT_UINT(3, motion_valid)
RTDR_INPUT_RGBA(4, reshaded)
RTDR_INPUT_RGBA(5, prev_color)
RTDR_INPUT_UINT(6, prev_mesh)
RTDR_INPUT_RG(7, falloff)
layout(std430, set = 0, binding = 8) writeonly buffer OutColor { vec4 out_color[]; };
layout(std430, set = 0, binding = 9) writeonly buffer OutFetched { vec4 out_fetched[]; };
layout(std430, set = 0, binding = 10) writeonly buffer OutClamped { vec4 out_clamped[]; };

layout(push_constant) uniform Push { TrmvTemporalPush push; };

// GPU only: the push constants, copied once at the top of main(). lavapipe loads a push constant lane by lane at
// each use; the copy is loaded once.
TrmvTemporalPush frame;

// The planes' accessors (Plane::at, inside): element y * width + x of the current or the previous frame.
int cur_index(int x, int y) { return y * int(frame.width) + x; }
bool cur_inside(int x, int y) { return x >= 0 && y >= 0 && x < int(frame.width) && y < int(frame.height); }
int prev_index(ivec2 q) { return q.y * int(frame.prev_width) + q.x; }
bool prev_inside(ivec2 q) {
  return q.x >= 0 && q.y >= 0 && q.x < int(frame.prev_width) && q.y < int(frame.prev_height);
}

// One pixel of the pass's output (TrmvTemporalPixel).
struct TrmvTemporalPixel {
  vec3 color;    // cbar_i [TRMV21 Eq. 2]
  vec3 fetched;  // cbar_{i-1}(x_{i-1}), unclamped [TRMV21 Eq. 8's denominator]
  vec3 clamped;  // cbar*_{i-1}(x_{i-1}) [TRMV21 Sec. 5, Eq. 8]
  float alpha;   // the alpha of the blend: the input's, or 1 without history
};

// No history: alpha = 1 and cbar_i = c~_i; the fetched and clamped histories are 0 (temporal.h).
TrmvTemporalPixel without_history(vec3 c) { return TrmvTemporalPixel(c, vec3(0.0), vec3(0.0), 1.0); }

// The history bilinearly at p_prev = x_{i-1} in the previous image, taps outside it or without a surface
// dropped and the rest renormalised; false when no tap carries weight.
bool trmv_fetch_history(vec2 p_prev, out vec3 result) {
  result = vec3(0.0);
  const float w = float(frame.prev_width), h = float(frame.prev_height);
  // More than a pixel off the previous image no tap can be inside (false for NaN too); this also keeps
  // floor(p_prev) within int range for far-off vectors such as kMotionBehindCamera.
  if (!(p_prev.x > -1.0 && p_prev.y > -1.0 && p_prev.x < w + 1.0 && p_prev.y < h + 1.0)) return false;
  // Pixel centres sit at integer + 0.5: the four centres around p_prev start at floor(p_prev - 0.5), and f is
  // where p_prev lies in their square, the bilinear parameters.
  precise vec2 s = p_prev - 0.5;
  const ivec2 q00 = ivec2(floor(s));
  precise vec2 f = s - floor(s);
  precise float sum_w = 0.0;
  precise vec3 sum_wc = vec3(0.0);
  [[unroll]] for (int k = 0; k < 4; ++k) {
    const ivec2 d = ivec2(k & 1, k >> 1);  // (0, 0), (1, 0), (0, 1), (1, 1)
    const ivec2 q = q00 + d;
    // Outside the previous image, or no surface there: dropped.
    if (!prev_inside(q) || prev_mesh(prev_index(q)).x == RTDR_INVALID_ID) continue;
    // Bilinear weight: (1 - f) towards the near centre, f towards the far one, on each axis.
    precise float w_q = (d.x != 0 ? f.x : 1.0 - f.x) * (d.y != 0 ? f.y : 1.0 - f.y);
    sum_w += w_q;
    sum_wc += w_q * prev_color(prev_index(q)).rgb;
  }
  if (!(sum_w > 0.0)) return false;
  // cbar_{i-1}(x_{i-1}) = sum_q w_q cbar_{i-1}(q) / sum_q w_q over the kept taps [TRMV21 Eq. 2].
  precise vec3 fetched = sum_wc / sum_w;
  result = fetched;
  return true;
}

// cbar*_{i-1}: `history` clamped per channel to [mu - gamma sigma, mu + gamma sigma] of c~ over the (2r+1)^2
// window around (x, y) [TRMV21 Sec. 5]; gamma = 0 returns it unchanged.
vec3 trmv_clamp_history(vec3 history, float gamma, int radius, int x, int y) {
  if (!(gamma > 0.0)) return history;  // gamma = 0: no clamp ("Trad. (No clamp)")
  // The mean and the second raw moment of c~ over the window's pixels that see a surface, per channel.
  precise vec3 sum = vec3(0.0), sum_sq = vec3(0.0);
  int n = 0;
  for (int dy = -radius; dy <= radius; ++dy)
    for (int dx = -radius; dx <= radius; ++dx) {
      const int qx = x + dx, qy = y + dy;
      if (!cur_inside(qx, qy) || mesh(cur_index(qx, qy)).x == RTDR_INVALID_ID) continue;
      const vec3 c = filtered(cur_index(qx, qy)).rgb;
      sum += c;
      sum_sq += c * c;
      ++n;
    }
  precise vec3 mu = sum / float(n);  // n >= 1: the centre sees a surface
  // sigma = sqrt(E[c^2] - mu^2), the population standard deviation (rounding may make the difference < 0).
  precise vec3 sigma = sqrt(max(sum_sq / float(n) - mu * mu, vec3(0.0)));
  // cbar*_{i-1} = clamp(cbar_{i-1}, mu - gamma sigma, mu + gamma sigma), per channel [TRMV21 Sec. 5].
  precise vec3 clamped = clamp(history, mu - gamma * sigma, mu + gamma * sigma);
  return clamped;
}

// The alpha plane's value at pixel i: alpha^V [TRMV21 Eq. 4] where there is a plane, else the constant alpha.
float alpha_plane(int i) { return frame.has_alpha == 0u ? frame.alpha : falloff(i).y; }

// The golden per-pixel function, trmv_temporal_pixel.
TrmvTemporalPixel trmv_temporal_pixel(int x, int y) {
  const int i = cur_index(x, y);
  const vec3 c = filtered(i).rgb;  // c~_i [TRMV21 Eq. 2], spatially filtered
  const bool covered = mesh(i).x != RTDR_INVALID_ID;
  const bool first_frame = frame.has_history == 0u;
  const bool valid = frame.has_valid == 0u || motion_valid(i).x != 0u;
  if (!covered || first_frame || !valid) return without_history(c);
  TrmvTemporalPixel result = TrmvTemporalPixel(vec3(0.0), vec3(0.0), vec3(0.0), 1.0);  // C++: out (a GLSL keyword)
  if (frame.has_reshaded != 0u && reshaded(i).w != 0.0) {
    // A disoccluded pixel's history, re-shaded from the cones at x^O [TRMV21 Sec. 4.3, Eq. 11] (reshade.h).
    result.fetched = reshaded(i).rgb;
  } else {
    // x_{i-1} = x_i + m(x_i): where this pixel's content was in the previous frame [TRMV21 Eq. 1].
    precise vec2 p_prev = vec2(float(x) + 0.5, float(y) + 0.5) + motion(i).xy;
    if (!trmv_fetch_history(p_prev, result.fetched)) return without_history(c);
  }
  result.clamped = trmv_clamp_history(result.fetched, frame.clamp_gamma, frame.clamp_radius, x, y);
  result.alpha = alpha_plane(i);
  // cbar_i(x_i) = alpha c~_i(x_i) + (1 - alpha) cbar*_{i-1}(x_{i-1})  [TRMV21 Eq. 2], the history clamped.
  precise vec3 color = result.alpha * c + (1.0 - result.alpha) * result.clamped;
  result.color = color;
  return result;
}

// trmv_temporal_pass: trmv_temporal_pixel at every pixel.
void main() {
  frame = push;  // the push constants, read once (see above)
  // This invocation's pixel; the last tiles overhang the frame.
  const ivec2 pixel = ivec2(gl_GlobalInvocationID.xy);
  if (pixel.x >= int(frame.width) || pixel.y >= int(frame.height)) return;
  const TrmvTemporalPixel p = trmv_temporal_pixel(pixel.x, pixel.y);
  const int i = cur_index(pixel.x, pixel.y);
  out_color[i] = vec4(p.color, p.alpha);
  out_fetched[i] = vec4(p.fetched, alpha_plane(i));  // what the clean-up reads as alpha^V
  out_clamped[i] = vec4(p.clamped, 0.0);
}
