// TRMV's clean-up weights [TRMV21 Eq. 7, Eq. 8] and std [TRMV21 Sec. 5], the Vulkan port of
// trmv_cleanup_weights_pixel (filters/trmv/cleanup.cpp), function for function:
//   w_A = (alpha^V - alpha)^2                                   [TRMV21 Eq. 7]
//   w_C = Y(|cbar*_{i-1} - cbar_{i-1}|) / (Y(cbar_{i-1}) + eps)  [TRMV21 Eq. 8], on luminance (cleanup.h)
//   std = min(w_A + w_C, sigma_max)                             [TRMV21 Sec. 5]
// The 9x9 separable bilateral with this std that follows in trmv_cleanup_pass is filters/trmv/spatial.comp,
// dispatched twice with the std plane; this pass writes its input, (cbar_i, std). One invocation per pixel.
//   in:  bindings 0 cbar_i, 1 (cbar_{i-1}, alpha^V), 2 cbar*_{i-1}; out: 3 (cbar_i, std), 4 (w_A, w_C, std, 0).
//   Layout: filters/svgf/planes_shared.h and filters/trmv/cleanup_shared.h.
// GPU only: every arithmetic result is `precise`, so no fma contraction or reordering changes the rounding; the
// C++ rounds after each operation in the same order (tests/gpu_trmv_cleanup_test.cpp derives the bound).
#version 450
#extension GL_GOOGLE_include_directive : require

#include "core/color.glsl"
#include "filters/trmv/cleanup_shared.h"

// The workgroup's shape, per device: the SVGF ports' (planes_shared.h).
layout(local_size_x_id = kSvgfGroupSizeXConstant, local_size_y_id = kSvgfGroupSizeYConstant,
       local_size_x = kSvgfGroupSizeX, local_size_y = kSvgfGroupSizeY) in;

RTDR_INPUT_RGBA(0, color)
RTDR_INPUT_RGBA(1, fetched_alpha_v)
RTDR_INPUT_RGBA(2, clamped)
layout(std430, set = 0, binding = 3) writeonly buffer OutColorSigma { vec4 out_color_sigma[]; };
layout(std430, set = 0, binding = 4) writeonly buffer OutWeights { vec4 out_weights[]; };

layout(push_constant) uniform Push { TrmvCleanupPush push; };

// GPU only: the push constants, copied once at the top of main(). lavapipe loads a push constant lane by lane at
// each use; the copy is loaded once.
TrmvCleanupPush frame;

// w_A = (alpha^V - alpha)^2 [TRMV21 Eq. 7] (trmv_weight_alpha).
float trmv_weight_alpha(float alpha_v, float alpha) {
  precise float w_a = (alpha_v - alpha) * (alpha_v - alpha);
  return w_a;
}

// w_C = Y(|cbar* - cbar|) / (Y(cbar) + epsilon) [TRMV21 Eq. 8], on luminance (trmv_weight_clamp).
float trmv_weight_clamp(vec3 clamped_history, vec3 fetched, float epsilon) {
  precise vec3 difference = clamped_history - fetched;
  precise float w_c = luminance(abs(difference)) / (luminance(fetched) + epsilon);
  return w_c;
}

// The clean-up's std, min{w_A + w_C, 5} [TRMV21 Sec. 5] (trmv_cleanup_sigma). std::min(a, b) is b < a ? b : a.
float trmv_cleanup_sigma(float w_a, float w_c, float sigma_max) {
  precise float sum = w_a + w_c;
  return sigma_max < sum ? sigma_max : sum;
}

// The golden per-pixel function, trmv_cleanup_weights_pixel: (w_A, w_C, std).
vec3 trmv_cleanup_weights_pixel(int i) {
  const vec4 f = fetched_alpha_v(i);
  const float a_v = frame.has_alpha_v == 0u ? frame.alpha : f.w;  // alpha^V [TRMV21 Eq. 4], alpha without it
  const float w_a = trmv_weight_alpha(a_v, frame.alpha);
  const float w_c = trmv_weight_clamp(clamped(i).rgb, f.rgb, frame.cleanup_eps);
  return vec3(w_a, w_c, trmv_cleanup_sigma(w_a, w_c, frame.cleanup_sigma_max));
}

// trmv_cleanup_pass's first loop: the weights at every pixel.
void main() {
  frame = push;  // the push constants, read once (see above)
  // This invocation's pixel; the last tiles overhang the frame.
  const ivec2 pixel = ivec2(gl_GlobalInvocationID.xy);
  if (pixel.x >= int(frame.width) || pixel.y >= int(frame.height)) return;
  const int i = pixel.y * int(frame.width) + pixel.x;
  const vec3 p = trmv_cleanup_weights_pixel(i);
  out_weights[i] = vec4(p, 0.0f);
  // GPU only: (cbar_i, std), the record spatial.comp filters with the std plane (spatial_shared.h).
  out_color_sigma[i] = vec4(color(i).rgb, p.z);
}
