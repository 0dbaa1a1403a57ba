// The splat of TRMV's shadow motion vectors [TRMV21 Sec. 4.1], the Vulkan port of trmv_splat_pixel
// (filters/trmv/splat.cpp), as its gather: pixel p averages the valid m^V (and the carried property) of the
// size x size window centred on it that lie on p's receiving surface (the same instance, normals within
// kTrmvSplatNormalCosine); none landed: the surface motion; no surface at p: (0, 0). One invocation per pixel.
// Window, weights and fallback: filters/trmv/splat.h.
//   in:  bindings 0 (m^V, valid, carried), 1 (surface motion), 2 id.instance, 3 the normal;
//   out: 4 (motion, landed, carried). Layout: filters/trmv/splat_shared.h.
// GPU only: every arithmetic result is `precise`; the sums run over the window row by row, left to right, as the
// golden loop does, so they are the same sums in the same order, and the normal test's dot product is glm's
// ((x + y) + z). The division by the count is the device's (tests/gpu_trmv_splat_test.cpp derives the bound).
// The golden pass's summed-area table skips the windows without a valid vector, for speed only; here every pixel
// visits its window.
#version 450
#extension GL_GOOGLE_include_directive : require

#include "filters/trmv/splat_shared.h"

#include "filters/svgf/planes_shared.h"

// The workgroup's shape, per device: the SVGF ports' (planes_shared.h).
layout(local_size_x_id = kSvgfGroupSizeXConstant, local_size_y_id = kSvgfGroupSizeYConstant,
       local_size_x = kSvgfGroupSizeX, local_size_y = kSvgfGroupSizeY) in;

RTDR_INPUT_RGBA(0, shadow)
RTDR_INPUT_RGBA(1, surface_motion)
RTDR_INPUT_UINT(2, instance)
RTDR_INPUT_RGBA(3, normal)
layout(std430, set = 0, binding = 4) writeonly buffer OutSplat { vec4 out_splat[]; };

layout(push_constant) uniform Push { TrmvSplatPush push; };

// GPU only: the push constants, copied once at the top of main(). lavapipe loads a push constant lane by lane at
// each use; the copy is loaded once.
TrmvSplatPush frame;

int index_of(int x, int y) { return y * int(frame.width) + x; }

// trmv_splat_same_surface: the same instance, and n_p . n_q >= kTrmvSplatNormalCosine (glm's dot order).
bool same_surface(int p, int q) {
  if (instance(q).x != instance(p).x) return false;
  const vec3 n_p = normal(p).xyz, n_q = normal(q).xyz;
  precise float cos_n = n_p.x * n_q.x + n_p.y * n_q.y + n_p.z * n_q.z;
  return cos_n >= kTrmvSplatNormalCosine;
}

// The golden per-pixel function, trmv_splat_pixel: (motion, landed, carried) at pixel (x, y).
vec4 splat_shadow_motion_pixel(int x, int y) {
  const int p = index_of(x, y);
  if (instance(p).x == RTDR_INVALID_ID) return vec4(0.0);  // no surface: (0, 0)
  const int width = int(frame.width), height = int(frame.height);
  const int radius = frame.size / 2;
  precise vec2 sum = vec2(0.0);
  precise float sum_carried = 0.0;
  int count = 0;  // splats landed: every weight is 1 (a box)
  for (int qy = max(0, y - radius); qy <= min(height - 1, y + radius); ++qy) {
    for (int qx = max(0, x - radius); qx <= min(width - 1, x + radius); ++qx) {
      const int q = index_of(qx, qy);
      const vec4 shadow_q = shadow(q);
      if (shadow_q.z == 0.0) continue;  // only in-shadow pixels with an Eq. 3 vector splat
      if (!same_surface(p, q)) continue;  // only onto their own receiving surface
      sum += shadow_q.xy;
      sum_carried += shadow_q.w;
      ++count;
    }
  }
  // "weight averaged into the center of each filter" [TRMV21 Sec. 4.1]; nothing landed: the surface motion.
  if (count == 0) return vec4(surface_motion(p).xy, 0.0, 0.0);
  precise vec2 mean = sum / float(count);
  precise float mean_carried = sum_carried / float(count);
  return vec4(mean, 1.0, mean_carried);
}

// trmv_splat_pass: trmv_splat_pixel at every pixel.
void main() {
  frame = push;  // the push constants, read once (see above)
  // This invocation's pixel; the last tiles overhang the frame.
  const ivec2 pixel = ivec2(gl_GlobalInvocationID.xy);
  if (pixel.x >= int(frame.width) || pixel.y >= int(frame.height)) return;
  out_splat[index_of(pixel.x, pixel.y)] = splat_shadow_motion_pixel(pixel.x, pixel.y);
}
