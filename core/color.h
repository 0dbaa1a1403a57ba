// Colour helpers for previews and for luminance-based filters. All colours in RTDR are linear
// Rec. 709 / sRGB primaries (scenes/scene.h); these functions turn them into displayable bytes.
#pragma once

#include "core/color_shared.h"
#include "core/demodulation_shared.h"

#include <glm/glm.hpp>

#include <cmath>
#include <cstdint>

namespace rtdr {

// Relative luminance Y of a linear RGB colour. The weights are the Y row of the linear RGB -> XYZ matrix
// for Rec. 709 primaries and a D65 white (IEC 61966-2-1:1999 Sec. 5.2; ITU-R BT.709-6 Item 3.2 lists the
// same three numbers). They sum to 1, so white (1, 1, 1) has luminance 1. The numbers live in
// core/color_shared.h, shared with the GLSL ports.
inline float luminance(const glm::vec3& rgb) {
  return RTDR_LUMINANCE_R * rgb.r + RTDR_LUMINANCE_G * rgb.g + RTDR_LUMINANCE_B * rgb.b;
}

// The sRGB encoding curve (IEC 61966-2-1:1999 Sec. 5.2): a linear segment of slope 12.92 near black,
// then a 1/2.4 power curve offset so the two meet at linear 0.0031308 (encoded 0.04045). Maps [0, 1]
// onto [0, 1]; values outside pass through the matching segment and are clamped later by to_byte.
inline float srgb_encode(float linear) {
  if (linear <= 0.0031308f) return 12.92f * linear;
  return 1.055f * std::pow(linear, 1.0f / 2.4f) - 0.055f;
}

// The inverse: an sRGB-encoded value in [0, 1] back to linear light (IEC 61966-2-1:1999 Sec. 5.2), as
// glTF requires for base colour textures.
inline float srgb_decode(float encoded) {
  if (encoded <= 0.04045f) return encoded / 12.92f;
  return std::pow((encoded + 0.055f) / 1.055f, 2.4f);
}

inline glm::vec3 srgb_encode(const glm::vec3& linear) {
  return {srgb_encode(linear.r), srgb_encode(linear.g), srgb_encode(linear.b)};
}

// An encoded value in [0, 1] -> a byte in [0, 255], rounded to nearest. Values below 0 and NaN give 0
// (a NaN must not become an arbitrary byte), values above 1 give 255.
inline uint8_t to_byte(float encoded) {
  if (!(encoded > 0.0f)) return 0;  // also true for NaN, whose comparisons are all false
  if (encoded >= 1.0f) return 255;
  return uint8_t(encoded * 255.0f + 0.5f);
}

// Demodulation [SVGF17 Sec. 3]: illumination = radiance / albedo, so the filters never blur texture. Where
// an albedo channel is (near) 0 the division is guarded by a floor (as Falcor's SVGF does); remodulation
// multiplies by the same factor, so demodulate-then-remodulate is exact for every albedo.
inline constexpr float kMinDemodulationAlbedo = float(RTDR_MIN_DEMODULATION_ALBEDO);  // core/demodulation_shared.h
inline glm::vec3 demodulation_factor(const glm::vec3& albedo) { return glm::max(albedo, glm::vec3(kMinDemodulationAlbedo)); }

}  // namespace rtdr
