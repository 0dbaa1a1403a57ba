// Variance estimation [SVGF17 Sec. 4.2], the Vulkan port of variance_pixel (variance.cpp), function for function:
// sigma'^2 = mu2' - mu1'^2 where n >= variance_min_history, else the same formula on moments averaged over a
// 7x7 neighbourhood with bilateral weights w = w_z w_n [SVGF17 Eq. 3, 4] (edge_stopping.cpp). One invocation
// per pixel.
//   in:  bindings 0-2: moment1, moment2, length (TemporalOutput); 3-6: depth, depth_grad, normal, mesh
//        (SurfacePlanes); out: binding 7: sigma2. Layout: variance_shared.h.
#version 450
#extension GL_GOOGLE_include_directive : require

#include "filters/svgf/variance_shared.h"

layout(local_size_x = kVarianceGroupSizeX, local_size_y = kVarianceGroupSizeY) in;

layout(std430, set = 0, binding = 0) readonly buffer Moment1 { float moment1[]; };
layout(std430, set = 0, binding = 1) readonly buffer Moment2 { float moment2[]; };
layout(std430, set = 0, binding = 2) readonly buffer Length { float history_length[]; };
layout(std430, set = 0, binding = 3) readonly buffer Depth { float depth[]; };
layout(std430, set = 0, binding = 4) readonly buffer DepthGrad { float depth_grad_xy[]; };
layout(std430, set = 0, binding = 5) readonly buffer Normal { float normal_xyz[]; };
layout(std430, set = 0, binding = 6) readonly buffer Mesh { uint mesh[]; };
layout(std430, set = 0, binding = 7) writeonly buffer Sigma2 { float sigma2[]; };

layout(push_constant) uniform Push { VariancePush frame; };

// The planes' accessors (Plane::at, inside, SurfacePlanes::covered): element y * width + x.
uint index_of(int x, int y) { return uint(y) * frame.width + uint(x); }
bool inside(int x, int y) { return x >= 0 && y >= 0 && x < int(frame.width) && y < int(frame.height); }
bool covered(int x, int y) { return mesh[index_of(x, y)] != kVarianceInvalidId; }
vec2 depth_grad_at(int x, int y) {
  const uint i = 2u * index_of(x, y);
  return vec2(depth_grad_xy[i], depth_grad_xy[i + 1u]);
}
vec3 normal_at(int x, int y) {
  const uint i = 3u * index_of(x, y);
  return vec3(normal_xyz[i], normal_xyz[i + 1u], normal_xyz[i + 2u]);
}

// --- edge_stopping.h / edge_stopping.cpp ---

// a_z = |z(p) - z(q)| / (sigma_z |grad z(p) . (p - q)| + epsilon) [SVGF17 Eq. 3].
float depth_exponent(float z_p, float z_q, vec2 grad_z_p, vec2 offset_pq, float sigma_z, float epsilon) {
  // The depth change the local plane predicts over p - q, scaled by sigma_z [SVGF17 Eq. 3, denominator].
  // GPU only: the dot product written out and `precise`, so no fma changes the rounding of glm::dot's
  // multiply, multiply, add, nor of the multiply-add with sigma_z and epsilon.
  precise float dot_pq = grad_z_p.x * offset_pq.x + grad_z_p.y * offset_pq.y;
  precise float predicted = sigma_z * abs(dot_pq) + epsilon;
  // At q = p: 0 / epsilon = 0, so w_z = exp(-0) = 1 exactly (epsilon > 0 keeps 0 / 0 away).
  return abs(z_p - z_q) / predicted;
}

float weight_depth(float z_p, float z_q, vec2 grad_z_p, vec2 offset_pq, float sigma_z, float epsilon) {
  // w_z = exp(-|z(p) - z(q)| / (sigma_z |grad z(p) . (p - q)| + epsilon)) [SVGF17 Eq. 3].
  return exp(-depth_exponent(z_p, z_q, grad_z_p, offset_pq, sigma_z, epsilon));
}

