// One 1-D pass of TRMV's separable joint bilateral [TRMV21 Sec. 5, "Choice of spatial filters"], the Vulkan port
// of trmv_spatial_pixel and trmv_spatial_axis (filters/trmv/spatial.cpp), function for function: at pixel p the taps
// q = p + k e, k = -r .. r, e the axis,
//   c'(p) = sum_k G(k; 0, sigma) w_z(p, q) w_n(p, q) c(q) / sum_k G(k; 0, sigma) w_z(p, q) w_n(p, q),
// G the spatial Gaussian with peak 1, w_z and w_n SVGF's weights [SVGF17 Eq. 3, Eq. 4] (edge_stopping.glsl). Taps off
// the image or without a surface are skipped, the centre gets weight 1, a pixel without a surface or with std 0
// passes through. The host dispatches it twice, horizontal then vertical (trmv_spatial_pass, 31x31), and TRMV's
// clean-up [TRMV21 Sec. 5, Eq. 7-8] runs it with its per-pixel std, 9x9 (trmv_cleanup_pass; the std from
// filters/trmv/cleanup.comp). RGB only: the method's visibility travels as (V, V, V). One invocation per pixel.
//   in:  bindings 0 (c, std), 1 surface, 2 depth gradient; out: 3 (c', std).
//   Layout: filters/svgf/planes_shared.h and filters/trmv/spatial_shared.h.
// GPU only: every arithmetic result is `precise`, so no fma contraction or reordering changes the rounding; the
// C++ rounds after each operation in the same order. Only exp and pow (G, w_z, w_n) differ from libm's
// (tests/gpu_trmv_spatial_test.cpp derives the bound).
#version 450
#extension GL_GOOGLE_include_directive : require

#include "filters/svgf/edge_stopping.glsl"
#include "filters/trmv/spatial_shared.h"

// The workgroup's shape, per device: the SVGF ports' (planes_shared.h).
layout(local_size_x_id = kSvgfGroupSizeXConstant, local_size_y_id = kSvgfGroupSizeYConstant,
       local_size_x = kSvgfGroupSizeX, local_size_y = kSvgfGroupSizeY) in;

RTDR_INPUT_RGBA(0, color_sigma)
RTDR_INPUT_RGBA(1, surface)
RTDR_INPUT_RG(2, depth_grad)
layout(std430, set = 0, binding = 3) writeonly buffer OutColor { vec4 out_color[]; };

layout(push_constant) uniform Push { TrmvSpatialPush push; };

// GPU only: the push constants, copied once at the top of main(). lavapipe loads a push constant lane by lane at
// each use; the copy is loaded once.
TrmvSpatialPush frame;

// The plane accessors (Plane::at, inside): element y * width + x.
int index_of(int x, int y) { return y * int(frame.width) + x; }
bool inside(int x, int y) { return x >= 0 && y >= 0 && x < int(frame.width) && y < int(frame.height); }

// G(k; 0, sigma) = exp(-k^2 / (2 sigma^2)), peak 1 (trmv_spatial_weight) [TRMV21 Sec. 5: the spatial Gaussian].
float trmv_spatial_weight(float k, float sigma) {
  precise float exponent = -(k * k) / (2.0f * sigma * sigma);
  return exp(exponent);
}

// The golden per-pixel function, trmv_spatial_pixel: one 1-D pass at (x, y) along frame.axis with std sigma.
vec3 trmv_spatial_pixel(ivec2 axis, int radius, float sigma, int x, int y) {
  const int i = index_of(x, y);
  const vec3 c_p = color_sigma(i).rgb;
  const vec4 s_p = surface(i);
  // No surface, nothing to compare with; and std 0 keeps every tap but the centre at weight 0: the identity.
  if (!has_surface(s_p) || !(sigma > 0.0f)) return c_p;
  const float z_p = s_p.w;
  const vec2 grad_z_p = depth_grad(i).xy;
  const vec3 n_p = s_p.xyz;
  precise float sum_w = 1.0f;  // sum of the weights, the centre's 1 included
  precise vec3 sum_wc = c_p;   // sum of the weighted values, the centre's included
  for (int k = -radius; k <= radius; ++k) {
    if (k == 0) continue;  // the centre, weight 1, is in the sums already (spatial.h)
    const ivec2 q = ivec2(x, y) + k * axis;  // the tap, k pixels along the axis
    // Off the image, or no surface there: skipped; the weights that remain renormalise.
    if (!inside(q.x, q.y)) continue;
    const vec4 s_q = surface(index_of(q.x, q.y));
    if (!has_surface(s_q)) continue;
    const vec2 offset_pq = vec2(float(x - q.x), float(y - q.y));  // p - q in pixels [SVGF17 Eq. 3]
    // G(k; 0, sigma) w_z w_n: the spatial Gaussian times SVGF's depth and normal weights [SVGF17 Eq. 3, Eq. 4].
    const float g = trmv_spatial_weight(float(k), sigma);
    const float w_z = weight_depth(z_p, s_q.w, grad_z_p, offset_pq, frame.sigma_z, frame.epsilon);
    const float w_n = weight_normal(n_p, s_q.xyz, frame.sigma_n);
    precise float w = g * w_z * w_n;
    sum_w += w;
    sum_wc += w * color_sigma(index_of(q.x, q.y)).rgb;
  }
  // c'(p) = sum_k G w_z w_n c(q) / sum_k G w_z w_n [TRMV21 Sec. 5: the joint bilateral, one axis].
  precise vec3 filtered = sum_wc / sum_w;
  return filtered;
}

// trmv_spatial_axis: trmv_spatial_pixel at every pixel, with the pixel's std (the plane's, or sigma_all).
void main() {
  frame = push;  // the push constants, read once (see above)
  // This invocation's pixel; the last tiles overhang the frame.
  const ivec2 pixel = ivec2(gl_GlobalInvocationID.xy);
  if (pixel.x >= int(frame.width) || pixel.y >= int(frame.height)) return;
  const int i = index_of(pixel.x, pixel.y);
  const float sigma_in = color_sigma(i).w;
  const float sigma_p = frame.has_sigma_plane != 0u ? sigma_in : frame.sigma;
  const vec3 c = trmv_spatial_pixel(ivec2(frame.axis_x, frame.axis_y), frame.radius, sigma_p, pixel.x, pixel.y);
  // GPU only: the std plane rides in the colour record's w (spatial_shared.h); it travels on, for the next axis.
  out_color[i] = vec4(c, sigma_in);
}
