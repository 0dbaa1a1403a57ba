// A-SVGF's gradient image [ASVGF18 Sec. 3.4, Eq. 3, Eq. 13]: what its C++ (gpu/asvgf_gradient_gpu.cpp,
// gpu/svgf_shaders.cpp) and GLSL (filters/asvgf/gradient_image.comp) share, written once: the binding count and the
// push-constant block. The workgroup shape is the SVGF ports' (filters/svgf/planes_shared.h), and the id of "no
// surface" or "no sample" core/frame_shared.h's. Both compilers include this file; GLSL has the C preprocessor, and
// core/shader_shared.h maps the types.
//
// Bindings (row-major planes; surface records as filters/svgf/planes_shared.h):
//   0 (C_i, f_{i-1})     RGBA32F, the frame's size: one stream's noisy colour, and in w gradient.prev_<stream>
//   1 gradient.source    R32UI, the frame's size (kInvalidId: no gradient sample at the pixel)
//   2 surface            RGBA32F (n.x, n.y, n.z, z), the frame's size
//   3 depth gradient     RG32F, the frame's size
//   4 id.mesh            R32UI, the frame's size
//   written, std430 arrays over the stratum grid (grid_width x grid_height):
//   5 (delta, Delta, l^(0), Var(l^(0)))  vec4
//   6 (n.x, n.y, n.z, z)                 vec4, the representative pixel's (0 where there is none)
//   7 depth gradient                     vec2, likewise
//   8 id.mesh                            uint: the representative pixel's mesh id (kInvalidId where there is
//                                        none), as the reconstruction reads it (gradient_atrous_shared.h, binding 3)
//   9 gradient samples                   uint: how many samples the stratum holds (more than 1: the per-pass port
//                                        throws, as the golden pass does)
#ifndef RTDR_FILTERS_ASVGF_GRADIENT_IMAGE_SHARED_H
#define RTDR_FILTERS_ASVGF_GRADIENT_IMAGE_SHARED_H

#include "core/frame_shared.h"

#include "filters/svgf/planes_shared.h"

#include "core/shader_shared.h"

#ifdef __cplusplus
namespace rtdr {
#endif

// The number of bindings (0..8 above): 5 inputs (storage texel buffers, or storage buffers when built for storage
// inputs: core/shader_shared.h) and 4 storage buffers. gpu/svgf_shaders.cpp checks that both fit the limits the
// context was chosen for (gpu/vulkan_context.h).
RTDR_SHARED_CONST RTDR_SHARED_UINT kGradientImageTexelBindings = 5;
RTDR_SHARED_CONST RTDR_SHARED_UINT kGradientImageStorageBindings = 5;

// The push-constant block: the frame's size, the stratum grid's (ceil(width / s) x ceil(height / s)), s, and the
// GradientForm (gradient_image.h). One invocation per stratum.
struct GradientImagePush {
  RTDR_SHARED_UINT width;
  RTDR_SHARED_UINT height;
  RTDR_SHARED_UINT grid_width;
  RTDR_SHARED_UINT grid_height;
  RTDR_SHARED_INT stratum_size;  // s (>= 1), the render's rtdr.gradient.stratum_size
  RTDR_SHARED_UINT before;       // GradientForm: 1 normalises per sample
  RTDR_SHARED_UINT absolute;     // 1: abs(delta) (after only)
  RTDR_SHARED_INT exponent;      // p
  float scale;                   // k
};

#ifdef __cplusplus
static_assert(sizeof(GradientImagePush) == 36, "nine 4-byte fields, the std430 layout of the GLSL block");
}  // namespace rtdr
#endif

#endif  // RTDR_FILTERS_ASVGF_GRADIENT_IMAGE_SHARED_H
