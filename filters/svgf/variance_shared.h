// What variance estimation's C++ (variance.h/.cpp, gpu/variance_gpu.cpp) and GLSL (variance.comp) share, written
// once: the 7x7 footprint's radius, the workgroup size, the "no surface" id and the push-constant block. Both
// compilers include this file; GLSL has the C preprocessor, and the #ifdef __cplusplus block maps the types.
//
// Buffer layout of the port (std430, set 0), each pixel (x, y) at element y * width + x, row-major, exactly the
// planes' data:
//   0 moment1 (float), 1 moment2 (float), 2 length (float)         TemporalOutput (temporal.h)
//   3 depth (float), 4 depth_grad (2 floats: dX, dY), 5 normal (3 floats: X, Y, Z), 6 mesh (uint32)
//                                                                   SurfacePlanes (svgf_shared.h)
//   7 sigma2 (float), written
#ifndef RTDR_FILTERS_SVGF_VARIANCE_SHARED_H
#define RTDR_FILTERS_SVGF_VARIANCE_SHARED_H

#include "core/frame_shared.h"

#include "core/shader_shared.h"

#ifdef __cplusplus
namespace rtdr {
#endif

// The spatial fallback's footprint: (2 r + 1)^2 = 7x7 pixels [SVGF17 Sec. 4.2, "a 7 x 7 bilateral filter"].
RTDR_SHARED_CONST RTDR_SHARED_INT kVarianceSpatialRadius = 3;

// One invocation per pixel in 8x8 tiles: 64 invocations, a multiple of every vendor's subgroup size.
RTDR_SHARED_CONST RTDR_SHARED_UINT kVarianceGroupSizeX = 8;
RTDR_SHARED_CONST RTDR_SHARED_UINT kVarianceGroupSizeY = 8;

// id.mesh where no surface: core/frame_shared.h's RTDR_INVALID_ID, core/frame.h's kInvalidId.
RTDR_SHARED_CONST RTDR_SHARED_UINT kVarianceInvalidId = RTDR_INVALID_ID;

// The push-constant block: the frame size (invocations outside it, the last tiles, do nothing) and the
// parameters variance_pixel reads (svgf_params.h). variance_min_history is an int in SvgfParams, >= 0 by its
// range, so a uint here.
struct VariancePush {
  RTDR_SHARED_UINT width;
  RTDR_SHARED_UINT height;
  RTDR_SHARED_UINT variance_min_history;
  float sigma_z;
  float sigma_n;
  float epsilon;
};

#ifdef __cplusplus
}  // namespace rtdr
#endif

#endif  // RTDR_FILTERS_SVGF_VARIANCE_SHARED_H
