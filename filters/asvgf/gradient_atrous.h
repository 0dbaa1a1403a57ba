// The reconstruction of the sparse temporal gradient on the stratum grid [ASVGF18 Sec. 3.4, Eq. 7-12].
//
// Pass: gradient_atrous_level(values_k, image, k, params) -> values_{k+1}, one of five iterations k = 0..4.
//   in:  the per-stratum values of iteration k (delta^, Delta^, l^, Var(l^); gradient_image.h at k = 0), the
//        strata's geometry, the iteration k (taps 2^k strata apart), SVGF's sigmas and epsilon
//   out: l^(k+1)(p) = sum_q h w l^(k)(q) / sum_q h w                                        [ASVGF18 Eq. 7]
//        delta^ and Delta^ the same, with the luminance's weights                          [ASVGF18 Eq. 12]
//        Var(l^(k+1)(p)) = sum_q h^2 w^2 Var(l^(k)(q)) / (sum_q h w)^2
//   where h is the 3x3 box [ASVGF18 Sec. 3.4] and w = w_z w_n w_l^(k) [ASVGF18 Eq. 8], SVGF's edge-stopping
//   functions called as they are (filters/svgf/edge_stopping.h) [ASVGF18 Eq. 9-11 = SVGF17 Eq. 3-5].
//
// Choices the paper leaves open (filters/asvgf/README.md, "Deviations and choices"):
// - Strata without a gradient sample stay in the sums with delta = Delta = 0: that is what makes the sample
//   density cancel in lambda's quotient [ASVGF18 Eq. 14]. Strata without a surface are skipped.
// - Eq. 10 has no epsilon (0/0 on a plane facing the camera); SVGF's w_z with its epsilon is used, with p - q
//   converted to pixels (s 2^k per stratum step), since grad z is per pixel.
// - How Var(l^) propagates over the iterations is unstated; SVGF's rule (above) [SVGF17 Sec. 4.3] is used, and
//   w_l reads the 3x3 Gaussian of the variance, as in SVGF [SVGF17 Eq. 5].
// - The centre tap has w = 1, as in SVGF's a-trous (filters/svgf/atrous.cpp says why).
#pragma once

#include "filters/asvgf/gradient_image.h"
#include "filters/probe.h"
#include "filters/svgf/svgf_params.h"

namespace rtdr {

struct GradientPixel {
  float delta = 0.0f, norm = 0.0f, luminance = 0.0f, variance = 0.0f;
};

// The golden per-stratum function: iteration k at stratum (sx, sy). prefiltered_variance is g3x3(Var(l^(k))).
GradientPixel gradient_atrous_pixel(const GradientValues& in, const FloatPlane& prefiltered_variance,
                                    const GradientImage& image, int level, const SvgfParams& params, int sx, int sy,
                                    Probe* probe = nullptr);

// Every stratum of iteration k (parallel over stratum rows, deterministic).
GradientValues gradient_atrous_level(const GradientValues& in, const GradientImage& image, int level,
                                     const SvgfParams& params);

}  // namespace rtdr
