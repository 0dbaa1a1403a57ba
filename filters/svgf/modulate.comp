// Remodulation [SVGF17 Sec. 3], the Vulkan port of remodulate_pixel (modulate.cpp), line for line:
// colour = emission + max(albedo, 0.001) * (direct + indirect). One invocation per pixel.
//   in:  bindings 0-3: direct, indirect, albedo, emission; out: binding 4: colour. Layout: modulate_shared.h.
#version 450
#extension GL_GOOGLE_include_directive : require

#include "filters/svgf/modulate_shared.h"

layout(local_size_x = kModulateGroupSizeX, local_size_y = kModulateGroupSizeY) in;

layout(std430, set = 0, binding = 0) readonly buffer Direct { float direct_rgb[]; };
layout(std430, set = 0, binding = 1) readonly buffer Indirect { float indirect_rgb[]; };
layout(std430, set = 0, binding = 2) readonly buffer Albedo { float albedo_rgb[]; };
layout(std430, set = 0, binding = 3) readonly buffer Emission { float emission_rgb[]; };
layout(std430, set = 0, binding = 4) writeonly buffer Colour { float colour_rgb[]; };

layout(push_constant) uniform Push { ModulatePush frame; };

vec3 remodulate_pixel(vec3 direct, vec3 indirect, vec3 albedo, vec3 emission) {
  // The factor the path tracer divided by: albedo floored at 0.001 per channel [SVGF17 Sec. 3; core/color.h].
  const vec3 factor = max(albedo, vec3(kModulateMinAlbedo));
  // The filtered untextured illumination: direct and indirect were filtered apart [SVGF17 Sec. 3].
  const vec3 illumination = direct + indirect;
  // Reapply the texture: "we (re-)modulate the filter output with the surface albedo" [SVGF17 Sec. 3].
  // GPU only: `precise` forbids fusing this product and the sum below into one fma, so the port rounds
  // twice, as the golden function does.
  precise vec3 reflected = factor * illumination;
  // The primary hit's own emitted radiance, never demodulated nor filtered, is added as it is.
  precise vec3 colour = emission + reflected;
  return colour;
}

void main() {
  // This invocation's pixel; the last tiles overhang the frame.
  const uvec2 pixel = gl_GlobalInvocationID.xy;
  if (pixel.x >= frame.width || pixel.y >= frame.height) return;
  // The pixel's first float: 3 floats (R, G, B) per pixel, row-major (modulate_shared.h).
  const uint i = 3u * (pixel.y * frame.width + pixel.x);
  const vec3 direct = vec3(direct_rgb[i], direct_rgb[i + 1u], direct_rgb[i + 2u]);
  const vec3 indirect = vec3(indirect_rgb[i], indirect_rgb[i + 1u], indirect_rgb[i + 2u]);
  const vec3 albedo = vec3(albedo_rgb[i], albedo_rgb[i + 1u], albedo_rgb[i + 2u]);
  const vec3 emission = vec3(emission_rgb[i], emission_rgb[i + 1u], emission_rgb[i + 2u]);
  const vec3 colour = remodulate_pixel(direct, indirect, albedo, emission);
  colour_rgb[i] = colour.r;
  colour_rgb[i + 1u] = colour.g;
  colour_rgb[i + 2u] = colour.b;
}
