// One iteration k of A-SVGF's reconstruction of the gradient on the stratum grid [ASVGF18 Sec. 3.4, Eq. 7-12], the
// Vulkan port of gradient_atrous_pixel (filters/asvgf/gradient_atrous.cpp) with the variance prefilter of
// prefilter_variance_pixel (filters/svgf/prefilter.cpp), line for line:
//   g3x3(Var(l^(k)))(p) = sum g(dx) g(dy) Var(l^(k))(p + (dx, dy)), clamped borders   [ASVGF18 Eq. 11]
//   w^(k)(p, q)         = w_z w_n w_l^(k)                                             [ASVGF18 Eq. 8]
//     w_n [ASVGF18 Eq. 9], w_z [ASVGF18 Eq. 10], w_l [ASVGF18 Eq. 11]: SVGF's (filters/svgf/edge_stopping.glsl)
//   l^(k+1)(p)          = sum h w l^(k)(q) / sum h w                                  [ASVGF18 Eq. 7]
//   delta^, Delta^ the same, with the luminance's weights                             [ASVGF18 Eq. 12]
//   Var(l^(k+1)(p))     = sum h^2 w^2 Var(l^(k)(q)) / (sum h w)^2                     [SVGF17 Sec. 4.3]
// with h the 3x3 box and taps 2^k strata apart. The golden pass's choices (filters/asvgf/gradient_atrous.h): taps
// outside the grid or without a surface are skipped, a stratum without a surface passes through, the centre tap
// has w = 1, p - q is converted to pixels (s 2^k per step) for w_z.
// What differs from the golden pass (GPU only below):
// - g3x3(Var) is computed per stratum here, where the golden gradient_atrous_level prefilters the whole grid first:
//   the same sum in the same order.
// - GLSL's exp and pow, which the weights call, may differ from libm's by a few ulp: the port's error bound covers
//   it (tests/gpu_gradient_atrous_test.cpp). Every other result is `precise` (no fma contraction, no reordering)
//   and rounds as the C++ does.
//   in:  bindings 0 (delta^, Delta^, l^(k), Var(l^(k))), 1 (n, z), 2 depth gradient, 3 id.mesh per stratum;
//   out: 4 (delta^, Delta^, l^(k+1), Var(l^(k+1))). Layout: filters/asvgf/gradient_atrous_shared.h.
#version 450
#extension GL_GOOGLE_include_directive : require
#extension GL_EXT_control_flow_attributes : require

#include "filters/asvgf/gradient_atrous_shared.h"
#include "filters/svgf/edge_stopping.glsl"

// The workgroup's shape, per device: the SVGF ports' (planes_shared.h).
layout(local_size_x_id = kSvgfGroupSizeXConstant, local_size_y_id = kSvgfGroupSizeYConstant,
       local_size_x = kSvgfGroupSizeX, local_size_y = kSvgfGroupSizeY) in;

RTDR_INPUT_RGBA(0, values_in)
RTDR_INPUT_RGBA(1, surface)
RTDR_INPUT_RG(2, depth_grad)
RTDR_INPUT_UINT(3, mesh)
layout(std430, set = 0, binding = 4) writeonly buffer OutValues { vec4 values_out[]; };

layout(push_constant) uniform Push { GradientAtrousPush push; };

// GPU only: the push constants, copied once at the top of main(). lavapipe loads a push constant lane by lane at
// each use; the copy is loaded once.
GradientAtrousPush frame;

// The grid's planes (Plane::at, inside, at_clamped) and SurfacePlanes::covered.
int index_of(int x, int y) { return y * int(frame.grid_width) + x; }
bool inside(int x, int y) { return x >= 0 && y >= 0 && x < int(frame.grid_width) && y < int(frame.grid_height); }
bool covered(int x, int y) { return mesh(index_of(x, y)).x != RTDR_INVALID_ID; }

// --- prefilter.cpp ---

// The 1D binomial weights (1/4, 1/2, 1/4) (prefilter.h's kGaussian3).
const float kGaussian3[3] = float[3](kPrefilterEdge, kPrefilterCentre, kPrefilterEdge);

