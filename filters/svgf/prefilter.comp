// The variance prefilter g3x3 [SVGF17 Sec. 4.4, Eq. 5], the Vulkan port of prefilter_variance_pixel
// (prefilter.cpp), line for line: sum over the 3x3 neighbourhood of g(dx) g(dy) Var(x + dx, y + dy), clamped
// borders. One invocation per pixel.
//   in: binding 0: variance; out: binding 1: g3x3(variance). Layout: atrous_shared.h.
#version 450
#extension GL_GOOGLE_include_directive : require

#include "filters/svgf/atrous_shared.h"

layout(local_size_x = kAtrousGroupSizeX, local_size_y = kAtrousGroupSizeY) in;

layout(std430, set = 0, binding = 0) readonly buffer Variance { float variance[]; };
layout(std430, set = 0, binding = 1) writeonly buffer Prefiltered { float prefiltered[]; };

layout(push_constant) uniform Push { AtrousPush frame; };

// The 1D binomial weights (1/4, 1/2, 1/4) (prefilter.h's kGaussian3).
const float kGaussian3[3] = float[3](kPrefilterEdge, kPrefilterCentre, kPrefilterEdge);

// at_clamped (filters/image.h): the nearest edge pixel where (x, y) falls outside.
float at_clamped(int x, int y) {
  x = x < 0 ? 0 : (x >= int(frame.width) ? int(frame.width) - 1 : x);
  y = y < 0 ? 0 : (y >= int(frame.height) ? int(frame.height) - 1 : y);
  return variance[uint(y) * frame.width + uint(x)];
}

float prefilter_variance_pixel(int x, int y) {
  precise float sum = 0.0f;
  for (int dy = -1; dy <= 1; ++dy)
    for (int dx = -1; dx <= 1; ++dx) {
      // The binomial weight of this tap, g(dx) g(dy): 1/4 at the centre, 1/8 at the edges, 1/16 at the corners.
      const float g = kGaussian3[dx + 1] * kGaussian3[dy + 1];
      // The neighbour's variance, the border pixel where (x + dx, y + dy) falls outside.
      const float var_q = at_clamped(x + dx, y + dy);
      // GPU only: `precise` keeps g * var_q and the sum two roundings, as in the golden function.
      sum += g * var_q;
    }
  return sum;
}

void main() {
  // This invocation's pixel; the last tiles overhang the frame.
  const uvec2 pixel = gl_GlobalInvocationID.xy;
  if (pixel.x >= frame.width || pixel.y >= frame.height) return;
  prefiltered[pixel.y * frame.width + pixel.x] = prefilter_variance_pixel(int(pixel.x), int(pixel.y));
}
