// The Vulkan port of SVGF variance estimation: filters/svgf/variance.comp run on the same planes as variance_pass().
//
//   in:  the temporal pass's output t (moment1, moment2, length) and the current G-buffer planes (depth,
//        depth_grad, normal, mesh), all the same size (throws rtdr::Error otherwise); sigma_z, sigma_n, epsilon,
//        variance_min_history from params
//   out: sigma'^2 per pixel, as variance_pass() (filters/svgf/variance.h); 0 where no surface
// Planes travel in the layout of filters/svgf/planes_shared.h (bindings in filters/svgf/variance_shared.h).
#pragma once

#include "filters/image.h"
#include "filters/svgf/svgf_params.h"
#include "filters/surface_planes.h"
#include "filters/svgf/temporal.h"
#include "gpu/vulkan_context.h"

namespace rtdr {

// Writes the dispatch's device time in milliseconds to *ms (see ComputePipeline::dispatch).
FloatPlane variance_vulkan(VulkanContext& context, const TemporalOutput& t, const SurfacePlanes& cur,
                           const SvgfParams& params, double* ms = nullptr);

}  // namespace rtdr
