// TAA [Karis14; the last pass of SVGF17 Sec. 3]: what its C++ (taa.cpp, gpu/taa_gpu.cpp, gpu/svgf_shaders.cpp) and GLSL (taa.comp)
// share, written once: the workgroup size and the push-constant block. Both compilers include this file; GLSL
// has the C preprocessor, and core/shader_shared.h maps the types.
//
// Bindings (layout: filters/svgf/planes_shared.h): 0 the current colour record, 1 the history colour record (one
// unread texel when has_history is 0), 2 the motion (RG32F), inputs (RTDR_INPUT_*); 3 the output colour record
// written.
// All planes are row-major, y down, of size width x height.
#ifndef RTDR_FILTERS_TAA_TAA_SHARED_H
#define RTDR_FILTERS_TAA_TAA_SHARED_H

#include "core/shader_shared.h"

#ifdef __cplusplus
#include <cstddef>
namespace rtdr {
#endif

// One invocation per pixel in workgroups of 64 invocations, a multiple of every vendor's subgroup size: 8x8 tiles
// unless the host specializes the shape (constant_id kTaaGroupSizeXConstant and kTaaGroupSizeYConstant), as
// SvgfShaders does per device, giving the TAA port the SVGF ports' shape (filters/svgf/planes_shared.h: 32x2 rows
// on lavapipe).
RTDR_SHARED_CONST RTDR_SHARED_UINT kTaaGroupSizeX = 8;
RTDR_SHARED_CONST RTDR_SHARED_UINT kTaaGroupSizeY = 8;
RTDR_SHARED_CONST int kTaaGroupSizeXConstant = 0;
RTDR_SHARED_CONST int kTaaGroupSizeYConstant = 1;

// The history clip's padding e: clip_towards_mean (taa.cpp, taa.comp) clips onto the box [box_min - e, box_max + e]
// per YCoCg channel, not onto the bare 3x3 box of Karis14. Why: where the box is flat in a channel (box_min =
// box_max = mean, e.g. Co and Cg of any grey neighbourhood) the bare clip jumps: a history on the face keeps t = 1,
// one an ulp beyond it gets t = (box_max - mean) / d = 0, the mean. Padded, the face is at least e from the mean:
// a history at h = box_max + e has d = h - mean = box_max + e - mean and t = d / d = 1, so t is continuous, and
// beyond the face t = (box_max + e - mean) / d with d >= e moves by at most |dh| / e. The clipped history then
// moves by at most |dh| (1 + |h - mean| / e): about 1025 |dh| for display values in [0, 1] (|h - mean| <= 1).
// Playdead's TAA for INSIDE (github.com/playdeadgames/temporal, TemporalReprojection.shader, clip_aabb) has a
// similar margin, FLT_EPS = 1e-8: it clips only a history beyond face + FLT_EPS, but onto the bare face, so a flat
// box still jumps; so tiny a margin bounds nothing. 1/1024 is a quarter of an 8-bit display step (1/255):
// invisible, yet it bounds the clip's sensitivity (tests/taa_taa_test.cpp, tests/gpu_svgf_test.cpp).
RTDR_SHARED_CONST float kTaaClipPadding = 1.0f / 1024.0f;

// The push-constant block (std430 in GLSL; every member sits at its natural C++ offset, vec2s at multiples of 8).
struct TaaPush {
  RTDR_SHARED_UINT width;            // the frame size: invocations outside it (the last tiles) do nothing
  RTDR_SHARED_UINT height;
  float alpha;                       // TaaParams::alpha, the weight of the current frame
  RTDR_SHARED_UINT clip_history;     // TaaParams::clip_history: 1 clip towards the mean, 0 clamp
  RTDR_SHARED_VEC2 jitter_current;   // TaaJitter::current, pixels
  RTDR_SHARED_VEC2 jitter_previous;  // TaaJitter::previous, pixels
  RTDR_SHARED_UINT has_history;      // 0: history is empty (width 0), the output is the current colour
  RTDR_SHARED_UINT padding;          // rounds the block up to its 8-byte alignment, 40 bytes on both sides
};

#ifdef __cplusplus
static_assert(sizeof(TaaPush) == 40 && offsetof(TaaPush, jitter_current) == 16 &&
              offsetof(TaaPush, jitter_previous) == 24 && offsetof(TaaPush, has_history) == 32);
}  // namespace rtdr
#endif

#endif  // RTDR_FILTERS_TAA_TAA_SHARED_H
