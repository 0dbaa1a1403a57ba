// TRMV's shadow motion vector [TRMV21 Eq. 3]: what its C++ (motion/shadow.h, gpu/motion_shadow_gpu.cpp) and GLSL
// (motion/shadow.comp) share, written once: the bindings, the record of an instance's motion, the push-constant
// block, and the parallel-line threshold of the golden pass. A View travels as raster/view_shared.h's ViewRecord.
// The workgroup shape is the SVGF ports' (filters/svgf/planes_shared.h, which the shader includes: the golden pass
// does not need it), and the id of "no surface" core/frame_shared.h's. Both compilers include this file; GLSL has
// the C preprocessor, and core/shader_shared.h maps the types.
//
// Bindings (planes row-major: filters/svgf/planes_shared.h):
//   0 l_i            RGBA32F (x, y, z, 0), path.light.X/Y/Z
//   1 b_i            RGBA32F (x, y, z, 0), path.blocker.X/Y/Z
//   2 s_i            RGBA32F (x, y, z, 0), position.X/Y/Z
//   3 n(s_i)         RGBA32F (x, y, z, 0), geonormal.X/Y/Z
//   4 light id       R32UI, path.light.instance
//   5 blocker id     R32UI, path.blocker.instance (RTDR_INVALID_ID: the ray was not blocked)
//   6 receiver id    R32UI, id.instance (RTDR_INVALID_ID: no surface)
//   7 instances      a std430 array of ShadowInstanceMotion, one per instance (InstanceMotion)
//   8 views          a std430 array of two ViewRecord (raster/view_shared.h): [0] this frame's View, [1] the
//                    previous frame's
//   9 out            a std430 array of vec4 (m^V.x, m^V.y, valid 0 or 1, 0): written
#ifndef RTDR_MOTION_SHADOW_SHARED_H
#define RTDR_MOTION_SHADOW_SHARED_H

#include "core/frame_shared.h"
#include "core/shader_shared.h"

#ifdef __cplusplus
#define RTDR_SHADOW_VEC4 glm::vec4
namespace rtdr {
#else
#define RTDR_SHADOW_VEC4 vec4
#endif

// The number of bindings (0..9 above): 7 inputs (storage texel buffers, or storage buffers when built for storage
// inputs: core/shader_shared.h) and 3 storage buffers (instances, views, output).
RTDR_SHARED_CONST RTDR_SHARED_UINT kShadowMotionTexelBindings = 7;
RTDR_SHARED_CONST RTDR_SHARED_UINT kShadowMotionStorageBindings = 3;

// A line parallel to the plane within this cosine (about 6e-5 degrees) has no intersection worth using.
RTDR_SHARED_CONST float kShadowParallelCosine = 1e-6f;

// T^{-1} of one instance (InstanceMotion): the columns of to_previous (mat4), then those of normal_to_previous
// (mat3), each padded to a vec4 (w = 0), so that the std430 layout is the C++ one: 112 bytes.
struct ShadowInstanceMotion {
  RTDR_SHADOW_VEC4 to_previous[4];
  RTDR_SHADOW_VEC4 normal_to_previous[3];
};

// The push-constant block: the frame's size (invocations outside it, the last tiles, do nothing) and the number
// of instances (an id at or beyond it is read as no instance: GPU only, the golden pass's precondition).
struct ShadowMotionPush {
  RTDR_SHARED_UINT width;
  RTDR_SHARED_UINT height;
  RTDR_SHARED_UINT instance_count;
  RTDR_SHARED_UINT unused;
};

#ifdef __cplusplus
static_assert(sizeof(ShadowInstanceMotion) == 112, "seven vec4 columns, the std430 layout of the GLSL struct");
static_assert(sizeof(ShadowMotionPush) == 16, "four 4-byte fields, the std430 layout of the GLSL block");
}  // namespace rtdr
#endif
#undef RTDR_SHADOW_VEC4

#endif  // RTDR_MOTION_SHADOW_SHARED_H
