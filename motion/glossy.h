// Glossy reflection motion vectors [TRMV21 Eq. 5]: where the reflection a pixel shows was in the previous frame.
//
// Pass: glossy_motion(geometry, frame) -> motion.glossy per pixel.
//   in:  per pixel the primary BSDF ray as the path tracer recorded it (path.secondary and its instance, the
//        surface h_i it hit), the reflector s_i (position, geonormal, id.instance, material.roughness), the
//        pixel's rng.seed, the poses and Views of this frame and the previous one
//   out: motion.glossy = x^R_{i-1} - x_i in pixels, motion.glossy.valid (1 where Eq. 5 gives a point)
//
// A reflection moves with the reflected object and the camera, not with the mirror: on a still floor under an
// orbiting camera the floor's own motion fetches history from where the reflected box was not (the ghosts of
// [TRMV21 Fig. 11]). A planar mirror shows h as its virtual image v, a real point behind the mirror (Zimmer et
// al. 2015, whom TRMV21 Sec. 4.2 follows); TRMV21 tracks v and then spreads the vector over the glossy lobe:
//
//   x^R_{i-1} = sample( P_{i-1} mirror[ T^{-1} h_i, T^{-1} plane(s_i) ], Sigma ),   m^R = x^R_{i-1} - x_i
//
// Steps (motion/glossy.cpp):
// 1. h' = T^{-1} h_i with h's own instance motion; the reflector plane is s_i's face plane (geonormal), carried
//    back with s_i's instance motion (the point by to_previous, the normal by normal_to_previous).
// 2. v = h' mirrored across that plane: the virtual image.
// 3. mu = P_{i-1}(v); s^C = where the segment eye_{i-1} -> v crosses the plane: the specular point, the spot on
//    the reflector where the previous camera saw h' as a mirror image. s^C lies on the eye's ray to v, so
//    P_{i-1}(s^C) = mu.
// 4. The footprint. "A glossy lobe (with the same roughness at s^C) traced from the virtual image of h_{i-1}
//    towards s^C" meets the plane in a region "approximated by tracking the endpoints of major and minor axes"
//    [TRMV21 Sec. 4.2]. The paper gives no width; ours (a choice):
//    - GGX half-vectors with alpha = ggx_alpha(roughness) (scenes/scene.h) have P(theta_h < theta) =
//      tan^2 theta / (alpha^2 + tan^2 theta). Setting it to 0.68, the mass of a Gaussian's +-1 standard
//      deviation, gives tan theta_h = sqrt(0.68 / 0.32) alpha = 1.458 alpha. The reflected direction turns by
//      twice the half-vector: sigma_theta = 2 atan(1.458 alpha), the lobe's angular standard deviation.
//      (GGX has no finite variance: its slopes' density falls as r^-3. With 68 % the round Gaussian's 90 %
//      radius, 2.15 x 1.458 alpha = 3.13 alpha, is close to GGX's, 3.0 alpha, but its core is wider than GGX's;
//      matching the 2D Gaussian's own one-sigma mass, 39 %, would give 0.805 alpha instead. The doubling holds
//      exactly in the plane of incidence; perpendicular to it the reflected direction turns by about 2 cos(i)
//      times the half-vector. We keep the lobe round, as the paper's "Gaussian in directions" does.)
//    - The cone of half-angle sigma_theta from v around v -> s^C cuts the plane in an ellipse around s^C with
//      semi-axes d tan(sigma_theta) / cos i (in the plane of incidence) and d tan(sigma_theta) (perpendicular),
//      d = |v - s^C|, cos i the incidence cosine at s^C (first order in sigma_theta: the exact conic is slightly
//      off-centre). This is the paper's construction, and it is exact for a distant eye only: a point p of the
//      plane reflects h within the lobe when the angle at p between the eye's ray and the direction to v (in the
//      unfolded mirror) is below sigma_theta, and that angle is the triangle eye-p-v's exterior angle, the angle
//      at v plus the angle at the eye. The cone counts the first only, so for an eye at distance D from s^C its
//      footprint is (d + D) / D times too wide (2x where d = D). We keep the paper's.
//    - The pixels that see that ellipse are the pixels that reflect h' within the lobe, so the image-space
//      footprint is the ellipse projected by P_{i-1}. It is centred at P_{i-1}(s^C) = mu: the reflector carries
//      the footprint, and the virtual image is seen through it. Each semi-axis's endpoints s^C +- r t are
//      projected and halved, a_k = (P_{i-1}(s^C + r t) - P_{i-1}(s^C - r t)) / 2 (the central difference, so
//      perspective does not lean the footprint towards the near end), giving Sigma = a1 a1^T + a2 a2^T.
// 5. One sample x^R = mu + a1 n1 + a2 n2, (n1, n2) standard normal by Box-Muller from new random numbers:
//    Sampler(hash_combine(rng.seed, kGlossyStream), 0), uncorrelated with the path's own (core/sampler.h), so a
//    frame's vectors are a function of the frame alone.
//
// Which point is x_i (our choice, like motion/shadow.h's). The path's sampled ray leaves the lobe's centre, so
// h_i's mirror image v_i is not seen exactly at the pixel centre: P_i(v_i) is off by up to a footprint. We use
// x_i = P_i(v_i), v_i = h_i mirrored across the current plane, so that mu = P_{i-1}(v_{i-1}) - P_i(v_i) is the
// motion of one point, the virtual image (Zimmer et al.'s specular motion vector), and a static scene gives mu
// = the surface motion up to rounding (both are the views' jitter difference; rtdr renders without jitter, so
// both are 0). The paper's pixel centre would add this sample's own lobe offset to every vector, a second
// footprint of noise on top of Sigma's.
//
// Roughness: s_i's `material.roughness` (a planar reflector has one material, so s^C has the same). At roughness
// 0 alpha is kMinGgxAlpha = 1e-3, the path tracer's narrowest lobe: sigma_theta = 2.9 mrad, so Sigma is small but
// not 0 (sqrt(trace Sigma) up to 0.15 px on cornell at 64 x 64, tests/motion_glossy_test.cpp; it grows with the
// image size), and x^R = mu holds only to within it.
//
// Valid where (else motion.glossy is (0, 0) and .valid is 0):
// - the pixel sees a surface and its BSDF ray hit one (path.secondary.instance is recorded);
// - in both frames, the eye and h are strictly on the same side of the reflector plane (else nothing is
//   reflected: v and the eye would be on one side), and the line eye -> v is not parallel to the plane:
//   |n . (v - eye)| > kGlossyParallelCosine |v - eye|;
// - v is in front of the camera in both frames (depth >= znear), and so are the footprint's four endpoints in
//   the previous frame (a footprint reaching behind the camera has no image-space ellipse);
// - the lobe meets the plane in a bounded ellipse: sigma_theta < pi/2 - i, the angle between the cone's axis and
//   the plane. A wider lobe reaches past the plane's horizon: its reflection is a blur with no image to follow
//   (at roughness 1, sigma_theta = 111 degrees), and the surface's own motion is the better vector. At normal
//   incidence this admits roughness up to 0.83, at 60 degrees up to 0.43.
// Eq. 5 is computed for every pixel with a secondary hit, whatever its material: which pixels use it (the glossy
// component, indirect.glossy) is the filter's choice.
//
// Curved reflectors are the paper's stated failure [TRMV21 Sec. 7, Fig. 14]: the tangent plane at s_i stands in
// for the mirror, with no special handling (the thin-lens virtual image that Sec. 7 suggests would replace
// steps 1-3 only).
#pragma once

