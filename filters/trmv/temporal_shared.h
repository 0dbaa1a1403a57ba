// TRMV's temporal blend [TRMV21 Eq. 2] and history clamp [TRMV21 Sec. 5]: what its C++ (gpu/trmv_temporal_gpu.cpp,
// gpu/svgf_shaders.cpp) and GLSL (filters/trmv/temporal.comp) share, written once: the binding count and the
// push-constant block. The workgroup shape is the SVGF ports' (filters/svgf/planes_shared.h), and the id of "no
// surface" core/frame_shared.h's. Both compilers include this file; GLSL has the C preprocessor, and
// core/shader_shared.h maps the types.
//
// Bindings (colour records (r, g, b, w), row-major: filters/svgf/planes_shared.h). Each optional plane of the golden
// pass travels as one unread texel when it is empty, and a push-constant flag says so:
//   0 c~_i           RGBA32F: the spatially filtered colour (w unread: the spatial port's std)
//   1 id.mesh        R32UI, current frame
//   2 surface        RGBA32F (n, z), current frame (pack_surface)
//   3 grad z         RG32F, current frame
//   4 vector         RGBA32F (m.x, m.y, code, 0): TrmvMotion::motion, and code = 0 where TrmvMotion::valid is 0,
//                    else 1 + TrmvMotion::test (GPU only: the validity and the test in one texel, so that the pass
//                    fits kTexelInputBindings; code is a small integer, exact in a float)
//   5 re-shaded      RGBA32F (r, g, b, 1 where TrmvMotion::reshaded_valid, else 0) (has_reshaded)
//   6 cbar_{i-1}     RGBA32F, prev_width x prev_height (has_history)
//   7 id.mesh        R32UI, the previous frame's, prev_width x prev_height
//   8 surface        RGBA32F (n, z), the previous frame's, prev_width x prev_height
//   9 the alpha plane RG32F (theta, alpha^V), as the falloff port writes it (falloff_shared.h): y is read
//                    (has_alpha)
//   10 (cbar_i, alpha), 11 (cbar_{i-1}(x_{i-1}), a), 12 (cbar*_{i-1}, 0): written, std430 arrays of vec4, where a
//                    is the pixel's alpha-plane value (alpha^V), or TrmvParams::alpha without one: what the clean-up
//                    reads as alpha^V (cleanup_shared.h, binding 1), so that the ports chain on the device
#ifndef RTDR_FILTERS_TRMV_TEMPORAL_SHARED_H
#define RTDR_FILTERS_TRMV_TEMPORAL_SHARED_H

#include "core/frame_shared.h"

#include "filters/svgf/planes_shared.h"

#include "core/shader_shared.h"

#ifdef __cplusplus
namespace rtdr {
#endif

// The number of bindings (0..12 above): 10 inputs (storage texel buffers, or storage buffers when built for storage
// inputs: core/shader_shared.h) and 3 storage buffers. gpu/svgf_shaders.cpp checks that both fit the limits the
// context was chosen for (gpu/vulkan_context.h).
RTDR_SHARED_CONST RTDR_SHARED_UINT kTrmvTemporalTexelBindings = 10;
RTDR_SHARED_CONST RTDR_SHARED_UINT kTrmvTemporalStorageBindings = 3;

// The history test of a pixel's vector (TrmvMotion::test, filters/trmv/temporal.h): which previous pixels its
// history may be read from.
RTDR_SHARED_CONST RTDR_SHARED_UINT kTrmvTestNone = 0u;     // any with a surface (the shadow vector; forced reuse)
RTDR_SHARED_CONST RTDR_SHARED_UINT kTrmvTestMesh = 1u;     // the same mesh id (the dual and glossy vectors)
RTDR_SHARED_CONST RTDR_SHARED_UINT kTrmvTestSurface = 2u;  // SVGF's consistency test: mesh, depth, normal

// The push-constant block: the current and the previous frame's sizes, which optional planes are given, and the
// parameters trmv_temporal_pixel reads (filters/trmv/trmv_params.h).
struct TrmvTemporalPush {
  RTDR_SHARED_UINT width;         // c~'s size: invocations outside it (the last tiles) do nothing
  RTDR_SHARED_UINT height;
  RTDR_SHARED_UINT prev_width;    // the history's size, 0 x 0 without one
  RTDR_SHARED_UINT prev_height;
  RTDR_SHARED_UINT has_history;   // 0: first frame (TrmvHistory::color empty), every pixel without history
  RTDR_SHARED_UINT has_reshaded;  // 0: TrmvMotion::reshaded empty, every history fetched
  RTDR_SHARED_UINT has_alpha;     // 0: the alpha plane is empty, alpha = TrmvParams::alpha everywhere
  RTDR_SHARED_UINT same_surface;  // 1: the clamp's window keeps to the pixel's surface (TrmvParams::history_test)
  float alpha;                    // TrmvParams::alpha
  float clamp_gamma;              // TrmvParams::clamp_gamma, gamma
  RTDR_SHARED_INT clamp_radius;   // TrmvParams::clamp_radius, r (>= 0)
  float temporal_depth_relative;  // SvgfParams::temporal_depth_relative: SVGF's consistency test
  float temporal_normal_cosine;   // SvgfParams::temporal_normal_cosine
};

#ifdef __cplusplus
static_assert(sizeof(TrmvTemporalPush) == 52, "thirteen 4-byte fields, the std430 layout of the GLSL block");
}  // namespace rtdr
#endif

#endif  // RTDR_FILTERS_TRMV_TEMPORAL_SHARED_H
