// What tone mapping's C++ (tonemap.cpp, gpu/tonemap_gpu.cpp) and GLSL (tonemap.comp) share, written once:
// the push-constant block and (from core/color_shared.h) the Rec. 709 luminance weights.
// Both compilers include this file; GLSL has the C preprocessor, and core/shader_shared.h maps the types.
//
// Bindings (layout: planes_shared.h): 0 the HDR colour record, an input (RTDR_INPUT_*); 1 the display colour written.
#ifndef RTDR_FILTERS_SVGF_TONEMAP_SHARED_H
#define RTDR_FILTERS_SVGF_TONEMAP_SHARED_H

#include "core/color_shared.h"

#include "core/shader_shared.h"

#include "filters/svgf/planes_shared.h"

#ifdef __cplusplus
namespace rtdr {
#endif

// The push-constant block: the frame size, so invocations outside the frame (the last tiles) do nothing, and
// TonemapParams::exposure (tonemap.h), Reinhard02 Eq. 2's fixed scale.
struct TonemapPush {
  RTDR_SHARED_UINT width;
  RTDR_SHARED_UINT height;
  float exposure;
};

#ifdef __cplusplus
}  // namespace rtdr
#endif

#endif  // RTDR_FILTERS_SVGF_TONEMAP_SHARED_H
