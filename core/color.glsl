// GLSL mirror of core/color.h, for the Vulkan ports (#include "core/color.glsl"; needs
// GL_GOOGLE_include_directive). The numbers are core/color_shared.h's, written once for both languages.
#ifndef RTDR_CORE_COLOR_GLSL
#define RTDR_CORE_COLOR_GLSL

#include "core/color_shared.h"

// Relative luminance Y of a linear RGB colour, Rec. 709 weights: R r + G g + B b (core/color.h's luminance).
// GPU only: `precise` keeps the products and sums from fusing into fmas, so the port rounds after each
// operation in the same order as the C++, (R term + G term) + B term.
float luminance(vec3 rgb) {
  precise float y = RTDR_LUMINANCE_R * rgb.r + RTDR_LUMINANCE_G * rgb.g + RTDR_LUMINANCE_B * rgb.b;
  return y;
}

#endif  // RTDR_CORE_COLOR_GLSL
