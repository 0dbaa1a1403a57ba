// Remodulation [SVGF17 Sec. 3], the Vulkan port of remodulate_pixel (modulate.cpp), line for line:
// colour = emission + max(albedo, 0.001) * (direct + indirect). One invocation per pixel.
//   in:  bindings 0: direct and indirect (illumination records: the last a-trous level's), 1-2: albedo, emission
//        (colour records); out: binding 3: colour. Layout: planes_shared.h, modulate_shared.h.
#version 450
#extension GL_GOOGLE_include_directive : require

#include "filters/svgf/modulate_shared.h"

// The workgroup's shape, per device (planes_shared.h).
layout(local_size_x_id = kSvgfGroupSizeXConstant, local_size_y_id = kSvgfGroupSizeYConstant,
       local_size_x = kSvgfGroupSizeX, local_size_y = kSvgfGroupSizeY) in;

RTDR_INPUT_ILLUMINATION(0, illumination_in)
RTDR_INPUT_RGBA(1, albedo_in)
RTDR_INPUT_RGBA(2, emission_in)
layout(std430, set = 0, binding = 3) writeonly buffer Colour { vec4 colour_out[]; };

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
  const int i = int(pixel.y * frame.width + pixel.x);
  const Illumination filtered = illumination_in(i);
  const vec3 colour = remodulate_pixel(filtered.stream[kDirectStream].rgb, filtered.stream[kIndirectStream].rgb,
                                       albedo_in(i).rgb, emission_in(i).rgb);
  colour_out[i] = vec4(colour, 0.0);
}
