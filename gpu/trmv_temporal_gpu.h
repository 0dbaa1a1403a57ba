// The Vulkan port of TRMV's temporal pass [TRMV21 Eq. 2, Sec. 5]: filters/trmv/temporal.comp run on the same planes
// as trmv_temporal_pass().
//
//   in:  c~_i, the current G-buffer, one component's motion (vectors, optional validity and history tests, optional
//        re-shaded history), the previous history (empty colour: first frame) with its G-buffer, the optional alpha
//        plane, params (alpha, clamp_gamma, clamp_radius, history_test) and SVGF's consistency thresholds; sizes as
//        trmv_temporal_pass demands (throws rtdr::Error), and clamp_radius >= 0
//   out: cbar_i, the fetched and the clamped history and the alpha used, as trmv_temporal_pass()
//        (filters/trmv/temporal.h)
// Planes travel as colour records, (n, z) surface records, RG32F gradients and R32UI ids
// (filters/svgf/planes_shared.h); the bindings and which optional plane rides in which record:
// filters/trmv/temporal_shared.h.
#pragma once

#include "filters/image.h"
#include "filters/surface_planes.h"
#include "filters/svgf/svgf_params.h"
#include "filters/trmv/temporal.h"
#include "filters/trmv/trmv_params.h"
#include "gpu/compute.h"
#include "gpu/vulkan_context.h"

namespace rtdr {

// Writes the dispatch's device time in milliseconds to *ms (see ComputePipeline::dispatch).
TrmvTemporalOutput trmv_temporal_vulkan(VulkanContext& context, const RgbPlane& filtered, const SurfacePlanes& cur,
                                        const TrmvMotion& motion, const TrmvHistory& prev, const FloatPlane& alpha,
                                        const TrmvParams& params, const SvgfParams& svgf, double* ms = nullptr);

// The motion's (m, code) records: code 0 where the vector is not valid, else 1 + its history test
// (temporal_shared.h, binding 4).
void pack_trmv_vector(const TrmvMotion& motion, GpuBuffer& out);
// The re-shaded history's records: (r, g, b, 1 where it is valid, else 0) (binding 5).
void pack_trmv_reshaded(const TrmvMotion& motion, GpuBuffer& out);

}  // namespace rtdr
