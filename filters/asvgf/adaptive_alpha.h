// A-SVGF's adaptive temporal weight [ASVGF18 Sec. 3.5, Eq. 14-15].
//
// Pass: adaptive_alpha_pass(reconstructed gradient, s, size, params) -> lambda, alpha_i and alpha_mu_i per pixel.
//   in:  the reconstructed delta^ and Delta^ per stratum (gradient_atrous.h, last iteration), the stratum size,
//        the base weights alpha and alpha_mu (0.1 for asvgf [ASVGF18 Sec. 5]; filters/asvgf/asvgf.h) and the
//        radius of the maximum (1: 3x3 strata [ASVGF18 Sec. 3.5])
//   out: per stratum   lambda(p) = min(1, |delta^(p)| / Delta^(p))                        [ASVGF18 Eq. 14]
//                      (with gradient_normalize = after and the rows p, k: min(1, k (|delta^| / Delta^)^p); with
//                      gradient_normalize = before delta^ / Delta^ is the mean ratio already: gradient_image.h)
//        per pixel     lambda_max = the maximum of lambda over the (2r+1)^2 strata around the pixel's stratum
//                      alpha_i = (1 - lambda_max) alpha + lambda_max                     [ASVGF18 Eq. 15]
//                      alpha_mu_i = (1 - lambda_max) alpha_mu + lambda_max, the same for the moments
// SVGF's temporal pass (filters/svgf/temporal.h, TemporalAdaptive) reads alpha_i and alpha_mu_i in place of its
// constant weights, and lambda_max for the history length: Eq. 15 is computed here only.
//
// Choices (filters/asvgf/README.md, "Deviations and choices"):
// - Delta^ = 0 (no gradient sample within the reconstruction's reach, or both luminances 0): lambda = 0, the
//   history is kept. Where the history was disoccluded it is dropped anyway by the temporal pass.
// - "the maximum alpha_i over a 3x3-neighborhood" is taken of lambda before Eq. 15, which is the same thing:
//   Eq. 15 increases with lambda (for alpha <= 1). Strata outside the grid are skipped.
// - The stratum's value is used at every one of its pixels (nearest, as the public ports do).
// - The moments take the same lambda as the colour (q2vkpt and Q2RTX do the same), with their own base weight.
#pragma once

#include "filters/asvgf/gradient_image.h"
#include "filters/probe.h"

namespace rtdr {

// The ratio min(1, k (|delta| / Delta)^p), 0 where Delta <= 0, for p = 1 or 2: Eq. 14 with p = k = 1, and the peers'
// variants (gradient_image.h, GradientForm), applied after the reconstruction or to each sample before it.
float gradient_ratio(float delta, float norm, int exponent, float scale);
// lambda = min(1, |delta^| / Delta^), 0 where Delta^ <= 0 [ASVGF18 Eq. 14]: gradient_ratio with p = k = 1.
float gradient_lambda(float delta, float norm);
// alpha_i = (1 - lambda) alpha + lambda [ASVGF18 Eq. 15].
float adaptive_alpha(float alpha, float lambda);

// What the pass reads of the parameter tables (filters/asvgf/asvgf.h fills it).
struct AdaptiveAlphaParams {
  float alpha = 0.1f;           // alpha of Eq. 15, the colour's (SvgfParams::alpha)
  float alpha_moments = 0.1f;   // the moments' (SvgfParams::alpha_moments)
  int radius = 1;               // the maximum over (2 radius + 1)^2 strata (AsvgfParams::alpha_max_radius)
  int exponent = 1;             // p and k of lambda = min(1, k (|delta^| / Delta^)^p): 1 and 1 for Eq. 14, and
  float scale = 1.0f;           // with gradient_normalize = before (asvgf.h's adaptive_alpha_params)
};

struct AdaptiveAlpha {
  FloatPlane lambda;         // per stratum [ASVGF18 Eq. 14]
  FloatPlane lambda_max;     // per pixel: the maximum over the neighbouring strata [ASVGF18 Sec. 3.5]
  FloatPlane alpha;          // per pixel, the colour's alpha_i [ASVGF18 Eq. 15]
  FloatPlane alpha_moments;  // per pixel, the moments' alpha_mu_i
};

struct AdaptiveAlphaPixel {
  float lambda_max = 0.0f, alpha = 0.0f, alpha_moments = 0.0f;
};

// The golden per-pixel function at pixel (x, y).
AdaptiveAlphaPixel adaptive_alpha_pixel(const GradientValues& reconstructed, int s, const AdaptiveAlphaParams& params,
                                        int x, int y, Probe* probe = nullptr);

// Every pixel of a width x height frame (parallel over rows, deterministic).
AdaptiveAlpha adaptive_alpha_pass(const GradientValues& reconstructed, int s, int width, int height,
                                  const AdaptiveAlphaParams& params);

}  // namespace rtdr
