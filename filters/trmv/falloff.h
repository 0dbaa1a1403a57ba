// TRMV's falloff heuristic for non-planar shadow receivers [TRMV21 Eq. 4].
//
// Pass: trmv_falloff_pass(receiver, shadow motion, previous positions, params) -> alpha^V per pixel.
//   in:  s_i and n(s_i), the receiver's point and normal per pixel (`position`, `geonormal`), and its surface
//        motion (`motion`); the shadow motion vectors m^V with their validity (x^V_{i-1} = pixel centre + m^V,
//        TRMV21 Eq. 3); the previous frame's `position`, `geonormal` and `id.mesh`; alpha, the falloff's std and
//        falloff_carry (trmv_params.h)
//   out: theta, the angle between n(T^{-1} s_i) and the direction T^{-1} s_i -> s^V_{i-1}, where s^V_{i-1} is the
//        previous frame's `position` at the pixel nearest to x^V_{i-1}, and
//          alpha^V = 1 - G(theta - pi/2; 0, sigma) (1 - alpha)                          [TRMV21 Eq. 4]
//        with G(x; 0, sigma) = exp(-x^2 / (2 sigma^2)), a Gaussian whose PEAK is 1 ("with its peak value
//        normalized to 1"), not its integral. alpha^V replaces alpha in Eq. 2 for the visibility.
//
// The shadow vector assumes the shadow point stays on the receiver's plane (Eq. 3 intersects that plane). Where
// the point it finds in the previous frame, s^V_{i-1}, lies on that plane, the direction s_i -> s^V_{i-1} is
// perpendicular to n(s_i), theta = pi/2, G = 1 and alpha^V = alpha: the vector is trusted as much as any. Where
// the receiver folds or curves, s^V_{i-1} leaves the plane, theta moves away from pi/2, and alpha^V grows
// towards 1: the history is trusted less, the spatial filter more.
//
// Units: theta and sigma are in radians. The paper writes G(theta - pi/2; 0, 0.1) next to "when theta is close
// to 90 degrees" without a unit for 0.1. theta - pi/2 is written in radians, so 0.1 is too: 0.1 rad = 5.7
// degrees, G = e^{-1/2} = 0.61 at that tilt. Read as 0.1 degree, G would fall to e^{-1/2} at 0.0017 rad and to
// 1e-4 at 0.0075 rad (0.43 degree): every receiver that is not exactly planar to float precision (interpolated
// positions, a plane seen at a grazing angle, a vector off by a fraction of a pixel) would get alpha^V ~ 1, no
// history at all, which would reject almost every tilt and undo the shadow vectors.
//
// Choices the paper leaves open (filters/trmv/README.md, "Deviations and choices"):
// - s^V_{i-1} is read at the nearest pixel to x^V_{i-1} (floor), not bilinearly: a bilinear mix of positions
//   across a fold is a point on neither face.
// - A static shadow (s^V_{i-1} = s_i, the direction undefined): theta = pi/2 when
//   |s^V_{i-1} - s_i| < 1e-6 (1 + |s_i|), a relative tolerance of float precision.
// - No Eq. 4 evidence (the pixel sees no surface, the vector is invalid, x^V_{i-1} is off the previous image or
//   sees no surface there, first frame): alpha^V = alpha, so w_A = 0 in Eq. 7. Whether such a pixel keeps any
//   history is the temporal pass's decision (alpha = 1 for an invalid vector, temporal.h), made from the same
//   validity plane; the two passes stay separate and agree.
// - Moving receivers: the paper transforms n(s_i) with the receiver's motion ("inverse transformed if the shadow
//   receiver moves over time"): s^V_{i-1} is a point of frame i-1, so the plane it is compared with must be the
//   receiver's plane in frame i-1 too. The filter has no transforms, but it has the previous G-buffer: the receiver
//   point carried back, T^{-1} s_i, is where the surface motion says it was, x_i + m, and the previous frame shows
//   that surface there. So with falloff_carry = 1 (the default) s_i and n(s_i) are the previous `position` and
//   `geonormal` at the pixel holding x_i + m, when that pixel shows the receiver's mesh: the receiver's plane in
//   frame i-1 exactly (a face's points and normal), its point within a pixel of T^{-1} s_i, which moves theta only
//   off the plane (on it theta = pi/2 whatever the point). Where the previous frame does not show it
//   (disoccluded, off the previous image) and with falloff_carry = 0, the current planes, exact for a static
//   receiver (tests/trmv_falloff_test.cpp: a translating and a rotating receiver).
#pragma once

