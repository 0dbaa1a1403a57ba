// A-SVGF's choice of a gradient sample's source pixel [ASVGF18 Sec. 3.3], step 2 of trace/gradients.h: the Vulkan
// port of select_gradient_source (trace/gradients.cpp), function for function. Per s x s stratum of frame i-1 (fewer
// pixels at the right and bottom edges), selection 0 hashes (global seed, frame i, stratum) to one of its pixels,
// which offers itself only where it sees a surface and, without seed chains, was no gradient sample itself;
// selection 1 takes the eligible pixel of largest direct + indirect luminance, the first in row order on ties.
// One invocation per stratum.
//   in:  binding 0 id.instance, 1 was_gradient, 2 (direct, indirect) luminance, per pixel of frame i-1;
//   out: 3 the source pixel j per stratum, or RTDR_INVALID_ID. Layout: trace/gradient_select_shared.h.
// Bit-identical to the golden function: the hash is integer arithmetic (core/sampler.glsl), and the brightest
// pixel compares the same fp32 sums (`precise`: one correctly rounded addition, as in C++).
#version 450
#extension GL_GOOGLE_include_directive : require

#include "filters/svgf/planes_shared.h"
#include "trace/gradient_select_shared.h"
#include "core/sampler.glsl"

// The workgroup's shape, per device: the SVGF ports' (planes_shared.h), over the stratum grid.
layout(local_size_x_id = kSvgfGroupSizeXConstant, local_size_y_id = kSvgfGroupSizeYConstant,
       local_size_x = kSvgfGroupSizeX, local_size_y = kSvgfGroupSizeY) in;

RTDR_INPUT_UINT(0, instance)
RTDR_INPUT_UINT(1, was_gradient)
RTDR_INPUT_RG(2, luminance)
layout(std430, set = 0, binding = 3) writeonly buffer OutSource { uint out_source[]; };

layout(push_constant) uniform Push { GradientSelectPush push; };

// GPU only: the push constants, copied once at the top of main(). lavapipe loads a push constant lane by lane at
// each use; the copy is loaded once.
GradientSelectPush frame;

// VisibilityBuffer::index: pixel (x, y)'s linear index in frame i-1.
int pixel_index(int x, int y) { return y * int(frame.width) + x; }

// A pixel may become a gradient sample when it sees a surface and, without chains, was not one itself (the golden
// function's `eligible`).
bool eligible(int j) {
  return instance(j).x != RTDR_INVALID_ID && (frame.seed_chains != 0 || was_gradient(j).x == 0u);
}

// select_gradient_source: the source pixel of stratum (sx, sy), or RTDR_INVALID_ID [ASVGF18 Sec. 3.3].
uint select_gradient_source(int sx, int sy) {
  const int s = frame.stratum_size, width = int(frame.width), height = int(frame.height);
  // The stratum's pixels: s x s, fewer at the right and bottom edges.
  const int x0 = sx * s, y0 = sy * s;
  const int columns = min(s, width - x0), rows = min(s, height - y0);
  if (frame.selection == 0) {
    // Random [ASVGF18 Sec. 3.3]: one of the stratum's pixels, uniformly, by a hash of (seed, frame, stratum).
    const uint salted = hash_u32(frame.global_seed ^ kGradientSelectionSalt);
    const uint h = hash_combine(hash_combine(hash_combine(salted, uint(frame.frame_index)), uint(sx)), uint(sy));
    const int k = int(h % uint(columns * rows));
    const int j = pixel_index(x0 + k % columns, y0 + k / columns);
    return eligible(j) ? uint(j) : RTDR_INVALID_ID;
  }
  // Brightest (Q2RTX): the eligible pixel of largest direct + indirect luminance; the first in row order on ties.
  uint best = RTDR_INVALID_ID;
  float best_luminance = 0.0;
  for (int y = y0; y < y0 + rows; ++y)
    for (int x = x0; x < x0 + columns; ++x) {
      const int j = pixel_index(x, y);
      const vec4 direct_indirect = luminance(j);
      precise float l = direct_indirect.x + direct_indirect.y;
      if (eligible(j) && (best == RTDR_INVALID_ID || l > best_luminance)) {
        best = uint(j);
        best_luminance = l;
      }
    }
  return best;
}

// gradient_samples' step 2: select_gradient_source at every stratum of frame i-1.
void main() {
  frame = push;  // the push constants, read once (see above)
  // This invocation's stratum; the last tiles overhang the grid.
  const ivec2 q = ivec2(gl_GlobalInvocationID.xy);
  if (q.x >= int(frame.strata_x) || q.y >= int(frame.strata_y)) return;
  out_source[q.y * int(frame.strata_x) + q.x] = select_gradient_source(q.x, q.y);
}
