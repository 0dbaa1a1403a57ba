// Tone mapping [Reinhard02 Eqs. 2-3 on luminance, SVGF17 Sec. 3 "Post Processing"], the Vulkan port of
// tonemap_pixel (tonemap.cpp), line for line: L_w = Y(colour), L = exposure * L_w, L_d = L / (1 + L),
// display = clamp(colour * L_d / L_w, 0, 1); black where L_w <= 0. One invocation per pixel.
//   in:  binding 0: HDR colour; out: binding 1: display colour. Layout: planes_shared.h, tonemap_shared.h.
#version 450
#extension GL_GOOGLE_include_directive : require

#include "core/color.glsl"
#include "filters/svgf/tonemap_shared.h"

// The workgroup's shape, per device (planes_shared.h).
layout(local_size_x_id = kSvgfGroupSizeXConstant, local_size_y_id = kSvgfGroupSizeYConstant,
       local_size_x = kSvgfGroupSizeX, local_size_y = kSvgfGroupSizeY) in;

RTDR_INPUT_RGBA(0, colour_in)
layout(std430, set = 0, binding = 1) writeonly buffer Display { vec4 display_out[]; };

layout(push_constant) uniform Push { TonemapPush frame; };

vec3 tonemap_pixel(vec3 colour, float exposure) {
  // World luminance L_w of the HDR colour (Rec. 709 Y, core/color.h).
  const float L_w = luminance(colour);
  // Black stays black; L_w <= 0 only comes from negative inputs, which have nothing to display.
  if (!(L_w > 0.0)) return vec3(0.0);
  // Scaled luminance L = exposure * L_w [Reinhard02 Eq. 2, a / L_w-bar replaced by a fixed exposure].
  precise float L = exposure * L_w;
  // Display luminance L_d = L / (1 + L): near-linear for dark values, approaching 1 for bright ones [Reinhard02 Eq. 3].
  precise float L_d = L / (1.0 + L);
  // Scale the colour so its luminance becomes L_d; the ratios of R, G, B (chromaticity) are kept.
  precise float scale = L_d / L_w;
  precise vec3 scaled = scale * colour;
  // Display clamp: a saturated bright colour can keep a channel above 1 (see tonemap.h).
  const vec3 display = clamp(scaled, 0.0, 1.0);
  return display;
}

void main() {
  // This invocation's pixel; the last tiles overhang the frame.
  const uvec2 pixel = gl_GlobalInvocationID.xy;
  if (pixel.x >= frame.width || pixel.y >= frame.height) return;
  const int i = int(pixel.y * frame.width + pixel.x);
  display_out[i] = vec4(tonemap_pixel(colour_in(i).rgb, frame.exposure), 0.0);
}
