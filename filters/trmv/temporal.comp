// TRMV's temporal blend [TRMV21 Eq. 2] with the neighbourhood clamp of the history [TRMV21 Sec. 5], the Vulkan port
// of trmv_temporal_pixel (filters/trmv/temporal.cpp), function for function: fetch the history bilinearly at
// x_{i-1} = pixel centre + m (taps off the previous image, without a surface or failing the vector's history test
// dropped, the rest renormalised), or take the re-shaded one; clamp it per channel to mu +- gamma sigma of c~ over
// the (2r+1)^2 window (with same_surface, its pixels on the pixel's surface); blend
// cbar_i = alpha c~_i + (1 - alpha) cbar*_{i-1}. No history: alpha = 1, cbar_i = c~_i. One invocation per pixel.
// The choices the paper leaves open are the golden pass's (filters/trmv/temporal.h).
//   in:  bindings 0 c~_i, 1 id.mesh, 2 (n, z), 3 grad z, 4 (motion, code), 5 re-shaded history, 6 cbar_{i-1}, 7 the
//        previous id.mesh, 8 the previous (n, z), 9 the alpha plane (theta, alpha^V); out: 10 (cbar_i, alpha),
//        11 (the fetched history, the alpha plane's value) and 12 the clamped history.
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
RTDR_INPUT_RGBA(2, surface)
RTDR_INPUT_RG(3, depth_grad)
RTDR_INPUT_RGBA(4, vector)
RTDR_INPUT_RGBA(5, reshaded)
RTDR_INPUT_RGBA(6, prev_color)
RTDR_INPUT_UINT(7, prev_mesh)
RTDR_INPUT_RGBA(8, prev_surface)
RTDR_INPUT_RG(9, falloff)
layout(std430, set = 0, binding = 10) writeonly buffer OutColor { vec4 out_color[]; };
layout(std430, set = 0, binding = 11) writeonly buffer OutFetched { vec4 out_fetched[]; };
layout(std430, set = 0, binding = 12) writeonly buffer OutClamped { vec4 out_clamped[]; };

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

// SVGF's consistency test of tap q (previous index iq, with id mesh_q and record (n, z)) for pixel i reached at
// p_prev: filters/svgf/temporal.cpp's temporal_tap_consistent, operation for operation (temporal.comp of SVGF has
// its own copy, on its own planes): the same mesh id, |z - z'| <= depth_relative max(z, z') + |grad z . (q - p')|,
// n . n' >= normal_cosine.
bool tap_consistent(int i, ivec2 q, uint mesh_q, vec4 surface_q, vec2 p_prev) {
  precise vec2 offset = vec2(q) + 0.5 - p_prev;  // the tap's centre relative to p'
  const bool same_mesh = mesh_q == mesh(i).x;
  const vec4 s_p = surface(i);
  const float z = s_p.w, z_q = surface_q.w;
  const float dz = abs(z - z_q);
  const vec2 grad_z = depth_grad(i).xy;
  // GPU only: glm::dot written out ((x x) + (y y)) and `precise`.
  precise float predicted = grad_z.x * offset.x + grad_z.y * offset.y;
  precise float dz_max = frame.temporal_depth_relative * max(z, z_q) + abs(predicted);
  const bool depth_ok = dz <= dz_max;
  precise float cos_n = s_p.x * surface_q.x + s_p.y * surface_q.y + s_p.z * surface_q.z;
  const bool normal_ok = cos_n >= frame.temporal_normal_cosine;
  return same_mesh && depth_ok && normal_ok;
}

// trmv_tap_passes: does previous pixel q pass pixel i's history test? Inside the previous image, a surface there,
// and the test: none, the same mesh, or SVGF's consistency test.
bool tap_passes(uint test, int i, ivec2 q, vec2 p_prev) {
  if (!prev_inside(q)) return false;
  const int iq = prev_index(q);
  const uint mesh_q = prev_mesh(iq).x;
  if (mesh_q == RTDR_INVALID_ID) return false;
  if (test == kTrmvTestNone) return true;
  if (test == kTrmvTestMesh) return mesh_q == mesh(i).x;
  return tap_consistent(i, q, mesh_q, prev_surface(iq), p_prev);
}

