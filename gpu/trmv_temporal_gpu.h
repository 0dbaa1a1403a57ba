// The Vulkan port of TRMV's temporal pass [TRMV21 Eq. 2, Sec. 5]: filters/trmv/temporal.comp run on the same planes
// as trmv_temporal_pass().
//
//   in:  c~_i, the current id.mesh, one component's motion (vectors, optional validity, optional re-shaded history),
//        the previous history (empty colour: first frame) with its id.mesh, the optional alpha plane and params
//        (alpha, clamp_gamma, clamp_radius); sizes as trmv_temporal_pass demands (throws rtdr::Error), and
//        clamp_radius >= 0
//   out: cbar_i, the fetched and the clamped history and the alpha used, as trmv_temporal_pass()
//        (filters/trmv/temporal.h)
// Planes travel as colour records, RG32F motion and R32UI ids (filters/svgf/planes_shared.h); the bindings and
// which optional plane rides in which record: filters/trmv/temporal_shared.h.
#pragma once

#include "filters/image.h"
#include "filters/trmv/temporal.h"
#include "filters/trmv/trmv_params.h"
#include "gpu/vulkan_context.h"

namespace rtdr {

// Writes the dispatch's device time in milliseconds to *ms (see ComputePipeline::dispatch).
TrmvTemporalOutput trmv_temporal_vulkan(VulkanContext& context, const RgbPlane& filtered, const UIntPlane& mesh,
                                        const TrmvMotion& motion, const TrmvHistory& prev, const FloatPlane& alpha,
                                        const TrmvParams& params, double* ms = nullptr);

}  // namespace rtdr
