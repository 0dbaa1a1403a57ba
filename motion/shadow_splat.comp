// The splat of TRMV's shadow motion vectors [TRMV21 Sec. 4.1], the Vulkan port of splat_shadow_motion_pixel
// (motion/shadow_splat.cpp), as its gather: pixel p averages the valid m^V of the size x size window centred on
// it whose depth is within kShadowSplatDepthRelative of p's (the same surface); none landed: the surface motion;
// no surface at p: (0, 0). One invocation per pixel. Window, weights and fallback: motion/shadow_splat.h.
//   in:  bindings 0 (m^V, valid), 1 (surface motion, depth);
//   out: 2 (motion, landed, 0). Layout: motion/shadow_splat_shared.h.
// GPU only: every arithmetic result is `precise`; the sums run over the window row by row, left to right, as the
// golden loop does, so they are the same sums in the same order. The division by the count is the device's
// (tests/gpu_motion_shadow_test.cpp derives the bound). The golden pass's summed-area table skips the windows
// without a valid vector, for speed only; here every pixel visits its window.
#version 450
#extension GL_GOOGLE_include_directive : require

#include "motion/shadow_splat_shared.h"

#include "filters/svgf/planes_shared.h"

// The workgroup's shape, per device: the SVGF ports' (planes_shared.h).
layout(local_size_x_id = kSvgfGroupSizeXConstant, local_size_y_id = kSvgfGroupSizeYConstant,
       local_size_x = kSvgfGroupSizeX, local_size_y = kSvgfGroupSizeY) in;

RTDR_INPUT_RGBA(0, shadow)
RTDR_INPUT_RGBA(1, surface)
layout(std430, set = 0, binding = 2) writeonly buffer OutSplat { vec4 out_splat[]; };

layout(push_constant) uniform Push { ShadowSplatPush push; };

// GPU only: the push constants, copied once at the top of main(). lavapipe loads a push constant lane by lane at
// each use; the copy is loaded once.
ShadowSplatPush frame;

int index_of(int x, int y) { return y * int(frame.width) + x; }

// The same surface: depths within kShadowSplatDepthRelative of the larger (symmetric in p and q). std::max(a, b)
// is (a < b ? b : a), GLSL's max the same.
bool same_surface(float z_q, float z_p) {
  precise float difference = abs(z_q - z_p);
  precise float limit = kShadowSplatDepthRelative * max(z_q, z_p);
  return !(difference > limit);
}

// The golden per-pixel function, splat_shadow_motion_pixel: (motion, landed) at pixel (x, y).
vec3 splat_shadow_motion_pixel(int x, int y) {
  const int p = index_of(x, y);
  const vec4 surface_p = surface(p);
  const float z_p = surface_p.z;
  if (z_p <= 0.0) return vec3(0.0);  // no surface: (0, 0)
  const int width = int(frame.width), height = int(frame.height);
  const int radius = frame.size / 2;
  precise vec2 sum = vec2(0.0);
  int count = 0;  // splats landed: every weight is 1 (a box)
  for (int qy = max(0, y - radius); qy <= min(height - 1, y + radius); ++qy) {
    for (int qx = max(0, x - radius); qx <= min(width - 1, x + radius); ++qx) {
      const int q = index_of(qx, qy);
      const vec4 shadow_q = shadow(q);
      if (shadow_q.z == 0.0) continue;  // only in-shadow pixels with an Eq. 3 vector splat
      if (!same_surface(surface(q).z, z_p)) continue;
      sum += shadow_q.xy;
      ++count;
    }
  }
  // "weight averaged into the center of each filter" [TRMV21 Sec. 4.1]; nothing landed: the surface motion.
  if (count == 0) return vec3(surface_p.xy, 0.0);
  precise vec2 mean = sum / float(count);
  return vec3(mean, 1.0);
}

// splat_shadow_motion: splat_shadow_motion_pixel at every pixel.
void main() {
  frame = push;  // the push constants, read once (see above)
  // This invocation's pixel; the last tiles overhang the frame.
  const ivec2 pixel = ivec2(gl_GlobalInvocationID.xy);
  if (pixel.x >= int(frame.width) || pixel.y >= int(frame.height)) return;
  out_splat[index_of(pixel.x, pixel.y)] = vec4(splat_shadow_motion_pixel(pixel.x, pixel.y), 0.0);
}
