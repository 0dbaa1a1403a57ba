// The Vulkan port of TRMV's dual motion vector [TRMV21 Eq. 6]: motion/dual.comp run on the same inputs as
// dual_motion().
//
// dual_motion_vulkan
//   in:  the Scene, a frame's geometry (both poses and Views, this frame's visibility buffer) and its `motion`
//        layer, row-major; throws rtdr::Error for a motion plane that is not the frame's size, as dual_motion does
//   out: every pixel's DualMotion, row-major, as dual_motion() (motion/dual.h)
// What needs the scene's triangles runs here, on the host, with the golden code: the previous visibility buffer
// (previous_visibility) and each sample's object-space point (object_point). The shader carries those points with
// the instances' transforms, projects them with the two Views and makes every decision of Eq. 6. Planes travel as
// (x, y, z, w) records, RG32F motion and R32UI ids (filters/svgf/planes_shared.h); the bindings:
// motion/dual_shared.h.
#pragma once

#include "gpu/vulkan_context.h"
#include "motion/dual.h"
#include "raster/gbuffer_frame.h"
#include "scenes/scene.h"

#include <glm/glm.hpp>

#include <vector>

namespace rtdr {

// Writes its dispatch's device time in milliseconds to *ms (see ComputeBatch::total_time).
std::vector<DualMotion> dual_motion_vulkan(VulkanContext& context, const Scene& scene, const FrameGeometry& geometry,
                                           const std::vector<glm::vec2>& surface_motion, double* ms = nullptr);

}  // namespace rtdr
