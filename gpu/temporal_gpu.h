// The Vulkan port of SVGF temporal accumulation: filters/svgf/temporal.comp run on the same planes as
// temporal_pass().
//
//   in:  the noisy colour C_i, the current G-buffer planes (depth, depth_grad, normal, mesh, motion), the
//        previous frame's history (empty colour: first frame) and params (alpha, alpha_moments, max_history,
//        temporal_depth_relative, temporal_normal_cosine), and optionally A-SVGF's TemporalAdaptive (lambda,
//        alpha_i and alpha_mu_i per pixel, the history rule; one set serves both streams here); sizes as
//        temporal_pass demands
//        (throws rtdr::Error)
//   out: C'_i, mu1'_i, mu2'_i, n_i, as temporal_pass() (filters/svgf/temporal.h)
// Planes travel in the layout of filters/svgf/planes_shared.h (bindings in filters/svgf/temporal_shared.h).
#pragma once

#include "filters/image.h"
#include "filters/svgf/svgf_params.h"
#include "filters/surface_planes.h"
#include "filters/svgf/temporal.h"
#include "gpu/vulkan_context.h"

namespace rtdr {

// Writes the dispatch's device time in milliseconds to *ms (see ComputePipeline::dispatch).
TemporalOutput temporal_vulkan(VulkanContext& context, const RgbPlane& noisy, const SurfacePlanes& cur,
                               const TemporalHistory& prev, const SvgfParams& params, double* ms = nullptr,
                               const TemporalAdaptive* adaptive = nullptr);

}  // namespace rtdr
