// The Rec. 709 luminance weights, written once for C++ (core/color.h's luminance) and GLSL
// (filters/svgf/tonemap_shared.h): Y = R * RTDR_LUMINANCE_R + G * RTDR_LUMINANCE_G + B * RTDR_LUMINANCE_B, the Y row
// of the linear RGB -> XYZ matrix for Rec. 709 primaries and a D65 white (IEC 61966-2-1:1999 Sec. 5.2; ITU-R
// BT.709-6 Item 3.2). Plain preprocessor with float literals (the `f` suffix is valid GLSL 4.50 too), so both
// compilers read the same fp32 numbers.
#ifndef RTDR_CORE_COLOR_SHARED_H
#define RTDR_CORE_COLOR_SHARED_H

#define RTDR_LUMINANCE_R 0.2126f
#define RTDR_LUMINANCE_G 0.7152f
#define RTDR_LUMINANCE_B 0.0722f

#endif  // RTDR_CORE_COLOR_SHARED_H