// g3x3(Var(l^(k)))(p) [ASVGF18 Eq. 11]: the 3x3 binomial blur of the variance, border strata repeated.
float prefilter_variance_pixel(int x, int y) {
  precise float sum = 0.0f;
  [[unroll]] for (int dy = -1; dy <= 1; ++dy)
    [[unroll]] for (int dx = -1; dx <= 1; ++dx) {
      // The binomial weight of this tap, g(dx) g(dy): 1/4 at the centre, 1/8 at the edges, 1/16 at the corners.
      const float g = kGaussian3[dx + 1] * kGaussian3[dy + 1];
      // The neighbour's variance, the border stratum where (x + dx, y + dy) falls outside.
      const int qx = clamp(x + dx, 0, int(frame.grid_width) - 1), qy = clamp(y + dy, 0, int(frame.grid_height) - 1);
      sum += g * values_in(index_of(qx, qy)).w;
    }
  return sum;
}

// --- gradient_atrous.cpp ---

// The golden per-stratum function, gradient_atrous_pixel: iteration k at stratum (sx, sy); (delta^, Delta^, l^,
// Var(l^)) in x, y, z, w (GradientPixel).
vec4 gradient_atrous_pixel(int sx, int sy) {
  const vec4 centre_values = values_in(index_of(sx, sy));
  // No surface in the stratum: passed through.
  if (!covered(sx, sy)) return centre_values;
  const int step = 1 << frame.level;  // 2^k strata between taps
  const int i = index_of(sx, sy);
  const vec4 s_p = surface(i);
  const float z_p = s_p.w, l_p = centre_values.z, var_p = prefilter_variance_pixel(sx, sy);
  const vec2 grad_z_p = depth_grad(i).xy;
  const vec3 n_p = s_p.xyz;

  precise float sum_hw = 0.0f, sum_h2w2_var = 0.0f;
  precise vec3 sum = vec3(0.0f);  // the weighted sums of delta, Delta and l^
  [[unroll]] for (int j = -1; j <= 1; ++j)
    [[unroll]] for (int k = -1; k <= 1; ++k) {
      const int qx = sx + k * step, qy = sy + j * step;
      if (!inside(qx, qy)) continue;   // skipped: outside the grid
      if (!covered(qx, qy)) continue;  // skipped: no surface in the stratum
      const int q = index_of(qx, qy);
      const vec4 v_q = values_in(q);
      precise float h = kAtrousBox * kAtrousBox;  // the 3x3 box h [ASVGF18 Sec. 3.4]: h(k) h(j)
      precise float w = 1.0f;  // the centre tap: every edge-stopping weight is 1 there
      if (k != 0 || j != 0) {
        const vec4 s_q = surface(q);
        // p - q in pixels: the depth gradient is per pixel, a stratum step is s pixels.
        precise vec2 offset_pq = float(frame.stratum_size) * vec2(float(sx - qx), float(sy - qy));
        const float w_z = weight_depth(z_p, s_q.w, grad_z_p, offset_pq, frame.sigma_z, frame.epsilon);  // Eq. 10
        const float w_n = weight_normal(n_p, s_q.xyz, frame.sigma_n);                                   // Eq. 9
        const float w_l = weight_luminance(l_p, v_q.z, var_p, frame.sigma_l, frame.epsilon);            // Eq. 11
        // w^(k)(p, q) = w_z w_n w_l^(k) [ASVGF18 Eq. 8].
        w = w_z * w_n * w_l;
      }
      sum_hw += h * w;
      sum.z += h * w * v_q.z;
      sum.x += h * w * v_q.x;  // with the luminance's weights [ASVGF18 Eq. 12]
      sum.y += h * w * v_q.y;
      sum_h2w2_var += h * h * w * w * v_q.w;
    }
  // l^(k+1)(p) = sum h w l^(k)(q) / sum h w [ASVGF18 Eq. 7]; delta^, Delta^ alike [ASVGF18 Eq. 12].
  precise vec4 result;  // C++: out (a GLSL keyword)
  result.z = sum.z / sum_hw;
  result.x = sum.x / sum_hw;
  result.y = sum.y / sum_hw;
  // Var(l^(k+1)) = sum h^2 w^2 Var(l^(k)) / (sum h w)^2 [SVGF17 Sec. 4.3].
  result.w = sum_h2w2_var / (sum_hw * sum_hw);
  return result;
}

// gradient_atrous_level: gradient_atrous_pixel at every stratum.
void main() {
  frame = push;  // the push constants, read once (see above)
  // This invocation's stratum; the last tiles overhang the grid.
  const ivec2 p = ivec2(gl_GlobalInvocationID.xy);
  if (p.x >= int(frame.grid_width) || p.y >= int(frame.grid_height)) return;
  values_out[index_of(p.x, p.y)] = gradient_atrous_pixel(p.x, p.y);
}
