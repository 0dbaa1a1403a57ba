// Shared fixtures of the SVGF pass tests.
#pragma once

#include "filters/surface_planes.h"

namespace rtdr {

// A flat, static G-buffer: one plane facing the camera at `depth` (gradient 0), normal +z, mesh `mesh`, no
// motion. Every depth and normal edge-stopping weight is exactly 1 here: |z_p - z_q| = 0 over 0 + epsilon is 0,
// and (0,0,1).(0,0,1) = 1.
inline SurfacePlanes flat_surface(int w, int h, uint32_t mesh = 0, float depth = 1.0f) {
  SurfacePlanes s;
  s.depth = FloatPlane(w, h, depth);
  s.depth_grad = Vec2Plane(w, h, glm::vec2(0.0f));
  s.normal = RgbPlane(w, h, glm::vec3(0.0f, 0.0f, 1.0f));
  s.mesh = UIntPlane(w, h, mesh);
  s.motion = Vec2Plane(w, h, glm::vec2(0.0f));
  return s;
}

}  // namespace rtdr
