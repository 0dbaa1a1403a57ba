// The Vulkan ports of TRMV's spatial filter [TRMV21 Sec. 5] and clean-up [TRMV21 Sec. 5, Eq. 7-8]:
// filters/trmv/spatial.comp (one 1-D pass of the joint bilateral, dispatched horizontally, then vertically) and
// filters/trmv/cleanup.comp (w_A, w_C and the std), run on the same planes as trmv_spatial_pass() and
// trmv_cleanup_pass().
//
//   in:  the RGB plane to filter (visibility travels as (V, V, V)), the current G-buffer planes, the radius and std
//        (or a std per pixel and axis), TrmvParams (alpha, cleanup_size, cleanup_eps, cleanup_sigma_max) and SVGF's
//        edge-stopping parameters; the clean-up also the temporal pass's output (cbar_i, the fetched and the
//        clamped history) and alpha^V (empty: alpha everywhere). Sizes as the golden passes demand (throws
//        rtdr::Error), and radii >= 0.
//   out: as trmv_spatial_pass() (filters/trmv/spatial.h) and trmv_cleanup_pass() (filters/trmv/cleanup.h)
// Planes travel as colour records (r, g, b, std), surface records and RG32F depth gradients
// (filters/svgf/planes_shared.h); the bindings: filters/trmv/spatial_shared.h and filters/trmv/cleanup_shared.h.
#pragma once

#include "filters/image.h"
#include "filters/surface_planes.h"
#include "filters/svgf/svgf_params.h"
#include "filters/trmv/cleanup.h"
#include "filters/trmv/temporal.h"
#include "filters/trmv/trmv_params.h"
#include "gpu/vulkan_context.h"

namespace rtdr {

// Write the dispatches' device time in milliseconds to *ms (see ComputePipeline::dispatch). With sigma_x and
// sigma_y given (not empty), each pixel's std per axis (the penumbra filter), else `sigma` everywhere.
RgbPlane trmv_spatial_vulkan(VulkanContext& context, const RgbPlane& c, const SurfacePlanes& s, int radius,
                             float sigma, const SvgfParams& edges, double* ms = nullptr,
                             const FloatPlane& sigma_x = {}, const FloatPlane& sigma_y = {});

TrmvCleanupOutput trmv_cleanup_vulkan(VulkanContext& context, const TrmvTemporalOutput& temporal,
                                      const FloatPlane& alpha_v, const SurfacePlanes& s, const TrmvParams& params,
                                      const SvgfParams& edges, double* ms = nullptr);

}  // namespace rtdr
