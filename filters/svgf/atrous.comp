// One level of SVGF's edge-avoiding a-trous wavelet filter [SVGF17 Sec. 4.3, Eq. 1-5], the Vulkan port of
// atrous_pixel (atrous.cpp), line for line (read_centre, tap_weight and centre_weight likewise):
//   c_{i+1}(p)      = sum h w c_i(q) / sum h w
//   Var(c_{i+1}(p)) = sum h^2 w^2 Var(c_i(q)) / (sum h w)^2
// Same skip rules: taps outside the image and taps without a surface are skipped, a pixel without a surface
// passes through, the centre tap gets w = 1. One invocation per pixel, a plain gather (no shared memory).
//   in:  bindings 0-6: colour, variance, g3x3(variance) (prefilter.comp), depth, depth gradient, normal, mesh id;
//   out: bindings 7-8: colour, variance. Layout and accuracy: atrous_shared.h.
#version 450
#extension GL_GOOGLE_include_directive : require

#include "filters/svgf/atrous_shared.h"

layout(local_size_x = kAtrousGroupSizeX, local_size_y = kAtrousGroupSizeY) in;

layout(std430, set = 0, binding = 0) readonly buffer Colour { float colour_rgb[]; };
layout(std430, set = 0, binding = 1) readonly buffer Variance { float variance[]; };
layout(std430, set = 0, binding = 2) readonly buffer Prefiltered { float prefiltered_variance[]; };
layout(std430, set = 0, binding = 3) readonly buffer Depth { float depth[]; };
layout(std430, set = 0, binding = 4) readonly buffer DepthGrad { float depth_grad_xy[]; };
layout(std430, set = 0, binding = 5) readonly buffer Normal { float normal_xyz[]; };
layout(std430, set = 0, binding = 6) readonly buffer Mesh { uint mesh[]; };
layout(std430, set = 0, binding = 7) writeonly buffer ColourOut { float colour_out_rgb[]; };
layout(std430, set = 0, binding = 8) writeonly buffer VarianceOut { float variance_out[]; };

layout(push_constant) uniform Push { AtrousPush p; };

// Plane accessors (filters/image.h's at, inside; SurfacePlanes::covered), pixel (x, y) at y * width + x.
uint index_of(int x, int y) { return uint(y) * p.width + uint(x); }
bool inside(int x, int y) { return x >= 0 && y >= 0 && x < int(p.width) && y < int(p.height); }
bool covered(int x, int y) { return mesh[index_of(x, y)] != kAtrousInvalidId; }
vec3 color_at(int x, int y) {
  const uint i = 3u * index_of(x, y);
  return vec3(colour_rgb[i], colour_rgb[i + 1u], colour_rgb[i + 2u]);
}
vec3 normal_at(int x, int y) {
  const uint i = 3u * index_of(x, y);
  return vec3(normal_xyz[i], normal_xyz[i + 1u], normal_xyz[i + 2u]);
}
vec2 depth_grad_at(int x, int y) {
  const uint i = 2u * index_of(x, y);
  return vec2(depth_grad_xy[i], depth_grad_xy[i + 1u]);
}

// core/color.h's luminance, in its order of operations.
float luminance(vec3 rgb) {
  precise float l = RTDR_LUMINANCE_R * rgb.r + RTDR_LUMINANCE_G * rgb.g + RTDR_LUMINANCE_B * rgb.b;
  return l;
}

// glm::dot in glm's order: (a.x b.x + a.y b.y) + a.z b.z, and a.x b.x + a.y b.y. GPU only: GLSL's dot() may
// fuse or reorder.
float dot3(vec3 a, vec3 b) {
  precise float d = a.x * b.x + a.y * b.y + a.z * b.z;
  return d;
}
float dot2(vec2 a, vec2 b) {
  precise float d = a.x * b.x + a.y * b.y;
  return d;
}

// a_z [SVGF17 Eq. 3] (edge_stopping.h's depth_exponent).
float depth_exponent(float z_p, float z_q, vec2 grad_z_p, vec2 offset_pq, float sigma_z, float epsilon) {
  // The depth change the local plane predicts over p - q, scaled by sigma_z [SVGF17 Eq. 3, denominator].
  precise float predicted = sigma_z * abs(dot2(grad_z_p, offset_pq)) + epsilon;
  // At q = p: 0 / epsilon = 0, so w_z = exp(-0) = 1 exactly (epsilon > 0 keeps 0 / 0 away).
  return abs(z_p - z_q) / predicted;
}

// Eq. 5's denominator, sigma_l sqrt(g3x3(Var(l(p)))) + epsilon (edge_stopping.cpp's luminance_scale).
float luminance_scale(float variance_prefiltered_p, float sigma_l, float epsilon) {
  precise float scale = sigma_l * sqrt(max(0.0f, variance_prefiltered_p)) + epsilon;
  return scale;
}

// What the weights need to know about p, read once per pixel.
struct Centre {
  int x, y;
  float z;            // z(p), linear view depth
  vec2 grad_z;        // grad z(p), per pixel [SVGF17 Eq. 3]
  vec3 n;             // n(p), world space [SVGF17 Eq. 4]
  float l;            // l_i(p), luminance of this level's input [SVGF17 Eq. 5]
  float var_g3x3;     // g3x3(Var(l_i))(p) [SVGF17 Eq. 5]
  float l_scale;      // Eq. 5's denominator, sigma_l sqrt(g3x3(Var)(p)) + epsilon
};

