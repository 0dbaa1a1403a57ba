// Back-projected motion vectors [TRMV21 Eq. 1]: where each pixel's surface point was in the previous frame.
//
// Pass: backproject_motion(scene, prev_pose, prev_view, cur_vis) -> motion per pixel.
//   in:  the current visibility buffer; the Scene's pose and View of the PREVIOUS frame
//   out: motion = x_{i-1} - x_i in pixels, layer motion.X / motion.Y (write_motion)
//
// TRMV21 Eq. 1 writes x_{i-1} = P_{i-1} T^{-1} P_i^{-1} x_i. With a visibility buffer, P_i^{-1} x_i is known
// exactly as a point on one triangle: its object-space point (object_point in raster/visibility.h) does not
// move with the instance, so T^{-1} P_i^{-1} x_i is that point under the instance's PREVIOUS transform, and
// P_{i-1} is the previous View's projection. Nothing of the current pose is needed.
//
// Sign convention: motion = previous screen position - current pixel centre, so the content at pixel centre
// p was at p + motion in the previous frame (TRMV21's m(x_i) = x_{i-1} - x_i; y down as everywhere).
// Both positions are in their own View's jittered screen: subtract (prev jitter - current jitter) for the
// jitter-free motion. Where no surface is seen the motion is (0, 0). Where the point was behind the previous
// camera (previous depth < znear) it has no previous screen position; the motion is then
// (kMotionBehindCamera, kMotionBehindCamera), which puts p + motion far off any screen.
#pragma once

#include "core/frame.h"
#include "raster/gbuffer_frame.h"
#include "raster/view.h"
#include "raster/visibility.h"
#include "scenes/scene.h"

#include <glm/glm.hpp>

#include <vector>

namespace rtdr {

inline constexpr float kMotionBehindCamera = 1.0e6f;

// The golden per-pixel function: the motion of the surface sample seen at screen position `pixel_centre`.
glm::vec2 backproject_pixel(const Scene& scene, const ScenePose& prev_pose, const View& prev_view,
                            const SurfaceSample& sample, glm::vec2 pixel_centre);

// Motion of every pixel of cur_vis, row-major; (0, 0) where no surface.
std::vector<glm::vec2> backproject_motion(const Scene& scene, const ScenePose& prev_pose, const View& prev_view,
                                          const VisibilityBuffer& cur_vis);

// Writes the motion as the float channels motion.X and motion.Y. The frame must have the buffer's size.
void write_motion(const std::vector<glm::vec2>& motion, Frame& frame);

// The motion layers of one frame of `rtdr render`: every pixel of geometry.vis back-projected to the
// previous frame's pose and View, written by write_motion.
void write_motion_layers(const Scene& scene, const FrameGeometry& geometry, Frame& frame);

}  // namespace rtdr
