// The splat of TRMV's shadow motion vectors [TRMV21 Sec. 4.1]: what its C++ (motion/shadow_splat.h,
// gpu/motion_shadow_gpu.cpp) and GLSL (motion/shadow_splat.comp) share, written once: the bindings, the
// push-constant block and the window and depth test of the golden pass. The workgroup shape is the SVGF ports'
// (filters/svgf/planes_shared.h, which the shader includes). Both compilers include this file; GLSL has the C
// preprocessor, and core/shader_shared.h maps the types.
//
// Bindings (planes row-major: filters/svgf/planes_shared.h):
//   0 m^V            RGBA32F (m^V.x, m^V.y, valid 0 or 1, 0): motion/shadow.comp's output, or ShadowMotion packed
//   1 surface        RGBA32F (m.x, m.y, depth, 0): the back-projected surface motion [TRMV21 Eq. 1] and the
//                    linear view depth (0 where no surface)
//   2 out            a std430 array of vec4 (motion.x, motion.y, landed 0 or 1, 0): written
#ifndef RTDR_MOTION_SHADOW_SPLAT_SHARED_H
#define RTDR_MOTION_SHADOW_SPLAT_SHARED_H

#include "core/shader_shared.h"

#ifdef __cplusplus
namespace rtdr {
#endif

// The number of bindings (0..2 above): 2 inputs (storage texel buffers, or storage buffers when built for storage
// inputs: core/shader_shared.h) and 1 storage buffer.
RTDR_SHARED_CONST RTDR_SHARED_UINT kShadowSplatTexelBindings = 2;
RTDR_SHARED_CONST RTDR_SHARED_UINT kShadowSplatStorageBindings = 1;

// The window's side and the same-surface depth test (motion/shadow_splat.h says why these).
RTDR_SHARED_CONST int kShadowSplatSize = 9;
RTDR_SHARED_CONST float kShadowSplatDepthRelative = 0.1f;

// The push-constant block: the frame's size (invocations outside it, the last tiles, do nothing) and the window's
// side (odd, at least 1: the host checks it as splat_shadow_motion does).
struct ShadowSplatPush {
  RTDR_SHARED_UINT width;
  RTDR_SHARED_UINT height;
  RTDR_SHARED_INT size;
  RTDR_SHARED_UINT unused;
};

#ifdef __cplusplus
static_assert(sizeof(ShadowSplatPush) == 16, "four 4-byte fields, the std430 layout of the GLSL block");
}  // namespace rtdr
#endif

#endif  // RTDR_MOTION_SHADOW_SPLAT_SHARED_H