// The history of pixel i bilinearly at p_prev = x_{i-1} in the previous image, the taps that fail `test` dropped and
// the rest renormalised (trmv_history_taps, then trmv_apply_taps); false when no tap carries weight.
bool trmv_fetch_history(uint test, int i, vec2 p_prev, out vec3 result) {
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
  ivec2 taps[4];
  float weights[4];
  int count = 0;
  [[unroll]] for (int k = 0; k < 4; ++k) {
    const ivec2 d = ivec2(k & 1, k >> 1);  // (0, 0), (1, 0), (0, 1), (1, 1)
    const ivec2 q = q00 + d;
    // Outside the previous image, no surface there, or not what the vector claims: dropped.
    if (!tap_passes(test, i, q, p_prev)) continue;
    // Bilinear weight: (1 - f) towards the near centre, f towards the far one, on each axis.
    precise float w_q = (d.x != 0 ? f.x : 1.0 - f.x) * (d.y != 0 ? f.y : 1.0 - f.y);
    taps[count] = q;
    weights[count] = w_q;
    ++count;
    sum_w += w_q;
  }
  if (!(sum_w > 0.0)) return false;
  // cbar_{i-1}(x_{i-1}) = sum_q (w_q / sum w) cbar_{i-1}(q) over the kept taps [TRMV21 Eq. 2].
  precise vec3 fetched = vec3(0.0);
  for (int k = 0; k < count; ++k) {
    precise float w_k = weights[k] / sum_w;
    fetched += w_k * prev_color(prev_index(taps[k])).rgb;
  }
  result = fetched;
  return true;
}

// cbar*_{i-1}: `history` clamped per channel to [mu - gamma sigma, mu + gamma sigma] of c~ over the (2r+1)^2
// window around (x, y) [TRMV21 Sec. 5], with same_surface its pixels that pass SVGF's consistency test against
// (x, y) in this frame; gamma = 0 returns it unchanged.
vec3 trmv_clamp_history(vec3 history, float gamma, int radius, int x, int y) {
  if (!(gamma > 0.0)) return history;  // gamma = 0: no clamp ("Trad. (No clamp)")
  const int i = cur_index(x, y);
  const vec2 centre = vec2(float(x) + 0.5, float(y) + 0.5);
  // The mean and the second raw moment of c~ over the window's pixels that see a surface, per channel.
  precise vec3 sum = vec3(0.0), sum_sq = vec3(0.0);
  int n = 0;
  for (int dy = -radius; dy <= radius; ++dy)
    for (int dx = -radius; dx <= radius; ++dx) {
      const int qx = x + dx, qy = y + dy;
      if (!cur_inside(qx, qy)) continue;
      const int iq = cur_index(qx, qy);
      const uint mesh_q = mesh(iq).x;
      if (mesh_q == RTDR_INVALID_ID) continue;
      if (frame.same_surface != 0u && !tap_consistent(i, ivec2(qx, qy), mesh_q, surface(iq), centre)) continue;
      const vec3 c = filtered(iq).rgb;
      sum += c;
      sum_sq += c * c;
      ++n;
    }
  precise vec3 mu = sum / float(n);  // n >= 1: the centre sees a surface, and is its own surface
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
  const vec4 v = vector(i);  // (m, code): code 0 no vector, else 1 + its history test (temporal_shared.h)
  const bool valid = v.z != 0.0;
  if (!covered || first_frame || !valid) return without_history(c);
  TrmvTemporalPixel result = TrmvTemporalPixel(vec3(0.0), vec3(0.0), vec3(0.0), 1.0);  // C++: out (a GLSL keyword)
  if (frame.has_reshaded != 0u && reshaded(i).w != 0.0) {
    // A disoccluded pixel's history, re-shaded from the cones at x^O [TRMV21 Sec. 4.3, Eq. 11] (reshade.h).
    result.fetched = reshaded(i).rgb;
  } else {
    // x_{i-1} = x_i + m(x_i): where this pixel's content was in the previous frame [TRMV21 Eq. 1].
    precise vec2 p_prev = vec2(float(x) + 0.5, float(y) + 0.5) + v.xy;
    if (!trmv_fetch_history(uint(v.z) - 1u, i, p_prev, result.fetched)) return without_history(c);
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
