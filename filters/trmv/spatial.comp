// One 1-D pass of TRMV's separable joint bilateral [TRMV21 Sec. 5, "Choice of spatial filters"], the Vulkan port
// of trmv_spatial_pixel and trmv_spatial_axis (filters/trmv/spatial.cpp), function for function: at pixel p the taps
// q = p + k e, k = -r .. r, e the axis,
//   c'(p) = sum_k G(k; 0, sigma) w_z(p, q) w_n(p, q) c(q) / sum_k G(k; 0, sigma) w_z(p, q) w_n(p, q),
// G the spatial Gaussian with peak 1, w_z and w_n SVGF's weights [SVGF17 Eq. 3, Eq. 4] (edge_stopping.glsl). Taps off
// the image or without a surface are skipped, the centre gets weight 1, a pixel without a surface or with std 0
// passes through. The host dispatches it twice, horizontal then vertical (trmv_spatial_pass, 31x31), and TRMV's
// clean-up [TRMV21 Sec. 5, Eq. 7-8] runs it with its per-pixel std, 9x9 (trmv_cleanup_pass; the std from
// filters/trmv/cleanup.comp). RGB only: the method's visibility travels as (V, V, V). One invocation per pixel, for
// one plane or (GPU only) for up to three side by side: the Vulkan TRMV filters its three components in one
// dispatch per axis, computing each tap's w_z and w_n once for all of them (gpu/trmv_vulkan.h); each plane does the
// same operations in the same order as alone.
//   in:  bindings 0-2 (c, std) of up to three planes, 3 surface, 4 depth gradient, 5 the std per axis (the penumbra
//        filter's (sigma_x, sigma_y), has_sigma_plane = 2); out: 6-8 (c', std).
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

// GPU only: how many planes one dispatch filters side by side, 1 to 3 (a specialization constant,
// spatial_shared.h). TRMV's components share the G-buffer, hence w_z and w_n, so each tap's weights are computed
// once for all of them, as the SVGF ports filter both streams at once.
layout(constant_id = kTrmvSpatialComponentsConstant) const int components = 1;

RTDR_INPUT_RGBA(0, color_sigma_0)
RTDR_INPUT_RGBA(1, color_sigma_1)
RTDR_INPUT_RGBA(2, color_sigma_2)
RTDR_INPUT_RGBA(3, surface)
RTDR_INPUT_RG(4, depth_grad)
RTDR_INPUT_RG(5, axis_sigma)
layout(std430, set = 0, binding = 6) writeonly buffer OutColor0 { vec4 out_color_0[]; };
layout(std430, set = 0, binding = 7) writeonly buffer OutColor1 { vec4 out_color_1[]; };
layout(std430, set = 0, binding = 8) writeonly buffer OutColor2 { vec4 out_color_2[]; };

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

// Plane m's record i (m a constant once `components` is: the selects fold).
vec4 color_sigma(int m, int i) { return m == 0 ? color_sigma_0(i) : m == 1 ? color_sigma_1(i) : color_sigma_2(i); }
void write_color(int m, int i, vec4 record) {
  if (m == 0) out_color_0[i] = record;
  if (m == 1) out_color_1[i] = record;
  if (m == 2) out_color_2[i] = record;
}

