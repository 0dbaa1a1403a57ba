// Remodulation [SVGF17 Sec. 3]: colour = emission + max(albedo, 0.001) * (direct + indirect). See modulate.h.
#include "filters/svgf/modulate.h"

#include "core/color.h"
#include "core/error.h"
#include "core/parallel.h"

#include <string>

namespace rtdr {

glm::vec3 remodulate_pixel(const glm::vec3& direct, const glm::vec3& indirect, const glm::vec3& albedo,
                           const glm::vec3& emission, Probe* probe) {
  // The factor the path tracer divided by: albedo floored at 0.001 per channel [SVGF17 Sec. 3; core/color.h].
  const glm::vec3 factor = demodulation_factor(albedo);
  note(probe, "demodulation factor max(albedo, 0.001)", factor, "SVGF17 Sec. 3");
  // The filtered untextured illumination: direct and indirect were filtered apart [SVGF17 Sec. 3].
  const glm::vec3 illumination = direct + indirect;
  note(probe, "illumination direct + indirect", illumination, "SVGF17 Sec. 3");
  // Reapply the texture: "we (re-)modulate the filter output with the surface albedo" [SVGF17 Sec. 3].
  const glm::vec3 reflected = factor * illumination;
  note(probe, "reflected factor * illumination", reflected, "SVGF17 Sec. 3");
  // The primary hit's own emitted radiance, never demodulated nor filtered, is added as it is.
  const glm::vec3 colour = emission + reflected;
  note(probe, "colour emission + reflected", colour, "SVGF17 Sec. 3");
  return colour;
}

RgbPlane remodulate(const RgbPlane& direct, const RgbPlane& indirect, const RgbPlane& albedo,
                    const RgbPlane& emission) {
  const auto same_size = [&](const RgbPlane& p) { return p.width == direct.width && p.height == direct.height; };
  if (!same_size(indirect) || !same_size(albedo) || !same_size(emission))
    throw Error("remodulate: direct, indirect, albedo and emission must have the same size (direct is " +
                std::to_string(direct.width) + "x" + std::to_string(direct.height) + ")");
  RgbPlane colour(direct.width, direct.height);
  parallel_rows(direct.height, [&](int y) {
    for (int x = 0; x < direct.width; ++x)
      colour.at(x, y) = remodulate_pixel(direct.at(x, y), indirect.at(x, y), albedo.at(x, y), emission.at(x, y));
  });
  return colour;
}

}  // namespace rtdr
