// The G-buffer planes the filters read: what SVGF's consistency tests and edge-stopping functions compare, and
// what EAW and TAA read too. (C++ only: a *_shared.h file is one that C++ and GLSL both include.)
#pragma once

#include "filters/image.h"

namespace rtdr {

// The noise-free surface attributes of one frame, from its G-buffer layers (docs/buffers.md).
struct SurfacePlanes {
  FloatPlane depth;       // depth.Z: linear view depth, 0 where no surface
  Vec2Plane depth_grad;   // depth.dX, depth.dY: d depth / d screen position [SVGF17 Eq. 3's grad z]
  RgbPlane normal;        // normal.X/Y/Z: world-space shading normal
  UIntPlane mesh;         // id.mesh: kInvalidId where no surface
  Vec2Plane motion;       // motion.X/Y: previous screen position minus pixel centre [TRMV21 Eq. 1]

  int width() const { return depth.width; }
  int height() const { return depth.height; }
  bool covered(int x, int y) const { return mesh.at(x, y) != kInvalidId; }

  // Reads the layers; throws rtdr::Error naming the first missing one.
  static SurfacePlanes from_frame(const Frame& frame);
};

}  // namespace rtdr
