// The Vulkan port of one a-trous level of SVGF, its variance prefilter included: filters/svgf/atrous.comp, run on
// the same planes as atrous_level() (filters/svgf/atrous.h).
//
//   in:  colour c_i, variance Var(c_i), the G-buffer (depth, depth gradient, normal, mesh id), level i, SvgfParams
//        (sigma_z, sigma_n, sigma_l, epsilon, kernel_size 5 or 3)
//   out: AtrousOutput as atrous_level: c_{i+1}, Var(c_{i+1}) and g3x3(Var(c_i))
// Throws rtdr::Error when the planes differ in size or kernel_size is not 5 or 3. The planes must hold finite
// values, as rtdr filter makes sure of its inputs (app/sequence.cpp): the port gives a skipped tap the weight 0
// where the golden level leaves it out, and 0 times a NaN or an infinity is a NaN. Planes travel in the layout of
// filters/svgf/planes_shared.h (accuracy in filters/svgf/atrous_shared.h).
#pragma once

#include "filters/svgf/atrous.h"
#include "gpu/vulkan_context.h"

namespace rtdr {

// One dispatch. Writes its device time in milliseconds to *ms (see ComputePipeline::dispatch).
AtrousOutput atrous_level_vulkan(VulkanContext& context, const RgbPlane& color, const FloatPlane& variance,
                                 const SurfacePlanes& s, int level, const SvgfParams& params, double* ms = nullptr);

}  // namespace rtdr