// The golden per-pixel function, trmv_spatial_pixel, for each plane m < components: one 1-D pass at (x, y) along
// axis with std sigma[m]. The same operations in the same order per plane as one plane alone.
void trmv_spatial_pixel(ivec2 axis, int radius, float sigma[3], int x, int y, out vec3 result[3]) {
  const int i = index_of(x, y);
  const vec4 s_p = surface(i);
  // No surface, nothing to compare with; and std 0 keeps every tap but the centre at weight 0: the identity.
  bool filters[3];
  precise float sum_w[3];   // sum of the weights, the centre's 1 included
  precise vec3 sum_wc[3];   // sum of the weighted values, the centre's included
  for (int m = 0; m < components; ++m) {
    result[m] = color_sigma(m, i).rgb;
    filters[m] = has_surface(s_p) && sigma[m] > 0.0f;
    sum_w[m] = 1.0f;
    sum_wc[m] = result[m];
  }
  if (!has_surface(s_p)) return;
  const float z_p = s_p.w;
  const vec2 grad_z_p = depth_grad(i).xy;
  const vec3 n_p = s_p.xyz;
  for (int k = -radius; k <= radius; ++k) {
    if (k == 0) continue;  // the centre, weight 1, is in the sums already (spatial.h)
    const ivec2 q = ivec2(x, y) + k * axis;  // the tap, k pixels along the axis
    // Off the image, or no surface there: skipped; the weights that remain renormalise.
    if (!inside(q.x, q.y)) continue;
    const int iq = index_of(q.x, q.y);
    const vec4 s_q = surface(iq);
    if (!has_surface(s_q)) continue;
    const vec2 offset_pq = vec2(float(x - q.x), float(y - q.y));  // p - q in pixels [SVGF17 Eq. 3]
    // G(k; 0, sigma) w_z w_n: the spatial Gaussian times SVGF's depth and normal weights [SVGF17 Eq. 3, Eq. 4].
    const float w_z = weight_depth(z_p, s_q.w, grad_z_p, offset_pq, frame.sigma_z, frame.epsilon);
    const float w_n = weight_normal(n_p, s_q.xyz, frame.sigma_n);
    // GPU only: with one std for every pixel (the spatial filter), every plane's Gaussian is the first's.
    const float g_all = trmv_spatial_weight(float(k), sigma[0]);
    for (int m = 0; m < components; ++m) {
      if (!filters[m]) continue;
      float g = g_all;
      if (frame.has_sigma_plane != 0u) g = trmv_spatial_weight(float(k), sigma[m]);
      precise float w = g * w_z * w_n;
      sum_w[m] += w;
      sum_wc[m] += w * color_sigma(m, iq).rgb;
    }
  }
  // c'(p) = sum_k G w_z w_n c(q) / sum_k G w_z w_n [TRMV21 Sec. 5: the joint bilateral, one axis].
  for (int m = 0; m < components; ++m) {
    precise vec3 filtered = sum_wc[m] / sum_w[m];
    if (filters[m]) result[m] = filtered;
  }
}

// trmv_spatial_axis: trmv_spatial_pixel at every pixel, with the pixel's std (the plane's, or sigma_all).
void main() {
  frame = push;  // the push constants, read once (see above)
  // This invocation's pixel; the last tiles overhang the frame.
  const ivec2 pixel = ivec2(gl_GlobalInvocationID.xy);
  if (pixel.x >= int(frame.width) || pixel.y >= int(frame.height)) return;
  const int i = index_of(pixel.x, pixel.y);
  float sigma_in[3], sigma_p[3];
  // The std per axis (has_sigma_plane 2): x across, y down (trmv_spatial_pass with sigma_x and sigma_y).
  const vec4 axis_std = frame.has_sigma_plane == 2u ? axis_sigma(i) : vec4(0.0);
  for (int m = 0; m < components; ++m) {
    sigma_in[m] = color_sigma(m, i).w;
    sigma_p[m] = frame.has_sigma_plane == 1u ? sigma_in[m] : frame.sigma;
    if (frame.has_sigma_plane == 2u) sigma_p[m] = frame.axis_x != 0 ? axis_std.x : axis_std.y;
  }
  vec3 c[3];
  trmv_spatial_pixel(ivec2(frame.axis_x, frame.axis_y), frame.radius, sigma_p, pixel.x, pixel.y, c);
  // GPU only: the std plane rides in the colour record's w (spatial_shared.h); it travels on, for the next axis.
  for (int m = 0; m < components; ++m) write_color(m, i, vec4(c[m], sigma_in[m]));
}
