// TRMV's non-planar receiver falloff [TRMV21 Eq. 4]: what its C++ (filters/trmv/falloff.cpp,
// gpu/trmv_falloff_gpu.cpp, gpu/svgf_shaders.cpp) and GLSL (filters/trmv/falloff.comp) share, written once: the
// binding count, the push-constant block and the two constants of the golden pass. The workgroup shape is the SVGF
// ports' (filters/svgf/planes_shared.h), and the id of "no surface" core/frame_shared.h's. Both compilers include
// this file; GLSL has the C preprocessor, and core/shader_shared.h maps the types.
//
// Bindings (records row-major: filters/svgf/planes_shared.h). Each optional plane of the golden pass travels as one
// unread texel when it is empty, and a push-constant flag says so:
//   0 s_i            RGBA32F (x, y, z, 0), TrmvReceiver::position
//   1 n(s_i)         RGBA32F (x, y, z, 0), TrmvReceiver::normal
//   2 id.mesh        R32UI, TrmvReceiver::mesh
//   3 m              RG32F (pixels), TrmvReceiver::motion, the surface motion
//   4 m^V            RG32F (pixels), TrmvMotion::motion
//   5 valid          R32UI, TrmvMotion::valid (has_valid)
//   6 position       RGBA32F (x, y, z, 0), TrmvPreviousPositions::position, prev_width x prev_height (has_prev)
//   7 geonormal      RGBA32F (x, y, z, 0), TrmvPreviousPositions::normal, prev_width x prev_height
//   8 id.mesh        R32UI, TrmvPreviousPositions::mesh, prev_width x prev_height
//   9 (theta, alpha^V): written, a std430 array of vec2
#ifndef RTDR_FILTERS_TRMV_FALLOFF_SHARED_H
#define RTDR_FILTERS_TRMV_FALLOFF_SHARED_H

#include "core/frame_shared.h"

#include "filters/svgf/planes_shared.h"

#include "core/shader_shared.h"

#ifdef __cplusplus
namespace rtdr {
#endif

// The number of bindings (0..9 above): 9 inputs (storage texel buffers, or storage buffers when built for storage
// inputs: core/shader_shared.h) and 1 storage buffer. gpu/svgf_shaders.cpp checks that both fit the limits the
// context was chosen for (gpu/vulkan_context.h).
RTDR_SHARED_CONST RTDR_SHARED_UINT kTrmvFalloffTexelBindings = 9;
RTDR_SHARED_CONST RTDR_SHARED_UINT kTrmvFalloffStorageBindings = 1;

// A static shadow: s^V_{i-1} within this relative distance of s_i has no direction (filters/trmv/falloff.h). 1e-6
// is about eight float epsilons (2^-23 = 1.2e-7) of the coordinates, the rounding of two positions that are the
// same point; relative to 1 + |s_i| so that points near the origin get an absolute 1e-6.
RTDR_SHARED_CONST float kTrmvFalloffSamePointRelative = 1e-6f;
// pi/2 as a float, glm::half_pi<float>() (0x3fc90fdb): theta without evidence, and the centre of Eq. 4's Gaussian.
RTDR_SHARED_CONST float kTrmvFalloffHalfPi = 1.57079637f;

// The push-constant block: the current and the previous frame's sizes, which optional planes are given, and the
// parameters trmv_falloff_pixel reads (filters/trmv/trmv_params.h).
struct TrmvFalloffPush {
  RTDR_SHARED_UINT width;        // the receiver's size: invocations outside it (the last tiles) do nothing
  RTDR_SHARED_UINT height;
  RTDR_SHARED_UINT prev_width;   // the previous positions' size, 0 x 0 on the first frame
  RTDR_SHARED_UINT prev_height;
  RTDR_SHARED_UINT has_prev;     // 0: first frame (TrmvPreviousPositions::position empty), no pixel has evidence
  RTDR_SHARED_UINT has_valid;    // 0: TrmvMotion::valid empty, every vector valid
  float alpha;                   // TrmvParams::alpha
  float falloff_sigma;           // TrmvParams::falloff_sigma, sigma (radians)
  RTDR_SHARED_UINT falloff_carry;  // TrmvParams::falloff_carry: 1 the receiver carried back to frame i-1
};

#ifdef __cplusplus
static_assert(sizeof(TrmvFalloffPush) == 36, "nine 4-byte fields, the std430 layout of the GLSL block");
}  // namespace rtdr
#endif

#endif  // RTDR_FILTERS_TRMV_FALLOFF_SHARED_H
