// GLSL mirror of View::project (raster/view.cpp) and of glm's mat4 * vec4 that it and world_point
// (raster/visibility.h) use, for the render side's Vulkan ports (#include "raster/view.glsl"; needs
// GL_GOOGLE_include_directive). Every result is `precise`, in glm's order, so that only the division is the
// device's: mat4 * vec4 is (c0 x + c1 y) + (c2 z + c3 w). It is P_i and P_{i-1} of [TRMV21 Eq. 3, Eq. 5, Eq. 6].
#ifndef RTDR_RASTER_VIEW_GLSL
#define RTDR_RASTER_VIEW_GLSL

#include "raster/view_shared.h"

// m * glm::vec4(p, 1) for a mat4 given as its four columns.
vec4 times_point(vec4 m[4], vec3 p) {
  precise vec4 r = (m[0] * p.x + m[1] * p.y) + (m[2] * p.z + m[3] * 1.0);
  return r;
}

// glm::vec3(m * glm::vec4(p, 1)): a point moved by a transform (world_point's instance_to_world).
vec3 transform_point(vec4 m[4], vec3 p) { return times_point(m, p).xyz; }

// View::project: world point -> (screen x, screen y, depth). Only meaningful when depth > 0.
vec3 project(ViewRecord view, vec3 world) {
  const vec4 clip = times_point(view.world_to_clip, world);
  const float depth = clip.w;  // w_clip = -z_view = linear depth for a perspective projection
  precise vec2 ndc = clip.xy / clip.w;
  precise float x = (ndc.x * 0.5 + 0.5) * view.width;
  precise float y = (0.5 - ndc.y * 0.5) * view.height;
  return vec3(x, y, depth);
}

#endif  // RTDR_RASTER_VIEW_GLSL
