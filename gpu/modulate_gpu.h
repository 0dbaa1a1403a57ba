// The Vulkan port of remodulation: filters/svgf/modulate.comp run on the same planes as remodulate().
//
//   in:  direct, indirect, albedo, emission (same size; throws rtdr::Error otherwise)
//   out: colour = emission + max(albedo, 0.001) * (direct + indirect), as remodulate() (filters/svgf/modulate.h)
// Planes travel as colour records (filters/svgf/planes_shared.h).
#pragma once

#include "filters/image.h"
#include "gpu/vulkan_context.h"

namespace rtdr {

// Writes the dispatch's device time in milliseconds to *ms (see ComputePipeline::dispatch).
RgbPlane remodulate_vulkan(VulkanContext& context, const RgbPlane& direct, const RgbPlane& indirect,
                           const RgbPlane& albedo, const RgbPlane& emission, double* ms = nullptr);

}  // namespace rtdr
