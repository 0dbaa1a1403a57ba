// The Vulkan port of A-SVGF's adaptive temporal weight [ASVGF18 Sec. 3.5, Eq. 14-15]: filters/asvgf/adaptive_alpha.comp
// run on the same planes as adaptive_alpha_pass().
//
//   in:  the reconstructed delta^ and Delta^ per stratum (GradientValues; luminance and variance are not read), the
//        stratum size s (>= 1), the frame's width x height, and AdaptiveAlphaParams (the base alpha and alpha_mu, the
//        radius of the maximum, >= 0); delta^ and Delta^ of one size (throws rtdr::Error otherwise)
//   out: lambda per stratum, lambda_max, alpha_i and alpha_mu_i per pixel, as adaptive_alpha_pass()
//        (filters/asvgf/adaptive_alpha.h)
// The bindings: filters/asvgf/adaptive_alpha_shared.h.
#pragma once

#include "filters/asvgf/adaptive_alpha.h"
#include "gpu/vulkan_context.h"

namespace rtdr {

// Writes the dispatch's device time in milliseconds to *ms (see ComputePipeline::dispatch).
AdaptiveAlpha adaptive_alpha_vulkan(VulkanContext& context, const GradientValues& reconstructed, int s, int width,
                                    int height, const AdaptiveAlphaParams& params, double* ms = nullptr);

}  // namespace rtdr