float weight_normal(vec3 n_p, vec3 n_q, float sigma_n) {
  // w_n = max(0, n(p) . n(q))^sigma_n [SVGF17 Eq. 4]: a cosine lobe; back-facing pairs get 0.
  // GPU only: the dot product written out and `precise`, in glm::dot's order ((x x + y y) + z z).
  precise float cosine = n_p.x * n_q.x + n_p.y * n_q.y + n_p.z * n_q.z;
  return pow(max(0.0, cosine), sigma_n);
}

// --- variance.cpp ---

// sigma'^2 = mu2' - mu1'^2 [SVGF17 Sec. 4.2], clamped at 0: a variance is never negative, but the difference
// of two rounded moments can be (by a few ulps where the variance is 0).
float variance_from_moments(float mu1, float mu2) {
  // GPU only: `precise`, so mu2 - mu1 * mu1 is not fused into one fma and rounds twice, as in C++.
  precise float sigma2 = max(0.0, mu2 - mu1 * mu1);
  return sigma2;
}

float variance_spatial_pixel(int x, int y) {
  const float z_p = depth[index_of(x, y)];
  const vec2 grad_z_p = depth_grad_at(x, y);
  const vec3 n_p = normal_at(x, y);
  precise float sum_w = 0.0, mu1 = 0.0, mu2 = 0.0;
  for (int dy = -kVarianceSpatialRadius; dy <= kVarianceSpatialRadius; ++dy)
    for (int dx = -kVarianceSpatialRadius; dx <= kVarianceSpatialRadius; ++dx) {
      const int qx = x + dx, qy = y + dy;
      // Taps outside the image or on no surface hold no moments.
      if (!inside(qx, qy) || !covered(qx, qy)) continue;
      const uint q = index_of(qx, qy);
      // w_z with p - q = (-dx, -dy) [SVGF17 Eq. 3], w_n [SVGF17 Eq. 4]: "weights driven by depths and
      // world-space normals" [SVGF17 Sec. 4.2].
      const float w_z = weight_depth(z_p, depth[q], grad_z_p, vec2(-dx, -dy), frame.sigma_z, frame.epsilon);
      const float w_n = weight_normal(n_p, normal_at(qx, qy), frame.sigma_n);
      precise float w = w_z * w_n;
      // GPU only: the sums are `precise` (declared above), so w * mu' + sum is not fused into one fma.
      sum_w += w;
      mu1 += w * moment1[q];
      mu2 += w * moment2[q];
    }
  // The centre tap has w = 1 (w_z = exp(-0 / epsilon), epsilon > 0 by the table's range), so sum w >= 1
  // unless p's normal is degenerate (zero length: every w_n = 0) or NaN; then the pixel's own moments remain.
  if (!(sum_w > 0.0)) return variance_from_moments(moment1[index_of(x, y)], moment2[index_of(x, y)]);
  // The weighted means of the moments: sum w mu'(q) / sum w.
  mu1 /= sum_w;
  mu2 /= sum_w;
  return variance_from_moments(mu1, mu2);
}

float variance_pixel(int x, int y) {
  const bool is_covered = covered(x, y);
  if (!is_covered) return 0.0;  // no surface, no variance
  const float n = history_length[index_of(x, y)];
  // "Where our temporal history is limited (<4 frames after a disocclusion), we instead estimate the variance
  // spatially" [SVGF17 Sec. 4.2]; 4 is variance_min_history.
  const bool temporal = n >= float(frame.variance_min_history);
  if (!temporal) return variance_spatial_pixel(x, y);
  return variance_from_moments(moment1[index_of(x, y)], moment2[index_of(x, y)]);
}

void main() {
  // This invocation's pixel; the last tiles overhang the frame.
  const uvec2 pixel = gl_GlobalInvocationID.xy;
  if (pixel.x >= frame.width || pixel.y >= frame.height) return;
  sigma2[index_of(int(pixel.x), int(pixel.y))] = variance_pixel(int(pixel.x), int(pixel.y));
}
