// SurfacePlanes from a frame's layers. See surface_planes.h.
#include "filters/surface_planes.h"

namespace rtdr {

SurfacePlanes SurfacePlanes::from_frame(const Frame& frame) {
  SurfacePlanes s;
  s.depth = frame.float_channel("depth.Z");
  s.depth_grad = Vec2Plane(frame.width(), frame.height());
  const FloatPlane& dx = frame.float_channel("depth.dX");
  const FloatPlane& dy = frame.float_channel("depth.dY");
  for (size_t i = 0; i < s.depth_grad.data.size(); ++i) s.depth_grad.data[i] = {dx.data[i], dy.data[i]};
  s.normal = xyz_plane(frame, "normal");
  s.mesh = frame.uint_channel("id.mesh");
  s.motion = xy_plane(frame, "motion");
  return s;
}

}  // namespace rtdr
