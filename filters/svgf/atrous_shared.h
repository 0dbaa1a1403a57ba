// What one a-trous level's C++ (atrous.cpp, prefilter.cpp, gpu/atrous_gpu.cpp) and GLSL (atrous.comp,
// prefilter.comp) share, written once: the workgroup size, the push-constant block, the a-trous kernel weights
// (atrous.cpp's atrous_kernel takes them from here) and the prefilter's binomial weights. Both compilers include
// this file; GLSL has the C preprocessor, and the #ifdef __cplusplus block maps GLSL's `uint` to C++.
//
// Buffer layout of the port (std430, set 0), every plane row-major, pixel (x, y) at index y * width + x:
//   prefilter.comp: binding 0 variance Var(c_i) (1 float per pixel), binding 1 g3x3(Var(c_i)) written.
//   atrous.comp:    binding 0 colour c_i (3 floats, R G B), 1 variance Var(c_i), 2 g3x3(Var(c_i)), 3 depth z,
//                   4 depth gradient (2 floats, d/dx d/dy), 5 normal (3 floats), 6 mesh id (1 uint,
//                   kAtrousInvalidId where no surface), 7 colour c_{i+1} written (3 floats), 8 Var(c_{i+1}) written.
// These are exactly the planes' data arrays (glm::vec3 is 3 packed floats, glm::vec2 2).
//
// Accuracy of the port: the shaders do the golden functions' fp32 operations in the same order (the sums and
// products are `precise`, so no fma contraction changes their rounding). What differs is exp, log and sqrt:
// GLSL's exp may be off by 3 + 2|x| ulp and log by a few ulp where libm's are within 1 ulp. With the tap exponents
// that matter (|x| < ~20; smaller weights are under 2e-9 of the centre's) a tap weight differs by a relative few
// 1e-6; the colour is a ratio of weighted sums (~2x that), the variance of squared weights (~4x). The prefilter
// has no transcendental and matches exactly. gpu_atrous_test asserts 5e-5 relative to max(|golden|, 1e-3);
// measured on llvmpipe: colour 8.4e-6, variance 1.4e-5, prefiltered variance 0.
#ifndef RTDR_FILTERS_SVGF_ATROUS_SHARED_H
#define RTDR_FILTERS_SVGF_ATROUS_SHARED_H

// The luminance weights RTDR_LUMINANCE_R/G/B of core/color.h's luminance(), written once.
#include "core/color_shared.h"

#include "core/frame_shared.h"

#include "core/shader_shared.h"

#ifdef __cplusplus
namespace rtdr {
#endif

// One invocation per pixel in 8x8 tiles: 64 invocations, a multiple of every vendor's subgroup size.
RTDR_SHARED_CONST RTDR_SHARED_UINT kAtrousGroupSizeX = 8;
RTDR_SHARED_CONST RTDR_SHARED_UINT kAtrousGroupSizeY = 8;

// id.mesh of a pixel without a surface: core/frame_shared.h's RTDR_INVALID_ID, core/frame.h's kInvalidId.
RTDR_SHARED_CONST RTDR_SHARED_UINT kAtrousInvalidId = RTDR_INVALID_ID;

// The 1D a-trous kernels h [SVGF17 Eq. 1, ASVGF18 Sec. 4], taps k = -radius..radius:
// kernel_size 5, the B3 spline (1/16, 1/4, 3/8, 1/4, 1/16); kernel_size 3, the box (1/3, 1/3, 1/3).
RTDR_SHARED_CONST float kAtrousB3Outer = 1.0f / 16.0f;  // h(+-2)
RTDR_SHARED_CONST float kAtrousB3Inner = 1.0f / 4.0f;   // h(+-1)
RTDR_SHARED_CONST float kAtrousB3Centre = 3.0f / 8.0f;  // h(0)
RTDR_SHARED_CONST float kAtrousBox = 1.0f / 3.0f;       // h(-1) = h(0) = h(1)

// The prefilter's 1D binomial weights g = (1/4, 1/2, 1/4) [SVGF17 Sec. 4.4]. prefilter.h's kGaussian3 holds the
// same numbers (gpu/atrous_gpu.cpp static_asserts that they agree).
RTDR_SHARED_CONST float kPrefilterEdge = 0.25f;   // g(+-1)
RTDR_SHARED_CONST float kPrefilterCentre = 0.5f;  // g(0)

// The push-constant block, for both shaders: the frame size (invocations outside it do nothing), the level i
// (taps 2^i apart), the kernel size (5 or 3) and the edge-stopping parameters of SvgfParams.
// The prefilter reads only width and height.
struct AtrousPush {
  RTDR_SHARED_UINT width;
  RTDR_SHARED_UINT height;
  int level;
  int kernel_size;
  float sigma_z;
  float sigma_n;
  float sigma_l;
  float epsilon;
};

#ifdef __cplusplus
}  // namespace rtdr
#endif

#endif  // RTDR_FILTERS_SVGF_ATROUS_SHARED_H
