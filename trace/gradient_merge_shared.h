// A-SVGF's one gradient sample per stratum of frame i [ASVGF18 Sec. 3.3, step 5 of trace/gradients.h]: what its
// C++ (gpu/gradient_select_gpu.cpp) and GLSL (trace/gradient_merge.comp) share, written once: the binding count, the
// workgroup size, the two phases and the push-constant block. Both compilers include this file; GLSL has the C
// preprocessor, and core/shader_shared.h maps the types.
//
// Bindings (one entry per candidate, and two planes over frame i's strata, strata_x x strata_y, row-major):
//   0 source     R32UI, per candidate: its source pixel j in frame i-1, RTDR_INVALID_ID where the entry is none
//   1 target     R32UI, per candidate: its target pixel jbar in frame i, as the linear index y width + x
//   2 min_source std430 array of uint, per stratum: the smallest j landing there (atomicMin, phase 0); the host
//                fills it with RTDR_INVALID_ID first
//   3 winner     std430 array of uint, per stratum: the index of the candidate that stays, the first of those with
//                the smallest j (atomicMin, phase 1); the host fills it with RTDR_INVALID_ID first
#ifndef RTDR_TRACE_GRADIENT_MERGE_SHARED_H
#define RTDR_TRACE_GRADIENT_MERGE_SHARED_H

#include "core/frame_shared.h"
#include "core/shader_shared.h"

#ifdef __cplusplus
namespace rtdr {
#endif

// The number of bindings (0..3 above): 2 inputs (storage texel buffers, or storage buffers when built for storage
// inputs: core/shader_shared.h) and 2 storage buffers.
RTDR_SHARED_CONST RTDR_SHARED_UINT kGradientMergeTexelBindings = 2;
RTDR_SHARED_CONST RTDR_SHARED_UINT kGradientMergeStorageBindings = 2;

// One invocation per candidate, in 1-D workgroups of 64 (a multiple of every vendor's subgroup size): a list has no
// 2-D shape to follow.
RTDR_SHARED_CONST RTDR_SHARED_UINT kGradientMergeGroupSize = 64;

// The two dispatches, in order (push.phase): the smallest j per stratum, then the candidate that holds it.
RTDR_SHARED_CONST RTDR_SHARED_UINT kGradientMergeMinSource = 0;
RTDR_SHARED_CONST RTDR_SHARED_UINT kGradientMergeWinner = 1;

// The push-constant block: frame i's size (width linearizes the targets), its stratum grid, the candidates'
// count and the phase.
struct GradientMergePush {
  RTDR_SHARED_UINT width;  // frame i's size
  RTDR_SHARED_UINT height;
  RTDR_SHARED_UINT strata_x;  // the stratum grid's size, ceil(width / s) x ceil(height / s)
  RTDR_SHARED_UINT strata_y;
  RTDR_SHARED_INT stratum_size;  // s (>= 1)
  RTDR_SHARED_UINT candidates;   // entries in bindings 0 and 1
  RTDR_SHARED_UINT phase;        // kGradientMergeMinSource or kGradientMergeWinner
};

#ifdef __cplusplus
static_assert(sizeof(GradientMergePush) == 28, "seven 4-byte fields, the std430 layout of the GLSL block");
}  // namespace rtdr
#endif

#endif  // RTDR_TRACE_GRADIENT_MERGE_SHARED_H
