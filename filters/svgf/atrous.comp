// One level of SVGF's edge-avoiding a-trous wavelet filter [SVGF17 Sec. 4.3, Eq. 1-5] with its variance prefilter
// [SVGF17 Sec. 4.4], the Vulkan port of atrous_pixel (atrous.cpp) and prefilter_variance_pixel (prefilter.cpp),
// line for line (read_centre, tap_weight and centre_weight likewise):
//   g3x3(Var(c_i))(p) = sum g(dx) g(dy) Var(c_i)(p + (dx, dy)), clamped borders  (Eq. 5's prefilter)
//   w(p, q)           = w_z w_n w_l                                               (Eq. 2-5)
//   c_{i+1}(p)        = sum h w c_i(q) / sum h w                                  (Eq. 1)
//   Var(c_{i+1}(p))   = sum h^2 w^2 Var(c_i(q)) / (sum h w)^2                     (Sec. 4.3)
// Same skip rules: taps outside the image and taps without a surface add nothing, a pixel without a surface passes
// through, the centre tap gets w = 1.
// What differs from the golden pass, and why (each marked GPU only below):
// - The three weights are fused into exp(sigma_n ln cos - a_z - a_l): one exp and one log per tap instead of two
//   exps and a pow. Equal up to float rounding; the port's error bound covers it (tests/gpu_atrous_test.cpp).
// - g3x3(Var) is computed per pixel here (and once more when keep_prefiltered asks for it to be written), where
//   the golden atrous_level prefilters the whole frame first. The same sum in the same order.
// - A skipped tap gets w = 0 and adds zeros, rather than being skipped by a branch: the same sums.
// - One dispatch per level filters both streams, direct and indirect, with one fetch of the tap's surface record
//   (whose w_z and w_n [Eq. 3, 4] both streams share; only w_l [Eq. 5] differs) and of its illumination pair
//   (planes_shared.h).
// - A plain gather, no shared memory, and the kernel size as a specialization constant, so the compiler unrolls
//   the taps. Both choices were measured; the figures are in docs/performance.md.
//   in:  bindings 0: illumination (c_i, Var(c_i)) of both streams, direct and indirect; 1: surface; 2: depth
//        gradient;
//   out: bindings 3: illumination (c_{i+1}, Var(c_{i+1})); 4: g3x3(Var(c_i)) of both streams, written only
//        when frame.keep_prefiltered is set. Layout: planes_shared.h and atrous_shared.h.
#version 450
#extension GL_GOOGLE_include_directive : require
#extension GL_EXT_control_flow_attributes : require

#include "core/color.glsl"
#include "filters/svgf/atrous_shared.h"
#include "filters/svgf/edge_stopping.glsl"

// The workgroup's shape, per device (planes_shared.h).
layout(local_size_x_id = kSvgfGroupSizeXConstant, local_size_y_id = kSvgfGroupSizeYConstant,
       local_size_x = kSvgfGroupSizeX, local_size_y = kSvgfGroupSizeY) in;

RTDR_INPUT_ILLUMINATION(0, illumination_in)
RTDR_INPUT_RGBA(1, surface)
RTDR_INPUT_RG(2, depth_grad)
RTDR_OUTPUT_ILLUMINATION(3, illumination_out)
layout(std430, set = 0, binding = 4) writeonly buffer Prefiltered { vec2 prefiltered_out[]; };

layout(push_constant) uniform Push { AtrousPush push; };

// GPU only: the push constants, copied once at the top of main(). lavapipe loads a push constant lane by lane at
// each use; the copy is loaded once.
AtrousPush frame;

// The kernel size, 5 or 3 (SvgfParams::kernel_size), fixed when the host creates the pipeline (a specialization
// constant): the compiler knows the taps and unrolls the loops over them. 5 is only the unspecialized value.
layout(constant_id = kAtrousKernelSizeConstant) const int kernel_size = 5;

// Plane accessors (filters/image.h's at, inside): pixel (x, y) at y * width + x.
int index_of(int x, int y) { return y * int(frame.width) + x; }
bool inside(int x, int y) { return x >= 0 && y >= 0 && x < int(frame.width) && y < int(frame.height); }

// --- prefilter.cpp ---

// The 1D binomial weights (1/4, 1/2, 1/4) (prefilter.h's kGaussian3).
const float kGaussian3[3] = float[3](kPrefilterEdge, kPrefilterCentre, kPrefilterEdge);

