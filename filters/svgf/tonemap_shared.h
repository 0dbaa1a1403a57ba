// What tone mapping's C++ (tonemap.cpp, gpu/tonemap_gpu.cpp) and GLSL (tonemap.comp) share, written once:
// the workgroup size, the push-constant block and (from core/color_shared.h) the Rec. 709 luminance weights.
// Both compilers include this file; GLSL has the C preprocessor, and the #ifdef __cplusplus block maps GLSL's
// `uint` to C++.
//
// Buffer layout of the port (std430, set 0): binding 0 is the HDR colour read, binding 1 the display colour
// written. Each is a float array with 3 floats per pixel, R G B, pixel (x, y) at floats 3 * (y * width + x) + 0..2:
// exactly RgbPlane::data (row-major, y down; glm::vec3 is 3 packed floats).
#ifndef RTDR_FILTERS_SVGF_TONEMAP_SHARED_H
#define RTDR_FILTERS_SVGF_TONEMAP_SHARED_H

#include "core/color_shared.h"

#include "core/shader_shared.h"

#ifdef __cplusplus
namespace rtdr {
#endif

// One invocation per pixel in 8x8 tiles: 64 invocations, a multiple of every vendor's subgroup size.
RTDR_SHARED_CONST RTDR_SHARED_UINT kTonemapGroupSizeX = 8;
RTDR_SHARED_CONST RTDR_SHARED_UINT kTonemapGroupSizeY = 8;

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
