// The Vulkan port of TRMV's splat of shadow motion vectors [TRMV21 Sec. 4.1]: filters/trmv/splat.comp run on the
// same planes as trmv_splat_pass().
//
//   in:  the splat's planes (TrmvSplatPlanes: m^V and its validity, the surface motion, id.instance, the normal and
//        an optional carried property) and the window's side; throws rtdr::Error as trmv_splat_pass does
//   out: the splatted motion, where a vector landed and the carried mean, as trmv_splat_pass() (filters/trmv/splat.h)
// Planes travel as (x, y, z, w) records and R32UI ids (filters/svgf/planes_shared.h); the bindings:
// filters/trmv/splat_shared.h.
#pragma once

#include "filters/trmv/splat.h"
#include "gpu/compute.h"
#include "gpu/vulkan_context.h"

namespace rtdr {

// Writes the dispatch's device time in milliseconds to *ms (see ComputeBatch::total_time).
TrmvSplatOutput trmv_splat_vulkan(VulkanContext& context, const TrmvSplatPlanes& planes, int size,
                                  double* ms = nullptr);

// Packs the splat's planes into the port's records (the first three for trmv_splat_vulkan and the method's batch).
void pack_trmv_splat(const TrmvSplatPlanes& planes, GpuBuffer& shadow, GpuBuffer& surface_motion, GpuBuffer& normal);

}  // namespace rtdr
