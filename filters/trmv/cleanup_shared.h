// TRMV's clean-up weights [TRMV21 Eq. 7, Eq. 8] and std [TRMV21 Sec. 5]: what the C++ (gpu/trmv_spatial_gpu.cpp,
// gpu/svgf_shaders.cpp) and GLSL (filters/trmv/cleanup.comp) share, written once: the binding count and the
// push-constant block. The filtering after it is filters/trmv/spatial.comp with the std plane
// (filters/trmv/spatial_shared.h). Both compilers include this file; core/shader_shared.h maps the types.
//
// Bindings (records row-major: filters/svgf/planes_shared.h):
//   0 cbar_i                 RGBA32F, the temporal blend's output
//   1 (cbar_{i-1}, alpha^V)  RGBA32F: the fetched history, unclamped; w alpha^V (has_alpha_v), else unread
//   2 cbar*_{i-1}            RGBA32F: the clamped history
//   3 (cbar_i, std)          written, std430 array of vec4: the input of spatial.comp's horizontal pass
//   4 (w_A, w_C, std, 0)     written, std430 array of vec4
#ifndef RTDR_FILTERS_TRMV_CLEANUP_SHARED_H
#define RTDR_FILTERS_TRMV_CLEANUP_SHARED_H

#include "filters/svgf/planes_shared.h"

#include "core/shader_shared.h"

#ifdef __cplusplus
namespace rtdr {
#endif

// The number of bindings (0..4 above): 3 inputs and 2 storage buffers (checked in gpu/svgf_shaders.cpp).
RTDR_SHARED_CONST RTDR_SHARED_UINT kTrmvCleanupTexelBindings = 3;
RTDR_SHARED_CONST RTDR_SHARED_UINT kTrmvCleanupStorageBindings = 2;

// The push-constant block: the frame's size, whether alpha^V is given, and the parameters
// trmv_cleanup_weights_pixel reads (filters/trmv/trmv_params.h).
struct TrmvCleanupPush {
  RTDR_SHARED_UINT width;        // invocations outside the frame (the last tiles) do nothing
  RTDR_SHARED_UINT height;
  RTDR_SHARED_UINT has_alpha_v;  // 0: alpha^V empty, alpha everywhere (w_A = 0)
  float alpha;                   // TrmvParams::alpha
  float cleanup_eps;             // TrmvParams::cleanup_eps, Eq. 8's epsilon
  float cleanup_sigma_max;       // TrmvParams::cleanup_sigma_max, the std's cap (5 px)
};

#ifdef __cplusplus
static_assert(sizeof(TrmvCleanupPush) == 24, "six 4-byte fields, the std430 layout of the GLSL block");
}  // namespace rtdr
#endif

#endif  // RTDR_FILTERS_TRMV_CLEANUP_SHARED_H
