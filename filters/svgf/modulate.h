// Remodulation [SVGF17 Sec. 3]: put the texture back on the filtered illumination.
//
// Pass: remodulate(direct, indirect, albedo, emission) -> colour.
//   in:  filtered demodulated direct and indirect illumination (the a-trous outputs), and the G-buffer's
//        albedo.R/G/B and emission.R/G/B layers of the same frame (docs/buffers.md)
//   out: linear HDR colour = emission + max(albedo, 0.001) * (direct + indirect), ready for tonemap.h
//
// The path tracer divided each pixel's radiance by demodulation_factor(albedo) = max(albedo, 0.001)
// (core/color.h) so the filters never blur texture; this pass multiplies by that same factor, so that
// demodulate-then-remodulate gives the radiance back for every albedo, black channels included. Emission
// seen at the primary hit is not part of the path (trace/README.md): it was never demodulated or
// filtered, and is added here unchanged.
#pragma once

#include "filters/image.h"
#include "filters/probe.h"

#include <glm/glm.hpp>

namespace rtdr {

// The golden per-pixel function: the colour of one pixel from its filtered illumination, albedo and emission.
glm::vec3 remodulate_pixel(const glm::vec3& direct, const glm::vec3& indirect, const glm::vec3& albedo,
                           const glm::vec3& emission, Probe* probe = nullptr);

// remodulate_pixel over a frame. All four planes must have the same size (throws rtdr::Error otherwise).
RgbPlane remodulate(const RgbPlane& direct, const RgbPlane& indirect, const RgbPlane& albedo, const RgbPlane& emission);

}  // namespace rtdr
