// TRMV's clean-up filter [TRMV21 Sec. 5, Eq. 7-8]: a small joint bilateral after the temporal blend, as strong
// as the blend leaned on the spatial filter.
//
// Pass: trmv_cleanup_pass(cbar_i, histories, alpha^V, s, params, edges) -> the cleaned colour, w_A, w_C, std.
//   in:  cbar_i, the temporal blend's output, and the history it fetched, unclamped (cbar_{i-1}) and clamped
//        (cbar*_{i-1}) (temporal.h); alpha^V per pixel (falloff.h; an empty plane stands for alpha everywhere,
//        the components without Eq. 4); the current G-buffer planes; trmv_params.h; SVGF's edge-stopping sigmas
//   out: w_A(x_i) = (alpha^V(x_i) - alpha)^2                                             [TRMV21 Eq. 7]
//        w_C(x_i) = |cbar*_{i-1}(x_{i-1}) - cbar_{i-1}(x_{i-1})| / (cbar_{i-1}(x_{i-1}) + epsilon)   [TRMV21 Eq. 8]
//        std(x_i) = min(w_A + w_C, 5) pixels                                              [TRMV21 Sec. 5]
//        and cbar_i filtered by the separable joint bilateral of spatial.h, "a fixed size 9x9 but with
//        potentially different standard deviations" [TRMV21 Sec. 5]: the horizontal 1-D pass, then the
//        vertical one, each at pixel p with p's std.
//
// w_A measures how much Eq. 4 moved alpha away from its default, i.e. how much more the blend relied on the
// spatially filtered frame (at most (1 - 0.1)^2 = 0.81); w_C measures the "lost of information" the clamp
// caused, relative to the history. Where neither happened the std is 0 and the clean-up is the identity.
//
// Choices the paper leaves open (filters/trmv/README.md, "Deviations and choices"):
// - Eq. 8 on RGB: w_C = Y(|cbar* - cbar|) / (Y(cbar) + epsilon), Y the luminance (core/color.h) and |.| per
//   channel. On a grey value (visibility) it is Eq. 8 exactly. Taking the luminance of the per-channel absolute
//   difference, not the difference of luminances, keeps channels clamped in opposite directions from
//   cancelling. The histories are radiance or visibility, >= 0, so the denominator is >= epsilon.
// - The std is in pixels (the paper gives none); w_A alone gives at most 0.81 px, so the clean-up bites
//   mostly where the clamp did.
// - Std 0 is the identity exactly (spatial.h), which is what Eq. 7-8 give where nothing was clamped and
//   alpha^V = alpha.
// - Guides: SVGF's w_z w_n, as in the spatial filter (the paper names none). The 1-D passes use the std of the
//   pixel they compute, so the vertical pass at p reads values that the horizontal pass filtered with their own
//   std: part of the separable approximation (spatial.h).
#pragma once

#include "filters/image.h"
#include "filters/probe.h"
#include "filters/surface_planes.h"
#include "filters/svgf/svgf_params.h"
#include "filters/trmv/temporal.h"
#include "filters/trmv/trmv_params.h"

#include <glm/glm.hpp>

namespace rtdr {

// w_A = (alpha^V - alpha)^2 [TRMV21 Eq. 7].
float trmv_weight_alpha(float alpha_v, float alpha);
// w_C = Y(|cbar* - cbar|) / (Y(cbar) + epsilon) [TRMV21 Eq. 8], on luminance (above).
float trmv_weight_clamp(glm::vec3 clamped, glm::vec3 fetched, float epsilon);
// The clean-up's std, min(w_A + w_C, sigma_max) [TRMV21 Sec. 5].
float trmv_cleanup_sigma(float w_a, float w_c, float sigma_max);

struct TrmvCleanupWeights {
  float w_a = 0.0f, w_c = 0.0f, sigma = 0.0f;
};

struct TrmvCleanupOutput {
  RgbPlane color;    // cbar_i after the clean-up
  FloatPlane w_a;    // [TRMV21 Eq. 7]
  FloatPlane w_c;    // [TRMV21 Eq. 8]
  FloatPlane sigma;  // the clean-up's std, pixels
};

// The golden per-pixel function of Eq. 7-8 and the std. The filter's per-pixel function is spatial.h's
// trmv_spatial_pixel, radius (cleanup_size - 1) / 2, with this std.
TrmvCleanupWeights trmv_cleanup_weights_pixel(const TrmvTemporalOutput& temporal, const FloatPlane& alpha_v,
                                              const TrmvParams& params, int x, int y, Probe* probe = nullptr);

// Throws rtdr::Error unless the fetched and clamped histories (and alpha^V, when given) have cbar_i's size: the
// clean-up's check, which its port makes too (gpu/trmv_spatial_gpu.h).
void check_trmv_cleanup_sizes(const TrmvTemporalOutput& temporal, const FloatPlane& alpha_v);

// Eq. 7-8 at every pixel, then the two 1-D passes (parallel over rows, deterministic). Throws rtdr::Error when
// the planes' sizes disagree.
TrmvCleanupOutput trmv_cleanup_pass(const TrmvTemporalOutput& temporal, const FloatPlane& alpha_v,
                                    const SurfacePlanes& s, const TrmvParams& params, const SvgfParams& edges);

}  // namespace rtdr