#include "core/frame.h"
#include "motion/glossy_shared.h"
#include "motion/shadow.h"
#include "raster/gbuffer_frame.h"
#include "raster/view.h"

#include <glm/glm.hpp>

#include <cstdint>
#include <vector>

namespace rtdr {

// kGlossyParallelCosine, kGgxLobeTanPerAlpha, kGlossyStream and kGlossyNormalIncidence: written once, for the C++
// and the shader, in motion/glossy_shared.h.

// One pixel's primary BSDF ray as the path tracer recorded it (the path.* layers), and its reflector.
struct GlossyRay {
  glm::vec3 reflector{0.0f};         // s_i, the pixel's surface point
  glm::vec3 reflector_normal{0.0f};  // n(s_i), its face normal (unit or not; its sign does not matter)
  glm::vec3 hit{0.0f};               // h_i, where the BSDF ray from s_i hit
  float roughness = 0.0f;            // s_i's material.roughness
  uint32_t seed = 0;                 // the pixel's rng.seed
  uint32_t reflector_instance = kInvalidId, hit_instance = kInvalidId;
};

struct GlossyMotion {
  glm::vec2 mu{0.0f};       // P_{i-1}(v_{i-1}) - x_i, pixels: the vector to the footprint's centre
  glm::mat2 axes{0.0f};     // columns a1 (plane of incidence) and a2 (perpendicular), pixels
  glm::mat2 Sigma{0.0f};    // a1 a1^T + a2 a2^T, pixels^2
  glm::vec2 motion{0.0f};   // m^R = x^R_{i-1} - x_i = mu + a1 n1 + a2 n2, pixels; (0, 0) when not valid
  bool valid = false;
  // The same lobe's footprint seen by the CURRENT camera: the columns b1, b2 and Sigma_i = b1 b1^T + b2 b2^T
  // (pixels^2), from the current virtual image v_i (steps 2-4 with P_i). Independent of the previous frame: what
  // the glossy spatial filter reads (filters/trmv/reflection.h, [LLK*19]'s lobe footprint). 0 without one.
  glm::mat2 footprint_axes{0.0f};
  glm::mat2 footprint{0.0f};
  bool has_footprint = false;
};

// sigma_theta = 2 atan(1.458 alpha): the reflected direction's angular standard deviation, radians (above).
float glossy_lobe_angle(float alpha);
// (n1, n2), two independent standard normal numbers for this seed: Box-Muller on
// Sampler(hash_combine(seed, kGlossyStream), 0).next_2d().
glm::vec2 glossy_normal_pair(uint32_t seed);

// The golden per-pixel function [TRMV21 Eq. 5]. `to_previous` is instance_to_previous(pose, prev_pose).
GlossyMotion glossy_motion_pixel(const GlossyRay& ray, const std::vector<InstanceMotion>& to_previous,
                                 const View& view, const View& prev_view);

// The channels of a frame that hold every pixel's BSDF ray: path.secondary.X/Y/Z and .instance, rng.seed, and
// its G-buffer (`position`, `geonormal`, `id.instance`, `material.roughness`). Read in place, not copied.
class GlossyRayLayers {
 public:
  explicit GlossyRayLayers(const Frame& frame);  // throws rtdr::Error naming a missing channel
  // Pixel i's ray; a pixel whose BSDF ray escaped (or that sees no surface) gets one with no hit.
  GlossyRay at(size_t i) const;

 private:
  const FloatPlane *secondary_[3], *position_[3], *normal_[3], *roughness_;
  const UIntPlane *secondary_id_, *reflector_id_, *seed_;
};

// Every pixel's glossy motion, row-major; bit-identical for any thread count.
std::vector<GlossyMotion> glossy_motion(const FrameGeometry& geometry, const Frame& frame);

// Adds motion.glossy.X, motion.glossy.Y and motion.glossy.valid (uint 0/1), the lobe's centre motion.glossy_mean.X/Y
// (mu, where motion.glossy is valid, else 0), and the current footprint glossy.footprint.XX/XY/YY (Sigma_i's
// entries, pixels^2) with glossy.footprint.valid, to a frame that holds the path.* layers (trace_layers).
void write_glossy_motion_layers(const FrameGeometry& geometry, Frame& frame);

}  // namespace rtdr
