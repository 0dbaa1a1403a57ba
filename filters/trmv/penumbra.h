// The penumbra-sized shadow filter [TRMV21 Sec. 4.1, 5, after LLK*19]: the visibility's spatial std from the width
// of the penumbra each in-shadow pixel lies in.
//
// TRMV21 Sec. 4.1 filters its shadows after "Liu et al. [HA19], which accurately calculates the filter size", and
// notes that "penumbra regions will also be spatially filtered more aggressively with larger filter size"; Sec. 5
// then uses a fixed 31x31 separable joint bilateral, which "turns out already good enough". ([HA19] is the Ray
// Tracing Gems book; the chapter is [LLK*19], Liu et al., "Cinematic Rendering in UE4 with Real-Time Ray Tracing and
// Denoising".) Liu et al. size their shadow filter from the light's size and the distances from the light to the
// blocker and to the receiver, the penumbra of similar triangles; ours, from that description:
//
//   W = D (d_r - d_b) / d_b                                  the penumbra's width at the receiver, metres
//   sigma_a = clamp(W / (6 m_a), sigma_floor, sigma_cap)     the filter's std along image axis a, pixels
//
// - D, the light's diameter: twice the radius of the disk with the light's second moment, D = 2 sqrt(2 E|l - c|^2),
//   c = E l, the moments of the frame's light samples of that light instance (path.light, uniform over the light's
//   area). A disk of radius R gives E|l - c|^2 = R^2 / 2, so D = 2R; fence's 0.4 x 1 m quad gives D = 0.88 m. The
//   frame does not carry the lights' shapes; their samples do, in every frame (a per-instance reduction, in double,
//   in pixel order: deterministic).
// - d_b = |b - l| and d_r = |s - l|: the light sample to the blocker (path.blocker) and to the receiver point
//   (`position`), as the pixel's own shadow ray saw them. Similar triangles: a point of the receiver sees the
//   light's disk of diameter D past the blocker's edge; moving along the receiver by W sweeps it across.
// - m_a, metres per pixel along axis a on the receiver: half the distance between the `position`s of the two
//   neighbours along a, where both lie on the pixel's surface (the same instance, normals within the splat's
//   25.8 degrees); else the one neighbour that does, to the pixel itself; else 0 (unknown: the floor std).
// - The window: the penumbra's width across, +-3 std of the Gaussian, as the fixed filter's 31 pixels are its
//   std 5 times 6: sigma = W_px / 6. Per axis, so that a receiver seen at a grazing angle (the floor, whose pixels
//   span more metres down the image than across) gets the same width in metres both ways.
// - sigma_cap, the fixed filter's std (spatial_sigma, scaled: filters/trmv/footprint.h): the paper's 31x31 is the
//   largest; sigma_floor = 0.5 px, a 3x3 window's std (footprint.h's floor).
// - Not modelled: the penumbra's stretch on a receiver the light meets obliquely (Liu et al. project the filter
//   anisotropically onto it), and several blockers along one ray (the nearest is recorded, path.blocker).
// - A lit pixel has no blocker of its own. The splat (splat.h) carries the in-shadow pixels' W to the pixels
//   around them, "along with other associated properties" [TRMV21 Sec. 4.1], and each pixel takes its std from
//   the mean W that landed on it and its own m_a. Where none landed the window holds no blocked sample on the
//   pixel's surface, the visibility there is 1, and the floor std serves.
//
// Pass: trmv_penumbra_pass(inputs) -> W per pixel (0 where the shadow ray reached the light) and (m_x, m_y) per pixel.
#pragma once

#include "filters/image.h"
#include "filters/probe.h"

#include <glm/glm.hpp>

#include <map>

namespace rtdr {

// The planes the penumbra reads.
struct TrmvPenumbraInputs {
  RgbPlane light;          // path.light: the light sample, world space
  UIntPlane light_id;      // path.light.instance (kInvalidId: no light sampled)
  RgbPlane blocker;        // path.blocker: the nearest blocker of the shadow ray
  UIntPlane blocker_id;    // path.blocker.instance (kInvalidId: the ray reached the light)
  RgbPlane position;       // s_i, world space
  UIntPlane instance;      // id.instance (kInvalidId: no surface)
  RgbPlane normal;         // unit

  static TrmvPenumbraInputs from_frame(const Frame& frame);  // throws rtdr::Error naming a missing layer
};

struct TrmvPenumbraOutput {
  FloatPlane width;         // W, metres; 0 where unblocked or no light sampled
  Vec2Plane metres;         // (m_x, m_y), metres per pixel on the receiver; 0 where unknown
};

// D per light instance: 2 sqrt(2 E|l - c|^2) over the frame's samples of that light.
std::map<uint32_t, float> trmv_light_diameters(const RgbPlane& light, const UIntPlane& light_id);
// W = D (d_r - d_b) / d_b, d_b = |b - l|, d_r = |s - l|; 0 when d_b is 0 or the receiver is nearer than the blocker.
float trmv_penumbra_width(float diameter, glm::vec3 light, glm::vec3 blocker, glm::vec3 receiver);
// m along `axis` at pixel (x, y) (above).
float trmv_metres_per_pixel(const TrmvPenumbraInputs& in, glm::ivec2 axis, int x, int y);
// sigma_a = clamp(W / (6 m_a), floor, cap); the floor where m_a = 0.
float trmv_penumbra_sigma(float width, float metres, float sigma_floor, float sigma_cap);

// The golden per-pixel function: W and (m_x, m_y) at pixel (x, y), given the light diameters.
void trmv_penumbra_pixel(const TrmvPenumbraInputs& in, const std::map<uint32_t, float>& diameters, int x, int y,
                         float& width, glm::vec2& metres, Probe* probe = nullptr);

// Throws rtdr::Error unless every plane has the position's size: the checks of trmv_penumbra_pass.
void check_trmv_penumbra_sizes(const TrmvPenumbraInputs& in);

// The light diameters, then trmv_penumbra_pixel at every pixel (parallel over rows, deterministic).
TrmvPenumbraOutput trmv_penumbra_pass(const TrmvPenumbraInputs& in);

// The std of the penumbra filter along each image axis at every pixel, from the splatted W (splat.h's carried mean)
// and the metres per pixel: sigma_x and sigma_y (trmv_penumbra_sigma).
void trmv_penumbra_sigmas(const FloatPlane& splatted_width, const Vec2Plane& metres, float sigma_floor,
                          float sigma_cap, FloatPlane& sigma_x, FloatPlane& sigma_y);

// 0.5 px: the std of a 3x3 window (footprint.h's floor), the penumbra filter's least.
inline constexpr float kTrmvPenumbraSigmaFloor = 0.5f;

}  // namespace rtdr
