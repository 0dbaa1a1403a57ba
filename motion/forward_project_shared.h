// The forward projection's occlusion tolerance (motion/forward_project.h), written once for C++ and for the ports
// that make the same depth test (motion/dual.comp): the occlusion test of [ASVGF18 Sec. 3.3] and TRMV's
// disocclusion test [TRMV21 Eq. 6]. Both compilers include this file; core/shader_shared.h maps the types.
#ifndef RTDR_MOTION_FORWARD_PROJECT_SHARED_H
#define RTDR_MOTION_FORWARD_PROJECT_SHARED_H

#include "core/shader_shared.h"

#ifdef __cplusplus
namespace rtdr {
#endif

// Relative depth tolerance of the occlusion test: a sample at depth z is occluded when the current depth
// buffer at its pixel is below z (1 - tolerance). The sample is up to ~0.7 pixel from that pixel's centre,
// where the surface's depth differs from z by about z * 0.7 * pixel angle * tan(slant). At 720p with a 45
// degree field of view (pixel angle ~1.1e-3 rad), 1 % absorbs that for surfaces slanted up to ~85 degrees
// from the view ray, while any occluder nearer than 99 % of the sample's depth still hides it.
RTDR_SHARED_CONST float kForwardProjectionDepthTolerance = 0.01f;

#ifdef __cplusplus
}  // namespace rtdr
#endif

#endif  // RTDR_MOTION_FORWARD_PROJECT_SHARED_H
