// Remodulation [SVGF17 Sec. 3]: what its C++ (modulate.cpp, gpu/modulate_gpu.cpp) and GLSL (modulate.comp)
// share, written once: the workgroup size, the push-constant block and (from core/demodulation_shared.h) the
// demodulation floor. Both compilers include this file; GLSL has the C preprocessor, and core/shader_shared.h
// maps the types.
//
// Buffer layout of the port (std430, set 0): bindings 0-3 are direct, indirect, albedo and emission, binding 4
// is the colour written. Each is a float array with 3 floats per pixel, R G B, pixel (x, y) at floats
// 3 * (y * width + x) + 0..2: exactly RgbPlane::data (row-major, y down; glm::vec3 is 3 packed floats).
#ifndef RTDR_FILTERS_SVGF_MODULATE_SHARED_H
#define RTDR_FILTERS_SVGF_MODULATE_SHARED_H

#include "core/demodulation_shared.h"

#include "core/shader_shared.h"

#ifdef __cplusplus
namespace rtdr {
#endif

// One invocation per pixel in 8x8 tiles: 64 invocations, a multiple of every vendor's subgroup size.
RTDR_SHARED_CONST RTDR_SHARED_UINT kModulateGroupSizeX = 8;
RTDR_SHARED_CONST RTDR_SHARED_UINT kModulateGroupSizeY = 8;

// The albedo floor of demodulation_factor [SVGF17 Sec. 3], the one the path tracer divided by: written once,
// in core/demodulation_shared.h.
RTDR_SHARED_CONST float kModulateMinAlbedo = float(RTDR_MIN_DEMODULATION_ALBEDO);

// The push-constant block: the frame size, so invocations outside the frame (the last tiles) do nothing.
struct ModulatePush {
  RTDR_SHARED_UINT width;
  RTDR_SHARED_UINT height;
};

#ifdef __cplusplus
}  // namespace rtdr
#endif

#endif  // RTDR_FILTERS_SVGF_MODULATE_SHARED_H
