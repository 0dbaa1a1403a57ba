// The Vulkan port of TRMV's glossy motion vector [TRMV21 Eq. 5]: motion/glossy.comp run on the same inputs as
// glossy_motion().
//
// glossy_motion_vulkan
//   in:  a rendered frame's path.secondary.X/Y/Z and .instance, rng.seed, position.X/Y/Z, geonormal.X/Y/Z,
//        id.instance and material.roughness (GlossyRayLayers), and its geometry's poses (each instance's T^{-1},
//        instance_to_previous) and Views; throws rtdr::Error naming a missing channel, or for a frame that is not
//        the geometry's size, as glossy_motion does
//   out: every pixel's GlossyMotion, row-major, as glossy_motion() (motion/glossy.h); Sigma = a1 a1^T + a2 a2^T
//        is made here from the shader's a1 and a2, as the golden pass makes it
// Planes travel as (x, y, z, w) records and R32UI ids (filters/svgf/planes_shared.h); the bindings:
// motion/glossy_shared.h.
#pragma once

#include "core/frame.h"
#include "gpu/vulkan_context.h"
#include "motion/glossy.h"
#include "raster/gbuffer_frame.h"

#include <vector>

namespace rtdr {

// Writes its dispatch's device time in milliseconds to *ms (see ComputeBatch::total_time).
std::vector<GlossyMotion> glossy_motion_vulkan(VulkanContext& context, const FrameGeometry& geometry,
                                               const Frame& frame, double* ms = nullptr);

}  // namespace rtdr
