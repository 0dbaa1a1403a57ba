// The demodulation floor [SVGF17 Sec. 3], written once for C++ (core/color.h's demodulation_factor) and GLSL
// (filters/svgf/modulate_shared.h): illumination = radiance / max(albedo, RTDR_MIN_DEMODULATION_ALBEDO) per
// channel, and remodulation multiplies by the same factor. Plain preprocessor, so both compilers read it.
#ifndef RTDR_CORE_DEMODULATION_SHARED_H
#define RTDR_CORE_DEMODULATION_SHARED_H

#define RTDR_MIN_DEMODULATION_ALBEDO 1e-3

#endif  // RTDR_CORE_DEMODULATION_SHARED_H
