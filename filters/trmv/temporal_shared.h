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
//   2 motion m       RG32F (pixels), TrmvMotion::motion
//   3 valid          R32UI, TrmvMotion::valid (has_valid)
//   4 re-shaded      RGBA32F (r, g, b, 1 where TrmvMotion::reshaded_valid, else 0) (has_reshaded)
//   5 cbar_{i-1}     RGBA32F, prev_width x prev_height (has_history)
//   6 id.mesh        R32UI, the previous frame's, prev_width x prev_height
//   7 the alpha plane RG32F (theta, alpha^V), as the falloff port writes it (falloff_shared.h): y is read
//                    (has_alpha)
//   8 (cbar_i, alpha), 9 (cbar_{i-1}(x_{i-1}), a), 10 (cbar*_{i-1}, 0): written, std430 arrays of vec4, where a
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

// The number of bindings (0..10 above): 8 inputs (storage texel buffers, or storage buffers when built for storage
// inputs: core/shader_shared.h) and 3 storage buffers. gpu/svgf_shaders.cpp checks that both fit the limits the
// context was chosen for (gpu/vulkan_context.h).
RTDR_SHARED_CONST RTDR_SHARED_UINT kTrmvTemporalTexelBindings = 8;
RTDR_SHARED_CONST RTDR_SHARED_UINT kTrmvTemporalStorageBindings = 3;

// The push-constant block: the current and the previous frame's sizes, which optional planes are given, and the
// parameters trmv_temporal_pixel reads (filters/trmv/trmv_params.h).
struct TrmvTemporalPush {
  RTDR_SHARED_UINT width;         // c~'s size: invocations outside it (the last tiles) do nothing
  RTDR_SHARED_UINT height;
  RTDR_SHARED_UINT prev_width;    // the history's size, 0 x 0 without one
  RTDR_SHARED_UINT prev_height;
  RTDR_SHARED_UINT has_history;   // 0: first frame (TrmvHistory::color empty), every pixel without history
  RTDR_SHARED_UINT has_valid;     // 0: TrmvMotion::valid empty, every vector valid
  RTDR_SHARED_UINT has_reshaded;  // 0: TrmvMotion::reshaded empty, every history fetched
  RTDR_SHARED_UINT has_alpha;     // 0: the alpha plane is empty, alpha = TrmvParams::alpha everywhere
  float alpha;                    // TrmvParams::alpha
  float clamp_gamma;              // TrmvParams::clamp_gamma, gamma
  RTDR_SHARED_INT clamp_radius;   // TrmvParams::clamp_radius, r (>= 0)
};

#ifdef __cplusplus
static_assert(sizeof(TrmvTemporalPush) == 44, "eleven 4-byte fields, the std430 layout of the GLSL block");
}  // namespace rtdr
#endif

#endif  // RTDR_FILTERS_TRMV_TEMPORAL_SHARED_H