// g3x3(Var(c_i)) at (x, y) for both streams: the 3x3 binomial blur of the variance, border pixels repeated
// (at_clamped) [SVGF17 Sec. 4.4].
vec2 prefilter_variance_pixel(int x, int y) {
  precise vec2 sum = vec2(0.0f);
  [[unroll]] for (int dy = -1; dy <= 1; ++dy)
    [[unroll]] for (int dx = -1; dx <= 1; ++dx) {
      // The binomial weight of this tap, g(dx) g(dy): 1/4 at the centre, 1/8 at the edges, 1/16 at the corners.
      const float g = kGaussian3[dx + 1] * kGaussian3[dy + 1];
      // The neighbour's variance, the border pixel where (x + dx, y + dy) falls outside.
      const int qx = clamp(x + dx, 0, int(frame.width) - 1), qy = clamp(y + dy, 0, int(frame.height) - 1);
      const Illumination q = illumination_in(index_of(qx, qy));
      // GPU only: `precise` keeps g * var_q and the sum two roundings, as in the golden function.
      sum += g * vec2(q.stream[0].w, q.stream[1].w);
    }
  return sum;
}

// --- atrous.cpp (the weights: edge_stopping.glsl) ---

// What the weights need to know about p, read once per pixel.
struct Centre {
  int x, y;
  float z;            // z(p), linear view depth
  vec2 grad_z;        // grad z(p), per pixel [SVGF17 Eq. 3]
  vec3 n;             // n(p), world space [SVGF17 Eq. 4]
  vec2 l;             // l_i(p), luminance of this level's input [SVGF17 Eq. 5], per stream
  vec2 var_g3x3;      // g3x3(Var(l_i))(p) [SVGF17 Eq. 5], per stream
  vec2 l_scale;       // Eq. 5's denominator, sigma_l sqrt(g3x3(Var)(p)) + epsilon, per stream (GPU only: once
                      // per pixel; the golden weight_luminance computes it per tap)
};

Centre read_centre(int x, int y, vec4 s, Illumination c) {
  const vec2 var_g3x3 = prefilter_variance_pixel(x, y);
  const vec2 l = vec2(luminance(c.stream[0].rgb), luminance(c.stream[1].rgb));
  const vec2 l_scale = vec2(luminance_scale(var_g3x3[0], frame.sigma_l, frame.epsilon),
                            luminance_scale(var_g3x3[1], frame.sigma_l, frame.epsilon));
  return Centre(x, y, s.w, depth_grad(index_of(x, y)).xy, s.xyz, l, var_g3x3, l_scale);
}

// w(p, q) = w_z w_n w_l [SVGF17 Eq. 2] of both streams for a tap q != p with surface record s_q and
// illumination c_q.
vec2 tap_weight(Centre c, int qx, int qy, vec4 s_q, Illumination c_q) {
  // p - q in pixels, at the tap's real distance (the step 2^i included) [SVGF17 Eq. 3].
  const vec2 offset_pq = vec2(float(c.x - qx), float(c.y - qy));
  const float z_q = s_q.w;
  const float a_z = depth_exponent(c.z, z_q, c.grad_z, offset_pq, frame.sigma_z, frame.epsilon);
  const float cos_pq = max(0.0f, dot3(c.n, s_q.xyz));
  const vec2 l_q = vec2(luminance(c_q.stream[0].rgb), luminance(c_q.stream[1].rgb));
  const vec2 a_l = abs(c.l - l_q) / c.l_scale;
  // w = w_z w_n w_l [SVGF17 Eq. 2] = exp(-a_z) cos^sigma_n exp(-a_l) = exp(sigma_n ln cos - a_z - a_l).
  // GPU only: one exp and one log for the three weights, where the golden tap_weight calls weight_depth,
  // weight_normal and weight_luminance and multiplies (two exps and a pow). The same value up to float
  // rounding, inside the port's error bound (tests/gpu_atrous_test.cpp). sigma_n ln cos - a_z is the same for
  // both streams.
  precise float exponent_zn = frame.sigma_n * log(cos_pq) - a_z;
  precise vec2 exponent = exponent_zn - a_l;
  // w_n = 0 when facing away. GPU only: a select, not an early return (see main()).
  return cos_pq > 0.0f ? exp(exponent) : vec2(0.0f);
}

// h(k), the 1D kernel weight of tap k (atrous_kernel) [SVGF17 Eq. 1, ASVGF18 Sec. 4]: the B3 spline (1/16, 1/4, 3/8,
// 1/4, 1/16) for kernel_size 5, the box (1/3, 1/3, 1/3) for 3. GPU only: selects, not a table, which lavapipe would
// keep in per-invocation memory; with the taps unrolled they fold to constants.
float kernel_weight(int k) {
  if (kernel_size != 5) return kAtrousBox;
  return k == 0 ? kAtrousB3Centre : (abs(k) == 1 ? kAtrousB3Inner : kAtrousB3Outer);
}

