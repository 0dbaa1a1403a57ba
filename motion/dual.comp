// TRMV's dual motion vector [TRMV21 Eq. 6], the Vulkan port of dual_motion_pixel (motion/dual.cpp), step for
// step: y = x_i + m; the current surface point carried back with its own instance, and the depth test against the
// previous visible depth at floor(y); the occluder seen there: y' = P_{i-1}(its previous point) and
// z = P_i T(y) P_{i-1}^{-1} y, its point now; x^O_{i-1} = y - (z - y'). Not disoccluded (no surface, y off the
// previous image, nothing nearer there, the occluder behind the current camera): x^O = y, the surface motion.
// One invocation per pixel. The choices the paper leaves open are the golden pass's (motion/dual.h).
//   in:  bindings 0-2 this frame's object points, instances and surface motion; 3-4 the previous visibility
//        buffer's object points with their depth, and instances; 5 each instance's two transforms; 6 the two Views;
//   out: 7 (x^O - x_i, disoccluded, 0). Layout: motion/dual_shared.h.
// GPU only: every arithmetic result is `precise`, so no fma contraction or reordering changes the rounding; the
// C++ rounds after each operation in the same order, and glm's mat4 * vec4 is written out in glm's order
// (raster/view.glsl). Every decision is made from the same fp32 operations as the C++ (no division, no square
// root), so it is the golden one; only View::project's division is the device's (tests/gpu_motion_dual_test.cpp
// derives the bound).
#version 450
#extension GL_GOOGLE_include_directive : require

#include "motion/dual_shared.h"

#include "filters/svgf/planes_shared.h"
#include "raster/view.glsl"

// The workgroup's shape, per device: the SVGF ports' (planes_shared.h).
layout(local_size_x_id = kSvgfGroupSizeXConstant, local_size_y_id = kSvgfGroupSizeYConstant,
       local_size_x = kSvgfGroupSizeX, local_size_y = kSvgfGroupSizeY) in;

RTDR_INPUT_RGBA(0, point)
RTDR_INPUT_UINT(1, instance)
RTDR_INPUT_RG(2, surface_motion)
RTDR_INPUT_RGBA(3, prev_point_depth)
RTDR_INPUT_UINT(4, prev_instance)
layout(std430, set = 0, binding = 5) readonly buffer Instances { DualInstance instances[]; };
layout(std430, set = 0, binding = 6) readonly buffer Views { ViewRecord views[2]; };
layout(std430, set = 0, binding = 7) writeonly buffer OutDual { vec4 out_dual[]; };

layout(push_constant) uniform Push { DualMotionPush push; };

// GPU only: the push constants, copied once at the top of main(). lavapipe loads a push constant lane by lane at
// each use; the copy is loaded once.
DualMotionPush frame;

// views[] holds this frame's View, then the previous frame's.
const int kCurrentView = 0;
const int kPreviousView = 1;

// An instance id the shader may index instances[] with. GPU only: the golden pass takes every id below the
// instance count (a visibility buffer names only the scene's instances); an id beyond it would read outside the
// buffer.
bool known_instance(uint id) { return id != RTDR_INVALID_ID && id < frame.instance_count; }

// world_point(scene, pose, sample) (raster/visibility.h), from the sample's object point: instance_to_world at
// this frame's pose or at the previous one.
vec3 world_point_now(uint k, vec3 object) { return transform_point(instances[k].to_world, object); }
vec3 world_point_before(uint k, vec3 object) { return transform_point(instances[k].prev_to_world, object); }

// The golden per-pixel function, dual_motion_pixel: (x^O - x_i, disoccluded).
vec3 dual_motion_pixel(int x, int y) {
  const int i = y * int(frame.width) + x;
  const vec2 m = surface_motion(i).xy;
  const vec3 keep = vec3(m, 0.0);  // x^O = y wherever Eq. 6 does not apply
  const uint k = instance(i).x;
  if (!known_instance(k)) return keep;

  // y = x_i + m: where this pixel's surface point was in frame i-1 [TRMV21 Eq. 1].
  const vec2 x_i = vec2(float(x) + 0.5, float(y) + 0.5);
  precise vec2 y_prev = x_i + m;
  // floor(y) inside the previous image (came in at the border otherwise). The range test is on y itself, which
  // is the same test for every finite y, and keeps floor() within int range; false for a NaN, as the golden
  // int(floor(NaN)) lands outside the image.
  const bool inside = y_prev.x >= 0.0 && y_prev.y >= 0.0 && y_prev.x < float(frame.prev_width) &&
                      y_prev.y < float(frame.prev_height);
  if (!inside) return keep;
  const ivec2 q = ivec2(floor(y_prev));

  // Disoccluded: in frame i-1 something nearer stood at y (motion/dual.h, the depth test).
  const float depth_prev = project(views[kPreviousView], world_point_before(k, point(i).xyz)).z;
  const int qi = q.y * int(frame.prev_width) + q.x;
  const vec4 occluder_record = prev_point_depth(qi);  // (object point, visible depth)
  const float visible_depth = occluder_record.w;
  // 1 - kForwardProjectionDepthTolerance is folded by glslc from the literal (0.99, rounded once to a float);
  // gpu/motion_dual_gpu.cpp checks it is C++'s float difference.
  precise float nearer = depth_prev * (1.0 - kForwardProjectionDepthTolerance);
  if (!(visible_depth > 0.0 && visible_depth < nearer)) return keep;

  // The occluder's point at y: y' where it was, z = P_i T(y) P_{i-1}^{-1} y where it is now [TRMV21 Eq. 6].
  const uint occluder = prev_instance(qi).x;
  if (!known_instance(occluder)) return keep;  // GPU only: a visible depth always names an instance
  const vec3 occluder_point = occluder_record.xyz;
  const vec2 y_occluder = project(views[kPreviousView], world_point_before(occluder, occluder_point)).xy;
  const vec3 z = project(views[kCurrentView], world_point_now(occluder, occluder_point));  // forward_project
  if (z.z < views[kCurrentView].znear) return keep;  // the occluder left through the near plane: no z
  // x^O_{i-1} = y + (x_i - z), with the occluder's motion v = z - y' taken at its own point.
  precise vec2 v = z.xy - y_occluder;
  precise vec2 motion = (y_prev - v) - x_i;
  return vec3(motion, 1.0);
}

// dual_motion: dual_motion_pixel at every pixel.
void main() {
  frame = push;  // the push constants, read once (see above)
  // This invocation's pixel; the last tiles overhang the frame.
  const ivec2 pixel = ivec2(gl_GlobalInvocationID.xy);
  if (pixel.x >= int(frame.width) || pixel.y >= int(frame.height)) return;
  out_dual[pixel.y * int(frame.width) + pixel.x] = vec4(dual_motion_pixel(pixel.x, pixel.y), 0.0);
}
