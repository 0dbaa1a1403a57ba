// Temporal accumulation [SVGF17 Sec. 4.1, 4.2]: what its C++ (gpu/svgf_shaders.cpp) and GLSL (temporal.comp)
// share, written once: the binding count and the push-constant block. The luminance weights come from
// core/color_shared.h (shared with core/color.h's luminance()). Both compilers include this file; GLSL has the C
// preprocessor, and core/shader_shared.h maps the types.
//
// Bindings (layout of each plane: planes_shared.h; the history's planes are prev_width x prev_height):
//   0 noisy illumination C_i, both streams                                           inputs (RTDR_INPUT_*)
//   1 surface, 2 depth gradient, 3 mesh id, 4 motion                                 current G-buffer
//   5 illumination C'_{i-1}, 6-7 moments (mu1', mu2', n) of the direct and indirect  TemporalHistory
//   8 surface, 9 mesh id                                                             TemporalHistory::surface
//   10 illumination C'_i, 11-12 moments, direct and indirect, written                storage buffers
//   13-14 A-SVGF's (lambda_max, alpha_i, alpha_mu_i, 0) of the direct and the         storage buffers (vec4),
//         indirect stream, as filters/asvgf/adaptive_alpha.comp writes them; one unread element unless push.adaptive
#ifndef RTDR_FILTERS_SVGF_TEMPORAL_SHARED_H
#define RTDR_FILTERS_SVGF_TEMPORAL_SHARED_H

#include "core/color_shared.h"

#include "filters/svgf/planes_shared.h"

#include "core/shader_shared.h"

#ifdef __cplusplus
namespace rtdr {
#endif

// The number of bindings (0..14 above): 10 storage texel buffers and 5 storage buffers. Vulkan guarantees only 4
// of each per stage (maxPerStageDescriptorStorageImages, which counts storage texel buffers, and
// maxPerStageDescriptorStorageBuffers). Built for storage inputs (core/shader_shared.h) all 15 are storage
// buffers. The context picks either build only where the device allows that many (gpu/vulkan_context.cpp,
// resolve_inputs).
RTDR_SHARED_CONST RTDR_SHARED_UINT kTemporalTexelBindings = 10;
RTDR_SHARED_CONST RTDR_SHARED_UINT kTemporalStorageBindings = 5;

// The push-constant block: the current and previous frame sizes, whether there is a history (0: first frame,
// every pixel a disocclusion), and the parameters temporal_pixel reads (svgf_params.h; max_history is an int
// there, >= 0 by its range, so a uint here); with A-SVGF, TemporalAdaptive's (filters/svgf/temporal.h).
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
  RTDR_SHARED_UINT adaptive;         // 1: A-SVGF's alpha_i, alpha_mu_i per pixel from bindings 13-14 [ASVGF18 Eq. 15]
  RTDR_SHARED_UINT restart_history;  // 1: n_{i-1} <- (1 - lambda) n_{i-1} (TemporalAdaptive::restart_history)
};

#ifdef __cplusplus
static_assert(sizeof(TemporalPush) == 48, "twelve 4-byte fields, the std430 layout of the GLSL block");
}  // namespace rtdr
#endif

#endif  // RTDR_FILTERS_SVGF_TEMPORAL_SHARED_H
