#include "filters/image.h"

namespace rtdr {
namespace {

template <class V>
Plane<V> from_vectors(const Frame& frame, const std::vector<V>& values) {
  Plane<V> p(frame.width(), frame.height());
  p.data = values;
  return p;
}

}  // namespace

RgbPlane rgb_plane(const Frame& frame, const std::string& layer) { return from_vectors(frame, frame.get_rgb(layer)); }
RgbPlane xyz_plane(const Frame& frame, const std::string& layer) { return from_vectors(frame, frame.get_vec3(layer)); }
Vec2Plane xy_plane(const Frame& frame, const std::string& layer) { return from_vectors(frame, frame.get_vec2(layer)); }

void set_rgb_plane(Frame& frame, const std::string& layer, const RgbPlane& plane) { frame.set_rgb(layer, plane.data); }

void set_float_plane(Frame& frame, const std::string& channel, const FloatPlane& plane) {
  frame.add_float(channel).data = plane.data;
}

}  // namespace rtdr
