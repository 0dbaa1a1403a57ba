// A-SVGF's adaptive temporal weight [ASVGF18 Sec. 3.5, Eq. 14-15]: what its C++ (gpu/asvgf_alpha_gpu.cpp,
// gpu/svgf_shaders.cpp) and GLSL (filters/asvgf/adaptive_alpha.comp) share, written once: the binding count and the
// push-constant block. The workgroup shape is the SVGF ports' (filters/svgf/planes_shared.h). Both compilers include
// this file; GLSL has the C preprocessor, and core/shader_shared.h maps the types.
//
// Bindings (row-major planes):
//   0 (delta^, Delta^, l, Var)  RGBA32F, the stratum grid's size (grid_width x grid_height): the reconstructed
//                           gradient and its normalisation (gradient_atrous.h, last iteration), as the
//                           reconstruction's port writes its values (gradient_atrous_shared.h); l and Var unread
//   1 (lambda_max, alpha_i, alpha_mu_i, 0) written, std430 array of vec4, the frame's size (width x height): what
//                           SVGF's temporal port reads (filters/svgf/temporal_shared.h, bindings 13-14)
//   2 lambda                written, std430 array of float, the stratum grid's size
#ifndef RTDR_FILTERS_ASVGF_ADAPTIVE_ALPHA_SHARED_H
#define RTDR_FILTERS_ASVGF_ADAPTIVE_ALPHA_SHARED_H

#include "filters/svgf/planes_shared.h"

#include "core/shader_shared.h"

#ifdef __cplusplus
namespace rtdr {
#endif

// The number of bindings (0..2 above): 1 input (a storage texel buffer, or a storage buffer when built for storage
// inputs: core/shader_shared.h) and 2 storage buffers. gpu/svgf_shaders.cpp checks that both fit the limits the
// context was chosen for (gpu/vulkan_context.h).
RTDR_SHARED_CONST RTDR_SHARED_UINT kAdaptiveAlphaTexelBindings = 1;
RTDR_SHARED_CONST RTDR_SHARED_UINT kAdaptiveAlphaStorageBindings = 2;

// The push-constant block: the frame's and the stratum grid's sizes, and the parameters adaptive_alpha_pixel reads
// (filters/asvgf/asvgf_params.h). One invocation per pixel of the larger of the two sizes on each axis: it writes
// pixel (x, y)'s alpha where that is inside the frame, and stratum (x, y)'s lambda where that is inside the grid.
struct AdaptiveAlphaPush {
  RTDR_SHARED_UINT width;        // the frame's size
  RTDR_SHARED_UINT height;
  RTDR_SHARED_UINT grid_width;   // the stratum grid's size (the planes of GradientValues)
  RTDR_SHARED_UINT grid_height;
  RTDR_SHARED_INT stratum_size;  // s (>= 1)
  RTDR_SHARED_INT radius;        // r (>= 0): the maximum over (2r + 1)^2 strata
  float alpha;                   // the base alpha of Eq. 15, the colour's
  float alpha_moments;           // and the moments'
  RTDR_SHARED_INT exponent;      // p and k of lambda = min(1, k (|delta^| / Delta^)^p) (AdaptiveAlphaParams)
  float scale;
};

#ifdef __cplusplus
static_assert(sizeof(AdaptiveAlphaPush) == 40, "ten 4-byte fields, the std430 layout of the GLSL block");
}  // namespace rtdr
#endif

#endif  // RTDR_FILTERS_ASVGF_ADAPTIVE_ALPHA_SHARED_H
