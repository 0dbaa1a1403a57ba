// TRMV's glossy motion vector [TRMV21 Eq. 5]: what its C++ (motion/glossy.h, gpu/motion_glossy_gpu.cpp) and GLSL
// (motion/glossy.comp) share, written once: the bindings, the push-constant block, the output record and the
// constants of the golden pass. An instance's T^{-1} travels as motion/shadow_shared.h's ShadowInstanceMotion (the
// golden pass reads motion/shadow.h's InstanceMotion), a View as raster/view_shared.h's ViewRecord; the workgroup
// shape is the SVGF ports' (filters/svgf/planes_shared.h, which the shader includes: the golden pass does not need
// it), and the id of "no surface" core/frame_shared.h's. Both compilers include this file; GLSL has the C
// preprocessor, and core/shader_shared.h maps the types.
//
// Bindings (planes row-major: filters/svgf/planes_shared.h):
//   0 s_i, roughness  RGBA32F (x, y, z, roughness): position.X/Y/Z and material.roughness
//   1 n(s_i)          RGBA32F (x, y, z, 0), geonormal.X/Y/Z
//   2 h_i             RGBA32F (x, y, z, 0), path.secondary.X/Y/Z
//   3 reflector id    R32UI, id.instance (RTDR_INVALID_ID: no surface)
//   4 hit id          R32UI, path.secondary.instance (RTDR_INVALID_ID: the BSDF ray escaped)
//   5 seed            R32UI, rng.seed
//   6 instances       a std430 array of ShadowInstanceMotion, one per instance (InstanceMotion)
//   7 views           a std430 array of two ViewRecord: [0] this frame's View, [1] the previous frame's
//   8 out             a std430 array of GlossyMotionRecord: written (the previous and the current footprint)
#ifndef RTDR_MOTION_GLOSSY_SHARED_H
#define RTDR_MOTION_GLOSSY_SHARED_H

#include "core/frame_shared.h"
#include "core/shader_shared.h"
#include "motion/shadow_shared.h"
#include "raster/view_shared.h"

#ifdef __cplusplus
#define RTDR_GLOSSY_VEC4 glm::vec4
namespace rtdr {
#else
#define RTDR_GLOSSY_VEC4 vec4
#endif

// The number of bindings (0..8 above): 6 inputs (storage texel buffers, or storage buffers when built for storage
// inputs: core/shader_shared.h) and 3 storage buffers (instances, views, output).
RTDR_SHARED_CONST RTDR_SHARED_UINT kGlossyMotionTexelBindings = 6;
RTDR_SHARED_CONST RTDR_SHARED_UINT kGlossyMotionStorageBindings = 3;

// A line eye -> v within this cosine of the plane (about 6e-5 degrees) has no specular point worth using.
RTDR_SHARED_CONST float kGlossyParallelCosine = 1e-6f;
// tan theta_h of the GGX half-vector cone holding 68 % of D(h) cos theta_h, per unit alpha: sqrt(0.68 / 0.32).
RTDR_SHARED_CONST float kGgxLobeTanPerAlpha = 1.4577380f;
// The tag that gives Eq. 5's two normal numbers their own sequence: hash_combine(rng.seed, kGlossyStream) is its
// seed, as trace/shading.h's kShadingStream is the shading term's. Any fixed value serves; this one is the ASCII
// bytes of "glos".
RTDR_SHARED_CONST RTDR_SHARED_UINT kGlossyStream = 0x676C6F73U;
// Normal incidence: the incidence direction's part along the plane is shorter than this (a unit vector's length
// 1e-6, an angle of 1e-6 rad), so the plane of incidence is undefined and any tangent spans the footprint, which is
// a circle there.
RTDR_SHARED_CONST float kGlossyNormalIncidence = 1e-6f;
// pi as a float, std::numbers::pi_v<float> (0x40490fdb): Box-Muller's angle 2 pi u.
RTDR_SHARED_CONST float kGlossyPi = 3.14159274f;

// The push-constant block: the two eyes (View::eye; w unused), the frame's size (invocations outside it, the last
// tiles, do nothing), the number of instances (an id at or beyond it is read as no instance: GPU only, the golden
// pass's precondition) and the narrowest GGX lobe (scenes/scene.h's kMinGgxAlpha, ggx_alpha's floor).
struct GlossyMotionPush {
  RTDR_GLOSSY_VEC4 eye;
  RTDR_GLOSSY_VEC4 prev_eye;
  RTDR_SHARED_UINT width;
  RTDR_SHARED_UINT height;
  RTDR_SHARED_UINT instance_count;
  float min_ggx_alpha;
};

// One pixel's GlossyMotion: m^R, mu, the footprint's columns a1 and a2 (pixels) and valid (0 or 1); the current
// footprint's columns b1 and b2 and has_footprint (0 or 1). Sigma = a1 a1^T + a2 a2^T and Sigma_i = b1 b1^T +
// b2 b2^T are made on the host as glossy_motion_pixel makes them. 64 bytes, the same in C++ and in std430.
struct GlossyMotionRecord {
  RTDR_SHARED_VEC2 motion;
  RTDR_SHARED_VEC2 mu;
  RTDR_SHARED_VEC2 a1;
  RTDR_SHARED_VEC2 a2;
  RTDR_SHARED_VEC2 b1;
  RTDR_SHARED_VEC2 b2;
  RTDR_SHARED_UINT valid;
  RTDR_SHARED_UINT has_footprint;
  RTDR_SHARED_UINT unused[2];
};

#ifdef __cplusplus
static_assert(sizeof(GlossyMotionPush) == 48, "two vec4 and four 4-byte fields, the std430 layout of the block");
static_assert(sizeof(GlossyMotionRecord) == 64, "six vec2 and four 4-byte fields, the std430 layout of the struct");
}  // namespace rtdr
#endif
#undef RTDR_GLOSSY_VEC4

#endif  // RTDR_MOTION_GLOSSY_SHARED_H
