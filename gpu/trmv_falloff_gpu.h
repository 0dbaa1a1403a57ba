// The Vulkan port of TRMV's non-planar receiver falloff [TRMV21 Eq. 4]: filters/trmv/falloff.comp run on the same
// planes as trmv_falloff_pass().
//
//   in:  the receiver (s_i, n(s_i), id.mesh, the surface motion), the shadow motion (vectors m^V, optional
//        validity; the test and re-shaded planes are not read), the previous frame's positions with their geonormals
//        and id.mesh (empty: first frame) and params (alpha, falloff_sigma, falloff_carry); sizes as
//        trmv_falloff_pass demands (throws rtdr::Error)
//   out: theta and alpha^V, as trmv_falloff_pass() (filters/trmv/falloff.h)
// Planes travel as (x, y, z, 0) records, RG32F motion and R32UI ids (filters/svgf/planes_shared.h); the bindings:
// filters/trmv/falloff_shared.h.
#pragma once

#include "filters/trmv/falloff.h"
#include "filters/trmv/temporal.h"
#include "filters/trmv/trmv_params.h"
#include "gpu/vulkan_context.h"

namespace rtdr {

// Writes the dispatch's device time in milliseconds to *ms (see ComputePipeline::dispatch).
TrmvFalloffOutput trmv_falloff_vulkan(VulkanContext& context, const TrmvReceiver& receiver, const TrmvMotion& shadow,
                                      const TrmvPreviousPositions& prev, const TrmvParams& params,
                                      double* ms = nullptr);

}  // namespace rtdr
