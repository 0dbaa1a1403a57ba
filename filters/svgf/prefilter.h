// The variance prefilter of SVGF [SVGF17 Sec. 4.4, Eq. 5's g3x3]: a 3x3 Gaussian blur of the luminance variance
// that only steers the luminance edge-stopping weight w_l. "It is not applied to the variance image propagated
// to the next iteration" [SVGF17 Sec. 4.4]: the a-trous (filters/svgf/atrous.cpp) keeps both planes.
// Inputs: the variance plane of one a-trous level. Output: g3x3(Var), same size.
#pragma once

#include "filters/image.h"
#include "filters/probe.h"
#include "filters/svgf/atrous_shared.h"

namespace rtdr {

// The 1D binomial weights (1/4, 1/2, 1/4); the 3x3 kernel is their outer product g(dx) g(dy), which sums to 1.
// The numbers are written once, in atrous_shared.h, which the Vulkan port of the a-trous level includes too.
inline constexpr float kGaussian3[3] = {kPrefilterEdge, kPrefilterCentre, kPrefilterEdge};

// g3x3(Var)(x, y) [SVGF17 Sec. 4.4]: sum over the 3x3 neighbourhood of g(dx) g(dy) Var(x + dx, y + dy), with
// clamped borders (a tap outside the image reads the nearest edge pixel).
float prefilter_variance_pixel(const FloatPlane& variance, int x, int y, Probe* probe = nullptr);

// The whole plane, parallel over rows.
FloatPlane prefilter_variance(const FloatPlane& variance);

}  // namespace rtdr
