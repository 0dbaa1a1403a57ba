// A-SVGF's gradient image [ASVGF18 Sec. 3.4, Eq. 3, Eq. 13], the Vulkan port of gradient_image
// (filters/asvgf/gradient_image.cpp), function for function: per stratum of s x s pixels (fewer at the right and
// bottom border), delta = the gradient sample's luminance now minus before [ASVGF18 Eq. 3] and Delta = the larger of
// the two [ASVGF18 Eq. 13] (both 0 without a sample), the mean luminance of the covered pixels and its population
// variance [ASVGF18 Sec. 3.4], and the geometry of the representative pixel; with the GradientForm's variants
// abs(delta), or the per-sample ratio and the sample-present weight. One invocation per stratum.
// The choices the paper leaves open are the golden pass's (filters/asvgf/gradient_image.h).
//   in:  bindings 0 (C_i, f_{i-1}), 1 gradient.source, 2 surface, 3 depth gradient, 4 id.mesh;
//   out: 5 (delta, Delta, l^(0), Var), 6 (n, z), 7 depth gradient, 8 id.mesh, 9 samples per stratum.
//   Layout: filters/asvgf/gradient_image_shared.h.
// GPU only: every arithmetic result is `precise`, so no fma contraction or reordering changes the rounding; the
// C++ rounds after each operation in the same order (tests/gpu_gradient_image_test.cpp derives the bound).
#version 450
#extension GL_GOOGLE_include_directive : require

#include "core/color.glsl"
#include "filters/asvgf/adaptive_alpha.glsl"
#include "filters/asvgf/gradient_image_shared.h"

// The workgroup's shape, per device: the SVGF ports' (planes_shared.h).
layout(local_size_x_id = kSvgfGroupSizeXConstant, local_size_y_id = kSvgfGroupSizeYConstant,
       local_size_x = kSvgfGroupSizeX, local_size_y = kSvgfGroupSizeY) in;

RTDR_INPUT_RGBA(0, noisy_prev)
RTDR_INPUT_UINT(1, source)
RTDR_INPUT_RGBA(2, surface)
RTDR_INPUT_RG(3, depth_grad)
RTDR_INPUT_UINT(4, mesh)
layout(std430, set = 0, binding = 5) writeonly buffer OutValues { vec4 out_values[]; };
layout(std430, set = 0, binding = 6) writeonly buffer OutSurface { vec4 out_surface[]; };
layout(std430, set = 0, binding = 7) writeonly buffer OutDepthGrad { vec2 out_depth_grad[]; };
layout(std430, set = 0, binding = 8) writeonly buffer OutMesh { uint out_mesh[]; };
layout(std430, set = 0, binding = 9) writeonly buffer OutSamples { uint out_samples[]; };

layout(push_constant) uniform Push { GradientImagePush push; };

// GPU only: the push constants, copied once at the top of main(). lavapipe loads a push constant lane by lane at
// each use; the copy is loaded once.
GradientImagePush frame;

// The frame's planes (Plane::at) and SurfacePlanes::covered.
int pixel_index(int x, int y) { return y * int(frame.width) + x; }
bool covered(int x, int y) { return mesh(pixel_index(x, y)).x != RTDR_INVALID_ID; }

// The values one gradient sample adds, (delta, Delta) as the push block's GradientForm makes them
// (gradient_sample_values).
vec2 gradient_sample_values(float f_now, float f_before) {
  // delta = f_i(G~, xi_{i-1,j}) - f_{i-1}(G, xi_{i-1,j}) as luminance [ASVGF18 Eq. 3].
  precise float delta = f_now - f_before;
  // Delta = max(f_i(G~, xi_{i-1,j}), f_{i-1}(G, xi_{i-1,j})) [ASVGF18 Eq. 13].
  const float norm = max(f_now, f_before);
  // Normalised per sample (Q2RTX, RTGL1): r = min(1, k (|delta| / Delta)^p), beside the sample-present weight 1.
  if (frame.before != 0u) return vec2(gradient_ratio(delta, norm, frame.exponent, frame.scale), 1.0);
  // abs(delta): opposite changes cannot cancel in the reconstruction.
  if (frame.absolute != 0u) return vec2(abs(delta), norm);
  return vec2(delta, norm);
}

