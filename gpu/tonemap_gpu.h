// The Vulkan port of tone mapping: filters/svgf/tonemap.comp run on the same plane as tonemap().
//
//   in:  linear HDR colour (remodulate's output), TonemapParams (validated; throws rtdr::Error when out of range)
//   out: display colour in [0, 1], as tonemap() (filters/svgf/tonemap.h)
// Planes travel as colour records (filters/svgf/planes_shared.h).
#pragma once

#include "filters/image.h"
#include "filters/svgf/tonemap.h"
#include "gpu/vulkan_context.h"

namespace rtdr {

// Writes the dispatch's device time in milliseconds to *ms (see ComputePipeline::dispatch).
RgbPlane tonemap_vulkan(VulkanContext& context, const RgbPlane& colour, const TonemapParams& params,
                        double* ms = nullptr);

}  // namespace rtdr
