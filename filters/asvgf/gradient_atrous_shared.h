// A-SVGF's reconstruction of the gradient on the stratum grid [ASVGF18 Sec. 3.4, Eq. 7-12]: what its C++
// (gpu/asvgf_atrous_gpu.cpp, gpu/svgf_shaders.cpp) and GLSL (filters/asvgf/gradient_atrous.comp) share, written once:
// the binding count and the push-constant block. The workgroup shape is the SVGF ports' (filters/svgf/planes_shared.h),
// the id of "no surface" core/frame_shared.h's, the box and prefilter weights filters/svgf/atrous_shared.h's. Both
// compilers include this file; GLSL has the C preprocessor, and core/shader_shared.h maps the types.
//
// Bindings (row-major planes over the stratum grid, grid_width x grid_height; what gradient_image_shared.h writes):
//   0 (delta^, Delta^, l^(k), Var(l^(k)))  RGBA32F: iteration k's values
//   1 (n.x, n.y, n.z, z)                   RGBA32F: the stratum's geometry
//   2 depth gradient                       RG32F, per pixel
//   3 id.mesh                              R32UI (kInvalidId: no surface in the stratum)
//   written:
//   4 (delta^, Delta^, l^(k+1), Var(l^(k+1)))  std430 array of vec4
// One dispatch per iteration; the host ping-pongs bindings 0 and 4 (gpu/asvgf_atrous_gpu.cpp).
#ifndef RTDR_FILTERS_ASVGF_GRADIENT_ATROUS_SHARED_H
#define RTDR_FILTERS_ASVGF_GRADIENT_ATROUS_SHARED_H

#include "core/frame_shared.h"

#include "filters/svgf/atrous_shared.h"
#include "filters/svgf/planes_shared.h"

#include "core/shader_shared.h"

#ifdef __cplusplus
namespace rtdr {
#endif

// The number of bindings (0..4 above): 4 inputs (storage texel buffers, or storage buffers when built for storage
// inputs: core/shader_shared.h) and 1 storage buffer. gpu/svgf_shaders.cpp checks that both fit the limits the
// context was chosen for (gpu/vulkan_context.h).
RTDR_SHARED_CONST RTDR_SHARED_UINT kGradientAtrousTexelBindings = 4;
RTDR_SHARED_CONST RTDR_SHARED_UINT kGradientAtrousStorageBindings = 1;

// The push-constant block: the stratum grid's size, the iteration k (taps 2^k strata apart), s (a stratum step is
// s pixels, for w_z) and SVGF's parameters that the golden gradient_atrous_pixel reads (filters/svgf/svgf_params.h).
// One invocation per stratum.
struct GradientAtrousPush {
  RTDR_SHARED_UINT grid_width;
  RTDR_SHARED_UINT grid_height;
  RTDR_SHARED_INT level;         // k, 0..30
  RTDR_SHARED_INT stratum_size;  // s (>= 1)
  float sigma_z;
  float sigma_n;
  float sigma_l;
  float epsilon;
};

#ifdef __cplusplus
static_assert(sizeof(GradientAtrousPush) == 32, "eight 4-byte fields, the std430 layout of the GLSL block");
}  // namespace rtdr
#endif

#endif  // RTDR_FILTERS_ASVGF_GRADIENT_ATROUS_SHARED_H
