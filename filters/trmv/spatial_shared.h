// One 1-D pass of TRMV's separable joint bilateral [TRMV21 Sec. 5] (the spatial filter and the clean-up's 9x9):
// what its C++ (gpu/trmv_spatial_gpu.cpp, gpu/svgf_shaders.cpp) and GLSL (filters/trmv/spatial.comp) share, written
// once: the binding count and the push-constant block. The workgroup shape is the SVGF ports'
// (filters/svgf/planes_shared.h). Both compilers include this file; GLSL has the C preprocessor, and
// core/shader_shared.h maps the types.
//
// Bindings (records row-major: filters/svgf/planes_shared.h):
//   0-2 (c, std)   RGBA32F: the planes to filter, the first `components` of them (kTrmvSpatialComponentsConstant);
//                  w the pixel's std (has_sigma_plane 1), else unread
//   3 surface      RGBA32F (n, z), z = kNoSurfaceDepth without a surface (pack_surface)
//   4 grad z       RG32F, per pixel
//   5 std per axis RG32F (sigma_x, sigma_y): the penumbra filter's (has_sigma_plane 2), else one unread texel
//   6-8 (c', std)  written, std430 arrays of vec4: the filtered planes, w copied from the input (the next axis
//                  reads it)
// Bindings of planes beyond `components` are bound (to any buffer) and never read or written.
#ifndef RTDR_FILTERS_TRMV_SPATIAL_SHARED_H
#define RTDR_FILTERS_TRMV_SPATIAL_SHARED_H

#include "filters/svgf/planes_shared.h"

#include "core/shader_shared.h"

#ifdef __cplusplus
namespace rtdr {
#endif

// The number of bindings (0..8 above): 6 inputs (storage texel buffers, or storage buffers when built for storage
// inputs: core/shader_shared.h) and 1 storage buffer. gpu/svgf_shaders.cpp checks that both fit the limits the
// context was chosen for (gpu/vulkan_context.h).
RTDR_SHARED_CONST RTDR_SHARED_UINT kTrmvSpatialTexelBindings = 6;
RTDR_SHARED_CONST RTDR_SHARED_UINT kTrmvSpatialStorageBindings = 3;

// The specialization constant that says how many planes a dispatch filters side by side (1 to 3; 1 unspecialized).
// 0 and 1 are the workgroup shape (planes_shared.h).
RTDR_SHARED_CONST int kTrmvSpatialComponentsConstant = 2;
// The most planes one dispatch filters: TRMV's three components.
RTDR_SHARED_CONST int kTrmvSpatialMaxComponents = 3;

// The push-constant block: the frame's size, the axis, and the arguments trmv_spatial_axis reads
// (filters/trmv/spatial.h) with SVGF's edge-stopping parameters (filters/svgf/svgf_params.h).
struct TrmvSpatialPush {
  RTDR_SHARED_UINT width;            // invocations outside the frame (the last tiles) do nothing
  RTDR_SHARED_UINT height;
  RTDR_SHARED_INT axis_x;            // the step e between taps: (1, 0) horizontal, (0, 1) vertical
  RTDR_SHARED_INT axis_y;
  RTDR_SHARED_INT radius;            // r >= 0: taps k = -r .. r
  RTDR_SHARED_UINT has_sigma_plane;  // 0: `sigma` everywhere; 1: each plane's std is its record's w per pixel;
                                     // 2: binding 5's, x along the horizontal axis and y along the vertical
  float sigma;                       // sigma_all, the spatial std in pixels
  float sigma_z;                     // SvgfParams::sigma_z [SVGF17 Eq. 3]
  float sigma_n;                     // SvgfParams::sigma_n [SVGF17 Eq. 4]
  float epsilon;                     // SvgfParams::epsilon [SVGF17 Eq. 3]
};

#ifdef __cplusplus
static_assert(sizeof(TrmvSpatialPush) == 40, "ten 4-byte fields, the std430 layout of the GLSL block");
}  // namespace rtdr
#endif

#endif  // RTDR_FILTERS_TRMV_SPATIAL_SHARED_H