Centre read_centre(int x, int y) {
  const float var_g3x3 = prefiltered_variance[index_of(x, y)];
  return Centre(x, y, depth[index_of(x, y)], depth_grad_at(x, y), normal_at(x, y), luminance(color_at(x, y)),
                var_g3x3, luminance_scale(var_g3x3, p.sigma_l, p.epsilon));
}

// w(p, q) = w_z w_n w_l [SVGF17 Eq. 2] for a tap q != p.
float tap_weight(Centre c, int qx, int qy) {
  // p - q in pixels, at the tap's real distance (the step 2^i included) [SVGF17 Eq. 3].
  const vec2 offset_pq = vec2(float(c.x - qx), float(c.y - qy));
  const float z_q = depth[index_of(qx, qy)];
  const float a_z = depth_exponent(c.z, z_q, c.grad_z, offset_pq, p.sigma_z, p.epsilon);
  const float cos_pq = max(0.0f, dot3(c.n, normal_at(qx, qy)));
  const float l_q = luminance(color_at(qx, qy));
  const float a_l = abs(c.l - l_q) / c.l_scale;
  if (cos_pq <= 0.0f) return 0.0f;  // w_n = 0: facing away
  // w = w_z w_n w_l [SVGF17 Eq. 2] = exp(sigma_n ln cos - a_z - a_l): one exp and one log for the three weights.
  precise float exponent = p.sigma_n * log(cos_pq) - a_z - a_l;
  return exp(exponent);
}

// w(p, p) = 1: Eq. 3-5 at q = p, written down rather than computed (see atrous.cpp's banner).
float centre_weight() { return 1.0f; }

void main() {
  // This invocation's pixel; the last tiles overhang the frame.
  const int x = int(gl_GlobalInvocationID.x), y = int(gl_GlobalInvocationID.y);
  if (x >= int(p.width) || y >= int(p.height)) return;
  const uint i = index_of(x, y);

  // No surface, nothing to compare with: the input passes through.
  if (!covered(x, y)) {
    const vec3 c = color_at(x, y);
    colour_out_rgb[3u * i] = c.r;
    colour_out_rgb[3u * i + 1u] = c.g;
    colour_out_rgb[3u * i + 2u] = c.b;
    variance_out[i] = variance[i];
    return;
  }
  // atrous_kernel (atrous.cpp): the host has checked kernel_size is 5 or 3; the weights are atrous_shared.h's.
  const int radius = p.kernel_size == 5 ? 2 : 1;
  const float h_b3[5] = float[5](kAtrousB3Outer, kAtrousB3Inner, kAtrousB3Centre, kAtrousB3Inner, kAtrousB3Outer);
  const float h_box[5] = float[5](kAtrousBox, kAtrousBox, kAtrousBox, 0.0f, 0.0f);
  const int step = 1 << p.level;  // 2^i: the taps' spacing at level i
  const Centre centre = read_centre(x, y);

  // GPU only: `precise` on the sums keeps each product and add a separate rounding, as in the golden function.
  precise float sum_hw = 0.0f;        // sum h w        [SVGF17 Eq. 1, denominator]
  precise vec3 sum_hwc = vec3(0.0f);  // sum h w c_i(q) [SVGF17 Eq. 1, numerator]
  precise float sum_h2w2_var = 0.0f;  // sum h^2 w^2 Var(c_i(q)) [SVGF17 Sec. 4.3]
  for (int j = -radius; j <= radius; ++j)
    for (int k = -radius; k <= radius; ++k) {
      const int qx = x + k * step, qy = y + j * step;  // the tap q, 2^i (k, j) away from p
      // Off the image: skipped; sum h w renormalises over the taps that remain.
      if (!inside(qx, qy)) continue;
      // No surface at q: nothing to filter there.
      if (!covered(qx, qy)) continue;
      const float hk = p.kernel_size == 5 ? h_b3[k + radius] : h_box[k + radius];
      const float hj = p.kernel_size == 5 ? h_b3[j + radius] : h_box[j + radius];
      precise float h = hk * hj;  // h(q) = h(dx) h(dy)
      // w(p, q) [SVGF17 Eq. 2]; 1 at the centre tap, where every edge-stopping weight is 1.
      const float w = (k == 0 && j == 0) ? centre_weight() : tap_weight(centre, qx, qy);
      const float var_q = variance[index_of(qx, qy)];
      sum_hw += h * w;                                 // the normaliser
      sum_hwc += h * w * color_at(qx, qy);             // the weighted colours
      sum_h2w2_var += h * h * w * w * var_q;           // the weighted variances, weights squared
    }

  // c_{i+1}(p) = sum h w c_i(q) / sum h w [SVGF17 Eq. 1].
  const vec3 c_next = sum_hwc / sum_hw;
  // Var(c_{i+1}(p)) = sum h^2 w^2 Var(c_i(q)) / (sum h w)^2 [SVGF17 Sec. 4.3].
  precise float var_next = sum_h2w2_var / (sum_hw * sum_hw);
  colour_out_rgb[3u * i] = c_next.r;
  colour_out_rgb[3u * i + 1u] = c_next.g;
  colour_out_rgb[3u * i + 2u] = c_next.b;
  variance_out[i] = var_next;
}
