// The Vulkan port of A-SVGF's reconstruction of the gradient [ASVGF18 Sec. 3.4, Eq. 7-12]:
// filters/asvgf/gradient_atrous.comp, one dispatch per iteration, run on the same planes as gradient_atrous_level.
//
//   in:  the per-stratum values of the first iteration (delta^, Delta^, l^, Var(l^); the GradientImage's own at
//        k = 0), the strata's geometry and s (the GradientImage), how many iterations and from which k, SVGF's sigmas
//        and epsilon; every plane the grid's size (throws rtdr::Error otherwise, and for a stratum size < 1 or an
//        iteration beyond k = 30)
//   out: what `iterations` calls of gradient_atrous_level (filters/asvgf/gradient_atrous.h) return, levels
//        first_level, first_level + 1, ...: the values of iteration first_level + iterations
// All iterations run in one batch, ping-ponging two value buffers on the device. The bindings:
// filters/asvgf/gradient_atrous_shared.h.
#pragma once

#include "filters/asvgf/gradient_atrous.h"
#include "gpu/vulkan_context.h"

namespace rtdr {

// Writes the iterations' device time in milliseconds, summed, to *ms (see ComputeBatch::total_time).
GradientValues gradient_atrous_vulkan(VulkanContext& context, const GradientValues& in, const GradientImage& image,
                                      const SvgfParams& params, int iterations, int first_level = 0,
                                      double* ms = nullptr);

}  // namespace rtdr
