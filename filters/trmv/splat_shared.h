// The splat of TRMV's shadow motion vectors [TRMV21 Sec. 4.1]: what its C++ (filters/trmv/splat.h,
// gpu/trmv_splat_gpu.cpp, gpu/trmv_shaders.cpp) and GLSL (filters/trmv/splat.comp) share, written once: the bindings, the
// push-constant block and the same-surface test of the golden pass. The workgroup shape is the SVGF ports'
// (filters/svgf/planes_shared.h, which the shader includes). Both compilers include this file; GLSL has the C
// preprocessor, and core/shader_shared.h maps the types.
//
// Bindings (planes row-major: filters/svgf/planes_shared.h):
//   0 m^V            RGBA32F (m^V.x, m^V.y, valid 0 or 1, carried): motion.shadow, its validity and the carried
//                    property (0 without one)
//   1 surface        RGBA32F (m.x, m.y, 0, 0): the back-projected surface motion [TRMV21 Eq. 1]
//   2 instance       R32UI, id.instance (RTDR_INVALID_ID where no surface)
//   3 normal         RGBA32F (n.x, n.y, n.z, 0), unit
//   4 out            a std430 array of vec4 (motion.x, motion.y, landed 0 or 1, carried): written
#ifndef RTDR_FILTERS_TRMV_SPLAT_SHARED_H
#define RTDR_FILTERS_TRMV_SPLAT_SHARED_H

#include "core/frame_shared.h"
#include "core/shader_shared.h"

#ifdef __cplusplus
namespace rtdr {
#endif

// The number of bindings (0..4 above): 4 inputs (storage texel buffers, or storage buffers when built for storage
// inputs: core/shader_shared.h) and 1 storage buffer.
RTDR_SHARED_CONST RTDR_SHARED_UINT kTrmvSplatTexelBindings = 4;
RTDR_SHARED_CONST RTDR_SHARED_UINT kTrmvSplatStorageBindings = 1;

// The same receiving surface: normals within this cosine, SVGF's temporal_normal_cosine (cos 25.8 degrees,
// filters/svgf/svgf_params.h), besides the same instance (filters/trmv/splat.h says why).
RTDR_SHARED_CONST float kTrmvSplatNormalCosine = 0.9f;

// The push-constant block: the frame's size (invocations outside it, the last tiles, do nothing) and the window's
// side (odd, at least 1: the host checks it as trmv_splat_pass does).
struct TrmvSplatPush {
  RTDR_SHARED_UINT width;
  RTDR_SHARED_UINT height;
  RTDR_SHARED_INT size;
  RTDR_SHARED_UINT unused;
};

#ifdef __cplusplus
static_assert(sizeof(TrmvSplatPush) == 16, "four 4-byte fields, the std430 layout of the GLSL block");
}  // namespace rtdr
#endif

#endif  // RTDR_FILTERS_TRMV_SPLAT_SHARED_H
