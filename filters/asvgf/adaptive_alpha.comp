// A-SVGF's adaptive temporal weight [ASVGF18 Sec. 3.5, Eq. 14-15], the Vulkan port of adaptive_alpha_pass
// (filters/asvgf/adaptive_alpha.cpp), function for function: per stratum lambda = min(1, k (|delta^| / Delta^)^p),
// 0 where Delta^ <= 0 [ASVGF18 Eq. 14 for p = k = 1]; per pixel its maximum over the (2r+1)^2 strata around the pixel's stratum
// [ASVGF18 Sec. 3.5], strata outside the grid skipped, and alpha_i = (1 - lambda_max) alpha + lambda_max
// [ASVGF18 Eq. 15], and alpha_mu_i the same of alpha_mu: the only place Eq. 15 is computed on the GPU (SVGF's temporal
// port reads both). One invocation per pixel (and per stratum: adaptive_alpha_shared.h).
// The choices the paper leaves open are the golden pass's (filters/asvgf/adaptive_alpha.h).
//   in:  binding 0 (delta^, Delta^, l, Var) per stratum; out: 1 (lambda_max, alpha_i, alpha_mu_i, 0) per pixel,
//   2 lambda per stratum.
//   Layout: filters/asvgf/adaptive_alpha_shared.h.
// GPU only: every arithmetic result is `precise`, so no fma contraction or reordering changes the rounding; the
// C++ rounds after each operation in the same order (tests/gpu_adaptive_alpha_test.cpp derives the bound).
#version 450
#extension GL_GOOGLE_include_directive : require

#include "filters/asvgf/adaptive_alpha.glsl"
#include "filters/asvgf/adaptive_alpha_shared.h"

// The workgroup's shape, per device: the SVGF ports' (planes_shared.h).
layout(local_size_x_id = kSvgfGroupSizeXConstant, local_size_y_id = kSvgfGroupSizeYConstant,
       local_size_x = kSvgfGroupSizeX, local_size_y = kSvgfGroupSizeY) in;

RTDR_INPUT_RGBA(0, gradient)
layout(std430, set = 0, binding = 1) writeonly buffer OutAlpha { vec4 out_alpha[]; };
layout(std430, set = 0, binding = 2) writeonly buffer OutLambda { float out_lambda[]; };

layout(push_constant) uniform Push { AdaptiveAlphaPush push; };

// GPU only: the push constants, copied once at the top of main(). lavapipe loads a push constant lane by lane at
// each use; the copy is loaded once.
AdaptiveAlphaPush frame;

// The stratum planes' accessors (Plane::at, inside).
int grid_index(int x, int y) { return y * int(frame.grid_width) + x; }
bool grid_inside(int x, int y) { return x >= 0 && y >= 0 && x < int(frame.grid_width) && y < int(frame.grid_height); }

// The golden per-pixel function, adaptive_alpha_pixel: (lambda_max, alpha_i, alpha_mu_i, 0) at pixel (x, y).
vec4 adaptive_alpha_pixel(int x, int y) {
  const int s = frame.stratum_size, radius = frame.radius;
  const int sx = x / s, sy = y / s;
  // The maximum over the (2r + 1)^2 strata around (sx, sy) [ASVGF18 Sec. 3.5].
  float lambda_max = 0.0;
  for (int qy = sy - radius; qy <= sy + radius; ++qy)
    for (int qx = sx - radius; qx <= sx + radius; ++qx) {
      if (!grid_inside(qx, qy)) continue;
      const vec4 g = gradient(grid_index(qx, qy));
      const float lambda = gradient_ratio(g.x, g.y, frame.exponent, frame.scale);
      lambda_max = max(lambda_max, lambda);
    }
  // Eq. 15 for the colour and, with the same lambda, for the moments: what the temporal pass reads.
  return vec4(lambda_max, adaptive_alpha(frame.alpha, lambda_max), adaptive_alpha(frame.alpha_moments, lambda_max), 0.0);
}

// adaptive_alpha_pass: lambda at every stratum, adaptive_alpha_pixel at every pixel.
void main() {
  frame = push;  // the push constants, read once (see above)
  // This invocation's pixel, and stratum; the last tiles overhang both.
  const ivec2 p = ivec2(gl_GlobalInvocationID.xy);
  if (grid_inside(p.x, p.y)) {
    const vec4 g = gradient(grid_index(p.x, p.y));
    out_lambda[grid_index(p.x, p.y)] = gradient_ratio(g.x, g.y, frame.exponent, frame.scale);
  }
  if (p.x < int(frame.width) && p.y < int(frame.height))
    out_alpha[p.y * int(frame.width) + p.x] = adaptive_alpha_pixel(p.x, p.y);
}
