// Temporal accumulation [SVGF17 Sec. 4.1, 4.2]: what its C++ (gpu/temporal_gpu.cpp) and GLSL (temporal.comp)
// share, written once: the workgroup size, the "no surface" id and the push-constant block. The luminance
// weights come from core/color_shared.h (shared with core/color.h's luminance()). Both compilers include this
// file; GLSL has the C preprocessor, and core/shader_shared.h maps the types.
//
// Buffer layout of the port (std430, set 0), pixel (x, y) at element y * width + x (the history's planes:
// y * prev_width + x), row-major, exactly the planes' data; vec2 planes are 2 floats, RGB planes 3 floats:
//   0 noisy C_i (rgb)
//   1 depth, 2 depth_grad (xy), 3 normal (xyz), 4 mesh (uint32), 5 motion (xy)       current SurfacePlanes
//   6 colour C'_{i-1} (rgb), 7 moment1, 8 moment2, 9 length                          TemporalHistory
//   10 depth, 11 normal (xyz), 12 mesh (uint32)                                      TemporalHistory::surface
//   13 colour C'_i (rgb), 14 moment1, 15 moment2, 16 length, written                 TemporalOutput
#ifndef RTDR_FILTERS_SVGF_TEMPORAL_SHARED_H
#define RTDR_FILTERS_SVGF_TEMPORAL_SHARED_H

#include "core/color_shared.h"

#include "core/frame_shared.h"

#include "core/shader_shared.h"

#ifdef __cplusplus
namespace rtdr {
#endif

// One invocation per pixel in 8x8 tiles: 64 invocations, a multiple of every vendor's subgroup size.
RTDR_SHARED_CONST RTDR_SHARED_UINT kTemporalGroupSizeX = 8;
RTDR_SHARED_CONST RTDR_SHARED_UINT kTemporalGroupSizeY = 8;

// The number of storage buffers (bindings 0..16 above).
RTDR_SHARED_CONST RTDR_SHARED_UINT kTemporalBufferCount = 17;

// id.mesh where no surface: core/frame_shared.h's RTDR_INVALID_ID, core/frame.h's kInvalidId.
RTDR_SHARED_CONST RTDR_SHARED_UINT kTemporalInvalidId = RTDR_INVALID_ID;

// The push-constant block: the current and previous frame sizes, whether there is a history (0: first frame,
// every pixel a disocclusion), and the parameters temporal_pixel reads (svgf_params.h; max_history is an int
// there, >= 0 by its range, so a uint here).
struct TemporalPush {
  RTDR_SHARED_UINT width;
  RTDR_SHARED_UINT height;
  RTDR_SHARED_UINT prev_width;
  RTDR_SHARED_UINT prev_height;
  RTDR_SHARED_UINT has_history;
  RTDR_SHARED_UINT max_history;
  float alpha;
  float alpha_moments;
  float temporal_depth_relative;
  float temporal_normal_cosine;
};

#ifdef __cplusplus
}  // namespace rtdr
#endif

#endif  // RTDR_FILTERS_SVGF_TEMPORAL_SHARED_H
