// The Vulkan port of TRMV's shadow motion vector [TRMV21 Eq. 3]: motion/shadow.comp run on the same inputs as
// shadow_motion(). (Its splat [TRMV21 Sec. 4.1] is the filter's: gpu/trmv_splat_gpu.h.)
//
// shadow_motion_vulkan
//   in:  a rendered frame's path.light.X/Y/Z, path.blocker.X/Y/Z, position.X/Y/Z, geonormal.X/Y/Z,
//        path.light.instance, path.blocker.instance and id.instance (ShadowRayLayers), and its geometry's poses
//        (each instance's T^{-1}, instance_to_previous) and Views; throws rtdr::Error naming a missing channel, or
//        for a frame that is not the geometry's size, as shadow_motion does
//   out: every pixel's ShadowMotion, row-major, as shadow_motion() (motion/shadow.h)
// Planes travel as (x, y, z, 0) records and R32UI ids (filters/svgf/planes_shared.h); the bindings:
// motion/shadow_shared.h.
#pragma once

#include "core/frame.h"
#include "gpu/vulkan_context.h"
#include "motion/shadow.h"
#include "raster/gbuffer_frame.h"

#include <glm/glm.hpp>

#include <vector>

namespace rtdr {

// Writes its dispatch's device time in milliseconds to *ms (see ComputeBatch::total_time).
std::vector<ShadowMotion> shadow_motion_vulkan(VulkanContext& context, const FrameGeometry& geometry,
                                               const Frame& frame, double* ms = nullptr);

}  // namespace rtdr
