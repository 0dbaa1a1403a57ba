// GLSL mirror of edge_stopping.h / edge_stopping.cpp, for the Vulkan ports (#include
// "filters/svgf/edge_stopping.glsl"): SVGF's edge-stopping weights [SVGF17 Sec. 4.4, Eq. 3-5], function for
// function, in the golden code's order of operations. variance.comp calls weight_depth and weight_normal;
// atrous.comp calls depth_exponent and luminance_scale for its fused form of w_z w_n w_l (GPU-only, below).
#ifndef RTDR_FILTERS_SVGF_EDGE_STOPPING_GLSL
#define RTDR_FILTERS_SVGF_EDGE_STOPPING_GLSL

// glm::dot in glm's order: a.x b.x + a.y b.y, and (a.x b.x + a.y b.y) + a.z b.z. GPU only: GLSL's dot() may
// fuse or reorder.
float dot2(vec2 a, vec2 b) {
  precise float d = a.x * b.x + a.y * b.y;
  return d;
}
float dot3(vec3 a, vec3 b) {
  precise float d = a.x * b.x + a.y * b.y + a.z * b.z;
  return d;
}

// a_z = |z(p) - z(q)| / (sigma_z |grad z(p) . (p - q)| + epsilon), the exponent of w_z = exp(-a_z)
// [SVGF17 Eq. 3]. GPU only: the golden weight_depth computes it inline; the shaders need it apart for the
// fused weight.
float depth_exponent(float z_p, float z_q, vec2 grad_z_p, vec2 offset_pq, float sigma_z, float epsilon) {
  // The depth change the local plane predicts over p - q, scaled by sigma_z [SVGF17 Eq. 3, denominator].
  precise float predicted = sigma_z * abs(dot2(grad_z_p, offset_pq)) + epsilon;
  // At q = p: 0 / epsilon = 0, so w_z = exp(-0) = 1 exactly (epsilon > 0 keeps 0 / 0 away).
  return abs(z_p - z_q) / predicted;
}

// Depth weight w_z = exp(-a_z) [SVGF17 Eq. 3] (edge_stopping.cpp's weight_depth).
float weight_depth(float z_p, float z_q, vec2 grad_z_p, vec2 offset_pq, float sigma_z, float epsilon) {
  return exp(-depth_exponent(z_p, z_q, grad_z_p, offset_pq, sigma_z, epsilon));
}

// Normal weight w_n = max(0, n(p) . n(q))^sigma_n [SVGF17 Eq. 4]: a cosine lobe; back-facing pairs get 0.
float weight_normal(vec3 n_p, vec3 n_q, float sigma_n) { return pow(max(0.0f, dot3(n_p, n_q)), sigma_n); }

// Eq. 5's denominator, sigma_l sqrt(g3x3(Var(l(p)))) + epsilon (edge_stopping.cpp's luminance_scale).
float luminance_scale(float variance_prefiltered_p, float sigma_l, float epsilon) {
  precise float scale = sigma_l * sqrt(max(0.0f, variance_prefiltered_p)) + epsilon;
  return scale;
}

// Luminance weight w_l = exp(-|l(p) - l(q)| / luminance_scale) [SVGF17 Eq. 5] (edge_stopping.cpp's
// weight_luminance).
float weight_luminance(float l_p, float l_q, float variance_prefiltered_p, float sigma_l, float epsilon) {
  return exp(-abs(l_p - l_q) / luminance_scale(variance_prefiltered_p, sigma_l, epsilon));
}

#endif  // RTDR_FILTERS_SVGF_EDGE_STOPPING_GLSL
