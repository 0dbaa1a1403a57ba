// The Vulkan ports of TRMV's shadow motion vector [TRMV21 Eq. 3] and of its splat [TRMV21 Sec. 4.1]:
// motion/shadow.comp and motion/shadow_splat.comp run on the same inputs as shadow_motion() and
// splat_shadow_motion().
//
// shadow_motion_vulkan
//   in:  a rendered frame's path.light.X/Y/Z, path.blocker.X/Y/Z, position.X/Y/Z, geonormal.X/Y/Z,
//        path.light.instance, path.blocker.instance and id.instance (ShadowRayLayers), and its geometry's poses
//        (each instance's T^{-1}, instance_to_previous) and Views; throws rtdr::Error naming a missing channel, or
//        for a frame that is not the geometry's size, as shadow_motion does
//   out: every pixel's ShadowMotion, row-major, as shadow_motion() (motion/shadow.h)
// splat_shadow_motion_vulkan
//   in:  the shadow motion, the surface motion and the depth, width x height, and the window's side; throws
//        rtdr::Error as splat_shadow_motion does
//   out: every pixel's SplatMotion, row-major, as splat_shadow_motion() (motion/shadow_splat.h)
// Planes travel as (x, y, z, 0) records and R32UI ids (filters/svgf/planes_shared.h); the bindings:
// motion/shadow_shared.h and motion/shadow_splat_shared.h.
#pragma once

#include "core/frame.h"
#include "gpu/vulkan_context.h"
#include "motion/shadow.h"
#include "motion/shadow_splat.h"
#include "raster/gbuffer_frame.h"

#include <glm/glm.hpp>

#include <vector>

namespace rtdr {

// Each writes its dispatch's device time in milliseconds to *ms (see ComputeBatch::total_time).
std::vector<ShadowMotion> shadow_motion_vulkan(VulkanContext& context, const FrameGeometry& geometry,
                                               const Frame& frame, double* ms = nullptr);
std::vector<SplatMotion> splat_shadow_motion_vulkan(VulkanContext& context, const std::vector<ShadowMotion>& shadow,
                                                    const std::vector<glm::vec2>& surface_motion,
                                                    const std::vector<float>& depth, int width, int height, int size,
                                                    double* ms = nullptr);

}  // namespace rtdr