#include "filters/image.h"
#include "filters/probe.h"
#include "filters/trmv/temporal.h"
#include "filters/trmv/trmv_params.h"

#include <glm/glm.hpp>

namespace rtdr {

// The receiver of each pixel's shadow: s_i and n(s_i), id.mesh (which pixels see a surface) and the surface motion
// (where the receiver point was in the previous frame).
struct TrmvReceiver {
  RgbPlane position;  // s_i, world space
  RgbPlane normal;    // n(s_i), unit (the geometric normal, the plane Eq. 3 intersects)
  UIntPlane mesh;
  Vec2Plane motion;   // `motion` [TRMV21 Eq. 1]
};

// The previous frame's surface points: `position`, `geonormal` and `id.mesh`. Empty (width 0): the first frame.
struct TrmvPreviousPositions {
  RgbPlane position;
  RgbPlane normal;
  UIntPlane mesh;
};

struct TrmvFalloffPixel {
  float theta = 0.0f;   // radians; pi/2 where there is no evidence
  float alpha_v = 0.0f; // alpha^V [TRMV21 Eq. 4]
};

struct TrmvFalloffOutput {
  FloatPlane theta;
  FloatPlane alpha_v;
};

// G(x; 0, sigma) = exp(-x^2 / (2 sigma^2)), peak 1 [TRMV21 Eq. 4].
float trmv_falloff_gaussian(float x, float sigma);
// alpha^V = 1 - G(theta - pi/2; 0, sigma) (1 - alpha) [TRMV21 Eq. 4].
float trmv_falloff_alpha(float theta, float alpha, float sigma);
// theta, the angle between n(s_i) and s_i -> s^V_{i-1}, in [0, pi]; pi/2 for the degenerate static shadow.
float trmv_falloff_theta(glm::vec3 s_i, glm::vec3 n_s_i, glm::vec3 s_v_prev);
// The receiver's point and normal carried back to frame i-1 (above): the previous position and geonormal at the
// pixel holding pixel (x, y) + its surface motion, where that pixel shows the same mesh; false (and s, n left as
// they are) where it does not.
bool trmv_falloff_carry_back(const TrmvReceiver& receiver, const TrmvPreviousPositions& prev, int x, int y,
                             glm::vec3& s, glm::vec3& n);

// The golden per-pixel function.
TrmvFalloffPixel trmv_falloff_pixel(const TrmvReceiver& receiver, const TrmvMotion& shadow,
                                    const TrmvPreviousPositions& prev, const TrmvParams& params, int x, int y,
                                    Probe* probe = nullptr);

// Throws rtdr::Error unless the receiver's and the shadow motion's planes share a size and the previous id.mesh and
// geonormal have the previous positions': the checks of trmv_falloff_pass, which its port makes too (gpu/trmv_falloff_gpu.h).
void check_trmv_falloff_sizes(const TrmvReceiver& receiver, const TrmvMotion& shadow,
                              const TrmvPreviousPositions& prev);

// trmv_falloff_pixel at every pixel (parallel over rows, deterministic). Throws rtdr::Error when the planes'
// sizes disagree.
TrmvFalloffOutput trmv_falloff_pass(const TrmvReceiver& receiver, const TrmvMotion& shadow,
                                    const TrmvPreviousPositions& prev, const TrmvParams& params);

}  // namespace rtdr
