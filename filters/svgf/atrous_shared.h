// What one a-trous level's C++ (atrous.cpp, prefilter.cpp, gpu/atrous_gpu.cpp, gpu/svgf_shaders.cpp,
// gpu/svgf_vulkan.cpp) and GLSL (atrous.comp) share, written once: the push-constant block, the a-trous kernel weights
// (atrous.cpp's atrous_kernel takes them from here) and the prefilter's binomial weights. Both compilers include this
// file; GLSL has the C preprocessor, and core/shader_shared.h maps GLSL's types to C++.
//
// Buffer layout (filters/svgf/planes_shared.h): binding 0 the illumination records (c_i, Var(c_i)) of both streams,
// direct and indirect, 1 the surface record, 2 the depth gradient, all inputs (RTDR_INPUT_*); 3 the records
// (c_{i+1}, Var(c_{i+1})) written, 4 g3x3(Var(c_i)) of both streams written (vec2 per pixel) when keep_prefiltered.
//
// Accuracy of the port: the shader does the golden functions' fp32 operations in the same order (the sums and
// products are `precise`, so no fma contraction changes their rounding), except that it fuses the three weights
// into one exp and one log, exp(sigma_n ln cos - a_z - a_l), where the golden code multiplies exp(-a_z),
// cos^sigma_n and exp(-a_l): the same value up to a few roundings. Beyond that what differs is exp, log and sqrt:
// GLSL's exp may be off by 3 + 2|x| ulp and log by a few ulp where libm's are within 1 ulp. With the tap exponents
// that matter (|x| < ~20; smaller weights are under 2e-9 of the centre's) a tap weight differs by a relative few
// 1e-6; the colour is a ratio of weighted sums (~2x that), the variance of squared weights (~4x). The prefilter
// has no transcendental and matches exactly. gpu_atrous_test asserts 5e-5 relative to max(|golden|, 1e-3);
// measured on llvmpipe: colour 8.4e-6, variance 1.4e-5, prefiltered variance 0.
// With fp16 illumination records (planes_shared.h) the level reads colour and variance as the records hold them
// and stores its result into halves: against the golden level on those values the bounds grow by the storage
// error, 2^-10 for the colour and 2^-9 for the variance (measured: 4.8e-4 and 9.7e-4).
#ifndef RTDR_FILTERS_SVGF_ATROUS_SHARED_H
#define RTDR_FILTERS_SVGF_ATROUS_SHARED_H

// The luminance weights RTDR_LUMINANCE_R/G/B of core/color.h's luminance(), written once.
#include "core/color_shared.h"

#include "core/shader_shared.h"

// The GPU planes' layout and the workgroup size of every SVGF port.
#include "filters/svgf/planes_shared.h"

#ifdef __cplusplus
namespace rtdr {
#endif

// The 1D a-trous kernels h [SVGF17 Eq. 1, ASVGF18 Sec. 4], taps k = -radius..radius:
// kernel_size 5, the B3 spline (1/16, 1/4, 3/8, 1/4, 1/16); kernel_size 3, the box (1/3, 1/3, 1/3).
RTDR_SHARED_CONST float kAtrousB3Outer = 1.0f / 16.0f;  // h(+-2)
RTDR_SHARED_CONST float kAtrousB3Inner = 1.0f / 4.0f;   // h(+-1)
RTDR_SHARED_CONST float kAtrousB3Centre = 3.0f / 8.0f;  // h(0)
RTDR_SHARED_CONST float kAtrousBox = 1.0f / 3.0f;       // h(-1) = h(0) = h(1)

// The prefilter's 1D binomial weights g = (1/4, 1/2, 1/4) [SVGF17 Sec. 4.4]; prefilter.h's kGaussian3 is made of them.
RTDR_SHARED_CONST float kPrefilterEdge = 0.25f;   // g(+-1)
RTDR_SHARED_CONST float kPrefilterCentre = 0.5f;  // g(0)

// The specialization constant that fixes the kernel size, 5 or 3, when the host creates the pipeline
// (atrous.comp's kernel_size, SvgfShaders).
RTDR_SHARED_CONST int kAtrousKernelSizeConstant = 2;  // 0 and 1: the workgroup shape (planes_shared.h)

// The push-constant block: the frame size (invocations outside it do nothing), the level i (taps 2^i apart), the
// edge-stopping parameters of SvgfParams, and whether to write the prefiltered variance (for dumps and tests; the
// pipeline needs it only inside the shader).
struct AtrousPush {
  RTDR_SHARED_UINT width;
  RTDR_SHARED_UINT height;
  int level;
  float sigma_z;
  float sigma_n;
  float sigma_l;
  float epsilon;
  RTDR_SHARED_UINT keep_prefiltered;  // 1: write g3x3(Var(c_i)) to binding 4
};

#ifdef __cplusplus
}  // namespace rtdr
#endif

#endif  // RTDR_FILTERS_SVGF_ATROUS_SHARED_H
