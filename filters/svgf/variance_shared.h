// What variance estimation's C++ (variance.h/.cpp, gpu/svgf_shaders.cpp) and GLSL (variance.comp) share, written
// once: the 7x7 footprint's radius and the push-constant block. Both compilers include this file; GLSL has the C
// preprocessor, and core/shader_shared.h maps the types.
//
// Bindings (layout of each plane: planes_shared.h): 0 illumination C' of both streams, 1-2 moments (mu1', mu2', n)
// of the direct and the indirect stream (TemporalOutput), 3 surface, 4 depth gradient, all inputs (RTDR_INPUT_*); 5
// the illumination records (C', sigma'^2) of both streams written.
#ifndef RTDR_FILTERS_SVGF_VARIANCE_SHARED_H
#define RTDR_FILTERS_SVGF_VARIANCE_SHARED_H

#include "filters/svgf/planes_shared.h"

#include "core/shader_shared.h"

#ifdef __cplusplus
namespace rtdr {
#endif

// The spatial fallback's footprint: (2 r + 1)^2 = 7x7 pixels [SVGF17 Sec. 4.2, "a 7 x 7 bilateral filter"].
RTDR_SHARED_CONST RTDR_SHARED_INT kVarianceSpatialRadius = 3;

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