// w(p, p) = 1: Eq. 3-5 at q = p, written down rather than computed (see atrous.cpp's banner).
float centre_weight() { return 1.0f; }

void main() {
  frame = push;  // the push constants, read once (see above)
  // This invocation's pixel; the last tiles overhang the frame.
  const int x = int(gl_GlobalInvocationID.x), y = int(gl_GlobalInvocationID.y);
  if (x >= int(frame.width) || y >= int(frame.height)) return;
  const int i = index_of(x, y);
  const vec4 s_p = surface(i);
  const Illumination c_p = illumination_in(i);
  if (frame.keep_prefiltered != 0u) prefiltered_out[i] = prefilter_variance_pixel(x, y);

  // No surface, nothing to compare with: the input passes through.
  if (!has_surface(s_p)) {
    illumination_out(i, c_p);
    return;
  }
  // atrous_kernel (atrous.cpp): the host has checked kernel_size is 5 or 3; the weights are atrous_shared.h's.
  const int radius = kernel_size == 5 ? 2 : 1;
  const int step = 1 << frame.level;  // 2^i: the taps' spacing at level i
  const Centre centre = read_centre(x, y, s_p, c_p);

  // GPU only: `precise` on the sums keeps each product and add a separate rounding, as in the golden function.
  // Per stream s: sum h w [SVGF17 Eq. 1, denominator], sum h w c_i(q) [Eq. 1, numerator], and
  // sum h^2 w^2 Var(c_i(q)) [SVGF17 Sec. 4.3].
  precise vec2 sum_hw = vec2(0.0f);
  precise vec3 sum_hwc[2] = vec3[2](vec3(0.0f), vec3(0.0f));
  precise vec2 sum_h2w2_var = vec2(0.0f);
  [[unroll]] for (int j = -radius; j <= radius; ++j)
    [[unroll]] for (int k = -radius; k <= radius; ++k) {
      const int qx = x + k * step, qy = y + j * step;  // the tap q, 2^i (k, j) away from p
      // The golden code skips a tap off the image (sum h w renormalises over the taps that remain) and a tap without a
      // surface (nothing to filter there). GPU only: such a tap gets w = 0 instead, read at the nearest pixel of the
      // image, and adds zeros to the sums: the same sums, since the planes hold finite values (a precondition of the
      // ports, gpu/atrous_gpu.h; rtdr filter rejects NaN and Inf in its input frames, app/sequence.cpp). lavapipe runs
      // every branch's body for all lanes anyway, and a select costs less than the masked updates of the sums (4% fewer
      // instructions).
      const bool in_image = inside(qx, qy);
      const int q = index_of(clamp(qx, 0, int(frame.width) - 1), clamp(qy, 0, int(frame.height) - 1));
      const vec4 s_q = surface(q);
      const bool skipped = !in_image || !has_surface(s_q);
      const Illumination c_q = illumination_in(q);
      const float hk = kernel_weight(k), hj = kernel_weight(j);
      precise float h = hk * hj;  // h(q) = h(dx) h(dy)
      // w(p, q) [SVGF17 Eq. 2] per stream; 1 at the centre tap, where every edge-stopping weight is 1.
      const vec2 w = skipped                ? vec2(0.0f)
                     : (k == 0 && j == 0) ? vec2(centre_weight())
                                          : tap_weight(centre, qx, qy, s_q, c_q);
      const vec2 var_q = vec2(c_q.stream[0].w, c_q.stream[1].w);
      sum_hw += h * w;                               // the normaliser
      sum_hwc[0] += h * w[0] * c_q.stream[0].rgb;    // the weighted colours
      sum_hwc[1] += h * w[1] * c_q.stream[1].rgb;
      sum_h2w2_var += h * h * w * w * var_q;         // the weighted variances, weights squared
    }

  // c_{i+1}(p) = sum h w c_i(q) / sum h w [SVGF17 Eq. 1].
  const vec3 c_next_direct = sum_hwc[0] / sum_hw[0];
  const vec3 c_next_indirect = sum_hwc[1] / sum_hw[1];
  // Var(c_{i+1}(p)) = sum h^2 w^2 Var(c_i(q)) / (sum h w)^2 [SVGF17 Sec. 4.3].
  precise vec2 var_next = sum_h2w2_var / (sum_hw * sum_hw);
  illumination_out(i, Illumination(vec4[2](vec4(c_next_direct, var_next[0]), vec4(c_next_indirect, var_next[1]))));
}
