// Dual motion vectors for disocclusions [TRMV21 Eq. 6, Sec. 4.3]: where a pixel that was hidden in the
// previous frame can find history that looks like it.
//
// Pass: dual_motion(scene, geometry) -> motion.dual per pixel.
//   in:  this frame's visibility buffer, the previous frame's (rasterized here from the previous pose and View,
//        so every frame stays an independent job), both poses and Views
//   out: motion.dual = x^O_{i-1} - x_i in pixels, and motion.dual.valid (1 where the pixel was disoccluded and
//        Eq. 6 replaced the surface motion)
//
// A pixel that a moving box has just uncovered has no history: its back-projection y lands on the box, which
// stood in front of it in frame i-1 (Fig. 5 of the paper). TRMV21 Eq. 6 looks elsewhere:
//
//   x^O_{i-1} = y + (x_i - z),   y = P_{i-1} T^{-1}(x_i) P_i^{-1} x_i,   z = P_i T(y) P_{i-1}^{-1} y
//
// y is the ordinary back-projection (the `motion` layer: y = x_i + motion). z is the occluder's point seen at y,
// carried forward with the OCCLUDER's motion T(y). So z - y is the occluder's screen motion v, and
// x^O = x_i - v: from where the pixel is now, step back by what the occluder did. Where the occluder translates,
// the background at x_i stood as far behind the occluder's trailing edge as x^O does in frame i-1: it lies
// next to the occluder then, on whatever surface was there (the wall, the floor, the other box), never on the
// occluder that uncovered the pixel (tests/motion_dual_test.cpp). Copying history from there repeats that
// surface's look ("the bunny will simply be repeated", Fig. 6), which the cones of Sec. 4.3 soften
// (filters/trmv/cones.h).
//
// Choices (motion/README.md, "Dual motion: the choices"):
// - Disoccluded: the current surface point, carried back to frame i-1 with its own instance's motion, lies
//   behind what the previous visibility buffer shows at floor(y): its previous depth is beyond the visible
//   depth there by more than the forward projection's tolerance (kForwardProjectionDepthTolerance, 1 %, the
//   same sub-pixel argument). That is the paper's "visible now but occluded in the previous frame", decided
//   from the geometry itself rather than from SVGF's filter-side consistency test.
// - The occluder's sample at y is the previous visibility buffer's sample at floor(y), the nearest pixel. Its
//   exact point is at y' = P_{i-1}(its previous position), a fraction of a pixel from y; we take v from that
//   point, v = z - y', so x^O = y - v. For an occluder whose screen motion is locally constant (translation, a
//   fraction of a pixel apart) this is Eq. 6; using z - y instead would add the sub-pixel offset y - y' to
//   every vector.
// - Not disoccluded (including y off screen, where the surface came in at the border rather than from behind
//   something, and y behind the previous camera): x^O = y, the surface motion, and .valid is 0.
// - Where the occluder's point is behind the current camera (it left through the near plane), z is undefined:
//   x^O = y, .valid 0.
#pragma once

#include "core/frame.h"
#include "raster/gbuffer_frame.h"
#include "raster/visibility.h"
#include "scenes/scene.h"

#include <glm/glm.hpp>

#include <vector>

namespace rtdr {

struct DualMotion {
  glm::vec2 motion{0.0f};  // x^O_{i-1} - x_i, pixels; the surface motion where the pixel was not disoccluded
  bool disoccluded = false;  // Eq. 6 applied (motion.dual.valid)
};

// The golden per-pixel function [TRMV21 Eq. 6] for pixel (x, y) of `geometry`, whose back-projected motion is
// `surface_motion` (the `motion` layer), against the previous visibility buffer `prev_vis`.
DualMotion dual_motion_pixel(const Scene& scene, const FrameGeometry& geometry, const VisibilityBuffer& prev_vis,
                             int x, int y, glm::vec2 surface_motion);

// The previous frame's visibility buffer, rasterized from geometry's previous pose and View.
VisibilityBuffer previous_visibility(const Scene& scene, const FrameGeometry& geometry);

// Every pixel's dual motion, row-major; `surface_motion` is the `motion` layer of the same frame.
std::vector<DualMotion> dual_motion(const Scene& scene, const FrameGeometry& geometry,
                                    const std::vector<glm::vec2>& surface_motion);

// Adds motion.dual.X, motion.dual.Y and motion.dual.valid (uint 0/1) to a frame that holds `motion`.
void write_dual_motion_layers(const Scene& scene, const FrameGeometry& geometry, Frame& frame);

}  // namespace rtdr
