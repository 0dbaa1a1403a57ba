// A-SVGF's choice of a gradient sample's source pixel [ASVGF18 Sec. 3.3, step 2 of trace/gradients.h]: what its
// C++ (gpu/gradient_select_gpu.cpp, and the golden select_gradient_source in trace/gradients.cpp) and GLSL
// (trace/gradient_select.comp) share, written once: the selection's hash salt, the binding count and the
// push-constant block. The workgroup shape is the SVGF ports' (filters/svgf/planes_shared.h, which the shader
// includes). Both compilers include this file; GLSL has the C preprocessor, and core/shader_shared.h maps the types.
//
// Bindings (row-major planes of frame i-1, width x height, and one output over its strata):
//   0 id.instance    R32UI, RTDR_INVALID_ID where the pixel sees no surface (PreviousFrame::vis.instance)
//   1 was_gradient   R32UI, 1 where the pixel was a gradient sample itself (gradient.source set), else 0
//   2 luminance      RG32F, (direct, indirect): the luminance of the pixel's demodulated streams
//   3 source         written, std430 array of uint, strata_x x strata_y: the selected source pixel j of each
//                    stratum, as the linear index y width + x of frame i-1, or RTDR_INVALID_ID (none)
#ifndef RTDR_TRACE_GRADIENT_SELECT_SHARED_H
#define RTDR_TRACE_GRADIENT_SELECT_SHARED_H

#include "core/frame_shared.h"
#include "core/shader_shared.h"

#ifdef __cplusplus
namespace rtdr {
#endif

// Salts the selection's hash, so that a stratum's choice is independent of the pixel seeds made from the same
// global seed (core/sampler.h's pixel_seed): "ASVG" in ASCII.
RTDR_SHARED_CONST RTDR_SHARED_UINT kGradientSelectionSalt = 0x41535647u;

// The number of bindings (0..3 above): 3 inputs (storage texel buffers, or storage buffers when built for storage
// inputs: core/shader_shared.h) and 1 storage buffer.
RTDR_SHARED_CONST RTDR_SHARED_UINT kGradientSelectTexelBindings = 3;
RTDR_SHARED_CONST RTDR_SHARED_UINT kGradientSelectStorageBindings = 1;

// The push-constant block: frame i-1's size, its stratum grid (ceil(width / s) x ceil(height / s)), and what
// select_gradient_source reads of GradientParams (trace/gradients.h), the global seed and frame i's index. One
// invocation per stratum.
struct GradientSelectPush {
  RTDR_SHARED_UINT width;        // frame i-1's size
  RTDR_SHARED_UINT height;
  RTDR_SHARED_UINT strata_x;     // the stratum grid's size
  RTDR_SHARED_UINT strata_y;
  RTDR_SHARED_INT stratum_size;  // s (>= 1)
  RTDR_SHARED_INT selection;     // 0: a hashed random pixel; 1: the brightest
  RTDR_SHARED_INT seed_chains;   // 0: a pixel that was a gradient sample is not eligible
  RTDR_SHARED_UINT global_seed;
  RTDR_SHARED_INT frame_index;   // frame i
};

#ifdef __cplusplus
static_assert(sizeof(GradientSelectPush) == 36, "nine 4-byte fields, the std430 layout of the GLSL block");
}  // namespace rtdr
#endif

#endif  // RTDR_TRACE_GRADIENT_SELECT_SHARED_H
