// Variance estimation [SVGF17 Sec. 4.2], the Vulkan port of variance_pixel (variance.cpp), function for function:
// sigma'^2 = mu2' - mu1'^2 where n >= variance_min_history, else the same formula on moments averaged over a
// 7x7 neighbourhood with bilateral weights w = w_z w_n [SVGF17 Eq. 3, 4] (edge_stopping.cpp). One invocation
// per pixel for both streams, direct and indirect: the bilateral weights depend on the G-buffer alone, so they
// are computed once for both.
//   in:  bindings 0: illumination C' (temporal output) of both streams, 1-2: moments (mu1', mu2', n) of the direct
//        and the indirect stream; 3-4: surface, depth gradient;
//   out: binding 5: illumination (C', sigma'^2) of both streams. Layout: planes_shared.h, variance_shared.h.
#version 450
#extension GL_GOOGLE_include_directive : require

#include "filters/svgf/edge_stopping.glsl"
#include "filters/svgf/variance_shared.h"

// The workgroup's shape, per device (planes_shared.h).
layout(local_size_x_id = kSvgfGroupSizeXConstant, local_size_y_id = kSvgfGroupSizeYConstant,
       local_size_x = kSvgfGroupSizeX, local_size_y = kSvgfGroupSizeY) in;

RTDR_INPUT_ILLUMINATION(0, illumination_in)
RTDR_INPUT_RGBA(1, moments_direct)
RTDR_INPUT_RGBA(2, moments_indirect)
RTDR_INPUT_RGBA(3, surface)
RTDR_INPUT_RG(4, depth_grad)
RTDR_OUTPUT_ILLUMINATION(5, illumination_out)

layout(push_constant) uniform Push { VariancePush push; };

// GPU only: the push constants, copied once at the top of main(). lavapipe loads a push constant lane by lane at
// each use; the copy is loaded once.
VariancePush frame;

// The planes' accessors (Plane::at, inside): element y * width + x.
int index_of(int x, int y) { return y * int(frame.width) + x; }
bool inside(int x, int y) { return x >= 0 && y >= 0 && x < int(frame.width) && y < int(frame.height); }

// --- variance.cpp ---

// sigma'^2 = mu2' - mu1'^2 [SVGF17 Sec. 4.2], clamped at 0: a variance is never negative, but the difference
// of two rounded moments can be (by a few ulps where the variance is 0).
float variance_from_moments(float mu1, float mu2) {
  // GPU only: `precise`, so mu2 - mu1 * mu1 is not fused into one fma and rounds twice, as in C++.
  precise float sigma2 = max(0.0, mu2 - mu1 * mu1);
  return sigma2;
}

// The moments of both streams: (mu1' direct, mu2' direct, mu1' indirect, mu2' indirect).
vec4 moments_at(int i) { return vec4(moments_direct(i).xy, moments_indirect(i).xy); }

// sigma'^2 of both streams from the 7x7 bilateral average of their moments.
vec2 variance_spatial_pixel(int x, int y, vec4 s_p) {
  const float z_p = s_p.w;
  const vec2 grad_z_p = depth_grad(index_of(x, y)).xy;
  const vec3 n_p = s_p.xyz;
  precise float sum_w = 0.0;
  precise vec4 mu = vec4(0.0);  // sum w mu1', sum w mu2' of the direct stream, then of the indirect
  for (int dy = -kVarianceSpatialRadius; dy <= kVarianceSpatialRadius; ++dy)
    for (int dx = -kVarianceSpatialRadius; dx <= kVarianceSpatialRadius; ++dx) {
      const int qx = x + dx, qy = y + dy;
      // Taps outside the image or on no surface hold no moments.
      if (!inside(qx, qy)) continue;
      const int q = index_of(qx, qy);
      const vec4 s_q = surface(q);
      if (!has_surface(s_q)) continue;
      // w_z with p - q = (-dx, -dy) [SVGF17 Eq. 3], w_n [SVGF17 Eq. 4]: "weights driven by depths and
      // world-space normals" [SVGF17 Sec. 4.2].
      const float w_z = weight_depth(z_p, s_q.w, grad_z_p, vec2(-dx, -dy), frame.sigma_z, frame.epsilon);
      const float w_n = weight_normal(n_p, s_q.xyz, frame.sigma_n);
      precise float w = w_z * w_n;
      // GPU only: the sums are `precise` (declared above), so w * mu' + sum is not fused into one fma.
      sum_w += w;
      mu += w * moments_at(q);
    }
  // The centre tap has w = 1 (w_z = exp(-0 / epsilon), epsilon > 0 by the table's range), so sum w >= 1
  // unless p's normal is degenerate (zero length: every w_n = 0) or NaN; then the pixel's own moments remain.
  if (!(sum_w > 0.0)) {
    const vec4 own = moments_at(index_of(x, y));
    return vec2(variance_from_moments(own.x, own.y), variance_from_moments(own.z, own.w));
  }
  // The weighted means of the moments: sum w mu'(q) / sum w.
  mu /= sum_w;
  return vec2(variance_from_moments(mu.x, mu.y), variance_from_moments(mu.z, mu.w));
}

// sigma'^2 of both streams at (x, y).
vec2 variance_pixel(int x, int y, vec4 s_p) {
  if (!has_surface(s_p)) return vec2(0.0);  // no surface, no variance
  const int i = index_of(x, y);
  const vec4 m_direct = moments_direct(i), m_indirect = moments_indirect(i);
  // "Where our temporal history is limited (<4 frames after a disocclusion), we instead estimate the variance
  // spatially" [SVGF17 Sec. 4.2]; 4 is variance_min_history. Each stream has its own history length n.
  const bvec2 temporal = bvec2(m_direct.z >= float(frame.variance_min_history),
                               m_indirect.z >= float(frame.variance_min_history));
  const vec2 from_history = vec2(variance_from_moments(m_direct.x, m_direct.y),
                                 variance_from_moments(m_indirect.x, m_indirect.y));
  if (all(temporal)) return from_history;
  const vec2 spatial = variance_spatial_pixel(x, y, s_p);
  return vec2(temporal.x ? from_history.x : spatial.x, temporal.y ? from_history.y : spatial.y);
}

void main() {
  frame = push;  // the push constants, read once (see above)
  // This invocation's pixel; the last tiles overhang the frame.
  const ivec2 pixel = ivec2(gl_GlobalInvocationID.xy);
  if (pixel.x >= int(frame.width) || pixel.y >= int(frame.height)) return;
  const int i = index_of(pixel.x, pixel.y);
  const vec2 sigma2 = variance_pixel(pixel.x, pixel.y, surface(i));
  const Illumination c = illumination_in(i);
  illumination_out(i, Illumination(vec4[2](vec4(c.stream[0].rgb, sigma2.x), vec4(c.stream[1].rgb, sigma2.y))));
}
