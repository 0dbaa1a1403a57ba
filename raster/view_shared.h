// What a port reads of a View (raster/view.h), written once for C++ and GLSL: the record that View::project needs.
// The GLSL side of View::project is raster/view.glsl; the C++ side fills the record with view_record(). Both
// compilers include this file; core/shader_shared.h maps the types. The projection is P_i and P_{i-1} of the motion
// vectors' equations [TRMV21 Eq. 3, Eq. 5, Eq. 6].
#ifndef RTDR_RASTER_VIEW_SHARED_H
#define RTDR_RASTER_VIEW_SHARED_H

#include "core/shader_shared.h"

#ifdef __cplusplus
#include "raster/view.h"
#define RTDR_VIEW_VEC4 glm::vec4
namespace rtdr {
#else
#define RTDR_VIEW_VEC4 vec4
#endif

// world_to_clip's columns, the image's size as floats (float(width) and float(height), as View::project converts
// them) and znear: 80 bytes, the same in C++ and in std430.
struct ViewRecord {
  RTDR_VIEW_VEC4 world_to_clip[4];
  float width;
  float height;
  float znear;
  float unused;
};

#ifdef __cplusplus
static_assert(sizeof(ViewRecord) == 80, "four vec4 columns and four floats, the std430 layout of the GLSL struct");

// The record of a View.
inline ViewRecord view_record(const View& v) {
  ViewRecord r{};
  for (int c = 0; c < 4; ++c) r.world_to_clip[c] = v.world_to_clip[c];
  r.width = float(v.width), r.height = float(v.height), r.znear = v.znear;
  return r;
}
}  // namespace rtdr
#endif
#undef RTDR_VIEW_VEC4

#endif  // RTDR_RASTER_VIEW_SHARED_H
