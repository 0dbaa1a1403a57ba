// Forward projection of a previous frame's surface sample into the current frame [ASVGF18 Sec. 3.1, 3.3].
//
// Pass (per sample; A-SVGF's gradient sampling picks one sample per 3x3 stratum and calls this):
//   in:  a SurfaceSample from the PREVIOUS visibility buffer; the Scene's CURRENT pose and View; the CURRENT
//        visibility buffer (for its depth)
//   out: where the same surface point is now: continuous screen position, receiving pixel, depth, and
//        whether the current depth buffer hides it.
//
// A visibility-buffer sample names an exact point on a triangle (instance, triangle, barycentrics), so
// carrying it forward needs no search: re-evaluate the same point at the current pose (world_point in
// raster/visibility.h) and project it with the current View [ASVGF18 Sec. 3.1]. Samples that the current
// depth buffer shows to be occluded are discarded by the caller [ASVGF18 Sec. 3.3].
#pragma once

#include "motion/forward_project_shared.h"
#include "raster/view.h"
#include "raster/visibility.h"
#include "scenes/scene.h"

#include <glm/glm.hpp>

namespace rtdr {

// kForwardProjectionDepthTolerance, the occlusion test's relative depth tolerance (1 %, and why): written once,
// for the C++ and the shaders, in motion/forward_project_shared.h.

struct ForwardProjection {
  bool on_screen = false;   // in front of the near plane and inside [0, width) x [0, height)
  glm::ivec2 pixel{-1, -1}; // the current pixel that receives it: floor(screen); (-1, -1) when off screen
  glm::vec2 screen{0.0f};   // continuous screen position at the current time (pixel centres at +0.5)
  float depth = 0.0f;       // linear view depth at the current time
  bool occluded = false;    // on screen and the current depth at `pixel` is nearer than depth (1 - tolerance);
                            // false where the current pixel sees no surface (depth 0)
};

ForwardProjection forward_project(const Scene& scene, const ScenePose& cur_pose, const View& cur_view,
                                  const VisibilityBuffer& cur_vis, const SurfaceSample& prev_sample,
                                  float depth_tolerance = kForwardProjectionDepthTolerance);

}  // namespace rtdr