// One stratum's values and geometry (GradientStratum), and how many gradient samples it holds.
struct GradientStratum {
  float delta, norm, luminance, variance;
  ivec2 representative;  // (-1, -1) when no pixel sees a surface
  int samples;           // C++: the golden function throws at the second
};

// The golden per-stratum function, gradient_stratum: stratum (sx, sy) of s x s pixels.
GradientStratum gradient_stratum(int sx, int sy) {
  const int s = frame.stratum_size;
  GradientStratum result = GradientStratum(0.0, 0.0, 0.0, 0.0, ivec2(-1), 0);  // C++: out (a GLSL keyword)
  // The stratum's pixels: s x s, fewer at the right and bottom edges.
  const int x0 = sx * s, y0 = sy * s;
  const int x1 = min(x0 + s, int(frame.width)), y1 = min(y0 + s, int(frame.height));

  // The representative pixel: the centre, else the first covered pixel in raster order (gradient_image.h).
  const ivec2 centre = ivec2(min(x0 + s / 2, x1 - 1), min(y0 + s / 2, y1 - 1));
  if (covered(centre.x, centre.y)) result.representative = centre;
  for (int y = y0; y < y1 && result.representative.x < 0; ++y)
    for (int x = x0; x < x1 && result.representative.x < 0; ++x)
      if (covered(x, y)) result.representative = ivec2(x, y);

  // l^(0)(p): the mean luminance of the covered pixels; Var(l^(0)(p)): their population variance [Sec. 3.4].
  int count = 0;
  precise float sum = 0.0, sum_squares = 0.0;
  for (int y = y0; y < y1; ++y)
    for (int x = x0; x < x1; ++x) {
      if (!covered(x, y)) continue;
      const vec4 c = noisy_prev(pixel_index(x, y));
      const float l = luminance(c.rgb);
      ++count;
      sum += l;
      sum_squares += l * l;
      if (source(pixel_index(x, y)).x == RTDR_INVALID_ID) continue;
      ++result.samples;  // C++: more than one throws
      // jbar = (x, y): this frame's luminance there, and the previous frame's at j [ASVGF18 Eq. 2].
      const vec2 values = gradient_sample_values(l, c.w);
      result.delta = values.x;
      result.norm = values.y;
    }
  if (count > 0) {
    precise float mean = sum / float(count);
    precise float variance = max(0.0, sum_squares / float(count) - mean * mean);
    result.luminance = mean;
    result.variance = variance;
  }
  return result;
}

// gradient_image: gradient_stratum at every stratum, with the representative pixel's geometry.
void main() {
  frame = push;  // the push constants, read once (see above)
  // This invocation's stratum; the last tiles overhang the grid.
  const ivec2 p = ivec2(gl_GlobalInvocationID.xy);
  if (p.x >= int(frame.grid_width) || p.y >= int(frame.grid_height)) return;
  const GradientStratum r = gradient_stratum(p.x, p.y);
  const int i = p.y * int(frame.grid_width) + p.x;
  out_values[i] = vec4(r.delta, r.norm, r.luminance, r.variance);
  const bool has_representative = r.representative.x >= 0;
  const int ri = has_representative ? pixel_index(r.representative.x, r.representative.y) : 0;
  out_surface[i] = has_representative ? surface(ri) : vec4(0.0);
  out_depth_grad[i] = has_representative ? depth_grad(ri).xy : vec2(0.0);
  out_mesh[i] = has_representative ? mesh(ri).x : RTDR_INVALID_ID;
  out_samples[i] = uint(r.samples);
}
