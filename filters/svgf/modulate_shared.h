// Remodulation [SVGF17 Sec. 3]: what its C++ (modulate.cpp, gpu/modulate_gpu.cpp) and GLSL (modulate.comp)
// share, written once: the push-constant block and (from core/demodulation_shared.h) the
// demodulation floor. Both compilers include this file; GLSL has the C preprocessor, and core/shader_shared.h
// maps the types.
//
// Bindings (layout: planes_shared.h): 0 the illumination records of both streams, direct and indirect, 1-2 the albedo
// and emission colour records, inputs (RTDR_INPUT_*); 3 the colour record written.
#ifndef RTDR_FILTERS_SVGF_MODULATE_SHARED_H
#define RTDR_FILTERS_SVGF_MODULATE_SHARED_H

#include "core/demodulation_shared.h"

#include "core/shader_shared.h"

#include "filters/svgf/planes_shared.h"

#ifdef __cplusplus
namespace rtdr {
#endif


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
