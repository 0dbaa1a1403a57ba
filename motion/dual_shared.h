// TRMV's dual motion vector [TRMV21 Eq. 6]: what its C++ (motion/dual.h, gpu/motion_dual_gpu.cpp) and GLSL
// (motion/dual.comp) share, written once: the bindings, the record of an instance's two transforms and the
// push-constant block. The depth test's tolerance is the forward projection's (motion/forward_project_shared.h),
// the View's record raster/view_shared.h's, the workgroup shape the SVGF ports' (filters/svgf/planes_shared.h,
// which the shader includes: the golden pass does not need it), and the id of "no surface" core/frame_shared.h's.
// Both compilers include this file; GLSL has the C preprocessor, and core/shader_shared.h maps the types.
//
// What needs the scene's triangles stays on the host: the previous frame's visibility buffer (rasterized by the
// golden previous_visibility) and, for every sample of either buffer, the object-space point it names
// (object_point, raster/visibility.h). The shader does the rest of Eq. 6: world points, projections, the depth
// test, y' and z.
//
// Bindings (planes row-major: filters/svgf/planes_shared.h):
//   0 current point     RGBA32F (x, y, z, 0): object_point of this frame's sample, width x height
//   1 current instance  R32UI, the sample's instance (RTDR_INVALID_ID: no surface)
//   2 surface motion    RG32F (pixels), the `motion` layer
//   3 previous point    RGBA32F (x, y, z, depth): object_point of the previous buffer's sample and its linear
//                       depth (0: no surface), prev_width x prev_height
//   4 previous instance R32UI, the previous sample's instance
//   5 instances         a std430 array of DualInstance, one per instance
//   6 views             a std430 array of two ViewRecord: [0] this frame's View, [1] the previous frame's
//   7 out               a std430 array of vec4 (x^O - x_i .x, .y, disoccluded 0 or 1, 0): written
#ifndef RTDR_MOTION_DUAL_SHARED_H
#define RTDR_MOTION_DUAL_SHARED_H

#include "core/frame_shared.h"
#include "core/shader_shared.h"
#include "motion/forward_project_shared.h"
#include "raster/view_shared.h"

#ifdef __cplusplus
#define RTDR_DUAL_VEC4 glm::vec4
namespace rtdr {
#else
#define RTDR_DUAL_VEC4 vec4
#endif

// The number of bindings (0..7 above): 5 inputs (storage texel buffers, or storage buffers when built for storage
// inputs: core/shader_shared.h) and 3 storage buffers (instances, views, output).
RTDR_SHARED_CONST RTDR_SHARED_UINT kDualMotionTexelBindings = 5;
RTDR_SHARED_CONST RTDR_SHARED_UINT kDualMotionStorageBindings = 3;

// One instance's instance_to_world at this frame's pose and at the previous one (ScenePose), as columns: 128 bytes,
// the same in C++ and in std430.
struct DualInstance {
  RTDR_DUAL_VEC4 to_world[4];
  RTDR_DUAL_VEC4 prev_to_world[4];
};

// The push-constant block: this frame's size (invocations outside it, the last tiles, do nothing), the previous
// visibility buffer's, and the number of instances (an id at or beyond it is read as no instance: GPU only, the
// golden pass's precondition).
struct DualMotionPush {
  RTDR_SHARED_UINT width;
  RTDR_SHARED_UINT height;
  RTDR_SHARED_UINT prev_width;
  RTDR_SHARED_UINT prev_height;
  RTDR_SHARED_UINT instance_count;
  RTDR_SHARED_UINT unused[3];
};

#ifdef __cplusplus
static_assert(sizeof(DualInstance) == 128, "eight vec4 columns, the std430 layout of the GLSL struct");
static_assert(sizeof(DualMotionPush) == 32, "eight 4-byte fields, the std430 layout of the GLSL block");
}  // namespace rtdr
#endif
#undef RTDR_DUAL_VEC4

#endif  // RTDR_MOTION_DUAL_SHARED_H
