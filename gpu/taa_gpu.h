// The Vulkan port of TAA: filters/taa/taa.comp run on the same planes as taa_pass().
//
//   in:  current display colour, history (current's size, or empty: width 0), motion (current's size), TaaParams
//        (validated), TaaJitter; throws rtdr::Error on a size mismatch or a parameter out of range, as taa_pass()
//   out: the antialiased colour, as taa_pass() (filters/taa/taa.h)
// Planes travel as colour records and RG32F motion (filters/svgf/planes_shared.h).
#pragma once

#include "filters/image.h"
#include "filters/taa/taa.h"
#include "gpu/vulkan_context.h"

namespace rtdr {

// Writes the dispatch's device time in milliseconds to *ms (see ComputePipeline::dispatch).
RgbPlane taa_vulkan(VulkanContext& context, const RgbPlane& current, const RgbPlane& history, const Vec2Plane& motion,
                    const TaaParams& params, const TaaJitter& jitter = {}, double* ms = nullptr);

}  // namespace rtdr
