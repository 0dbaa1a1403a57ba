// The image types the golden passes read and write: planes of one value per pixel (core/frame.h's Plane),
// row-major, y down. Colours are linear RGB; "luminance" is Rec. 709 Y (core/color.h).
// Illumination planes hold demodulated radiance, divided by the albedo [SVGF17 Sec. 3].
#pragma once

#include "core/frame.h"

#include <glm/glm.hpp>

namespace rtdr {

using RgbPlane = Plane<glm::vec3>;
using Vec2Plane = Plane<glm::vec2>;

// Clamped access: the pixel at (x, y) with x, y clamped into the image. Filters never read outside.
template <class T>
const T& at_clamped(const Plane<T>& p, int x, int y) {
  x = x < 0 ? 0 : (x >= p.width ? p.width - 1 : x);
  y = y < 0 ? 0 : (y >= p.height ? p.height - 1 : y);
  return p.at(x, y);
}

inline bool inside(const auto& p, int x, int y) { return x >= 0 && y >= 0 && x < p.width && y < p.height; }

// Whether plane p is w x h; and whether it is w x h or empty (width 0), which a pass reads as "not given".
inline bool has_size(const auto& p, int w, int h) { return p.width == w && p.height == h; }
inline bool empty_or_size(const auto& p, int w, int h) { return p.width == 0 || has_size(p, w, h); }

// Frame layers <-> planes: "direct" <-> direct.R/G/B, "normal" <-> normal.X/Y/Z (see docs/buffers.md).
RgbPlane rgb_plane(const Frame& frame, const std::string& layer);
RgbPlane xyz_plane(const Frame& frame, const std::string& layer);
Vec2Plane xy_plane(const Frame& frame, const std::string& layer);
void set_rgb_plane(Frame& frame, const std::string& layer, const RgbPlane& plane);
void set_float_plane(Frame& frame, const std::string& channel, const FloatPlane& plane);

}  // namespace rtdr
