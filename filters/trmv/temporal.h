// TRMV's temporal blend [TRMV21 Eq. 2] with the neighbourhood clamp of the history [TRMV21 Sec. 5].
//
// Pass: trmv_temporal_pass(c~, cur, motion, prev, alpha, params) -> cbar_i, the fetched and the clamped history.
//   in:  c~_i, the spatially filtered current frame (spatial.h); the current `id.mesh` (which pixels see a
//        surface); one component's motion vectors m (previous position = pixel centre + m, the convention of
//        motion/backproject.h) with their validity; the previous history cbar_{i-1} and the previous `id.mesh`
//        (empty history: the first frame); alpha per pixel (alpha^V of falloff.h for visibility, else the
//        constant alpha of trmv_params.h, which an empty alpha plane stands for)
//   out: cbar_{i-1}(x_{i-1}), the history fetched bilinearly at x_{i-1} = pixel centre + m (or given re-shaded,
//        TrmvMotion);
//        cbar*_{i-1}, that history clamped per channel to [mu - gamma sigma, mu + gamma sigma] of c~ over the
//        (2r+1)^2 window around the pixel [TRMV21 Sec. 5], gamma = clamp_gamma, r = clamp_radius;
//        cbar_i = alpha c~_i + (1 - alpha) cbar*_{i-1}   [TRMV21 Eq. 2]
//        and the alpha the blend used (1 where there was no history). Eq. 8 (cleanup.h) reads both histories.
//
// The paper's clamp: "limit the temporal color / radiance value x_{i-1} (still found using our motion vectors)
// to the [mu - 3 sigma, mu + 3 sigma] interval in each x_i's neighborhood" [TRMV21 Sec. 5]; Salvi's clamp, the
// "Trad. (Clamp)" baseline, is mu +- sigma [TRMV21 Sec. 4.3].
//
// Choices the paper leaves open (filters/trmv/README.md, "Deviations and choices"):
// - Resampling: bilinear, the 2x2 pixel centres around x_{i-1}. A tap outside the previous image or without a
//   surface there (previous id.mesh = kInvalidId) is dropped and the remaining bilinear weights are renormalised
//   by their sum (as SVGF's temporal pass does with failed taps). No mesh, depth or normal test: a shadow's or a
//   reflection's vector legitimately lands on other surfaces than the pixel's own; Eq. 4 and the clamp guard it.
// - No history (first frame, invalid vector, x_{i-1} off the previous image, every tap dropped): alpha = 1, so
//   cbar_i = c~_i; the fetched and clamped histories are 0 there, which gives w_C = 0 in Eq. 8.
// - A pixel without a surface passes c~ through with alpha = 1.
// - The clamp's window: c~ at the pixels of the (2r+1)^2 window inside the image that see a surface (the centre
//   always does); mu and sigma are their mean and population standard deviation, per RGB channel.
// - gamma = 0 switches the clamp off ("Trad. (No clamp)"), it does not clamp to mu.
#pragma once

#include "filters/image.h"
#include "filters/probe.h"
#include "filters/trmv/trmv_params.h"

#include <glm/glm.hpp>

namespace rtdr {

// One component's motion vectors: m = x_{i-1} - x_i in pixels, and 1 where the vector is valid. An empty
// validity plane (width 0) means every vector is valid (the back-projected `motion` has none of its own).
// At a pixel where `reshaded_valid` is 1 the history is `reshaded` instead of a fetch along m: the diffuse light
// re-shaded from the cones at the dual vector's target [TRMV21 Sec. 4.3, Eq. 11] (filters/trmv/reshade.h). Both
// empty: every history is fetched.
struct TrmvMotion {
  Vec2Plane motion;
  UIntPlane valid;
  RgbPlane reshaded;
  UIntPlane reshaded_valid;
};

// The previous frame's history of one component. An empty colour (width 0) means "first frame".
struct TrmvHistory {
  RgbPlane color;  // cbar_{i-1}
  UIntPlane mesh;  // the previous frame's id.mesh: taps without a surface are dropped
};

// One pixel of the pass's output.
struct TrmvTemporalPixel {
  glm::vec3 color{0.0f};    // cbar_i [TRMV21 Eq. 2]
  glm::vec3 fetched{0.0f};  // cbar_{i-1}(x_{i-1}), unclamped [TRMV21 Eq. 8's denominator]
  glm::vec3 clamped{0.0f};  // cbar*_{i-1}(x_{i-1}) [TRMV21 Sec. 5, Eq. 8]
  float alpha = 1.0f;       // the alpha of the blend: the input's, or 1 without history
};

struct TrmvTemporalOutput {
  RgbPlane color;    // cbar_i
  RgbPlane fetched;  // cbar_{i-1}
  RgbPlane clamped;  // cbar*_{i-1}
  FloatPlane alpha;  // the alpha used
};

// The history bilinearly at p_prev = x_{i-1} in the previous image, taps outside it or without a surface
// dropped and the rest renormalised; false when no tap carries weight.
bool trmv_fetch_history(const TrmvHistory& prev, glm::vec2 p_prev, glm::vec3& out, Probe* probe = nullptr);

// cbar*_{i-1}: `history` clamped per channel to [mu - gamma sigma, mu + gamma sigma] of c~ over the (2r+1)^2
// window around (x, y) [TRMV21 Sec. 5]; gamma = 0 returns it unchanged.
glm::vec3 trmv_clamp_history(glm::vec3 history, const RgbPlane& filtered, const UIntPlane& mesh, float gamma,
                             int radius, int x, int y, Probe* probe = nullptr);

// The golden per-pixel function.
TrmvTemporalPixel trmv_temporal_pixel(const RgbPlane& filtered, const UIntPlane& mesh, const TrmvMotion& motion,
                                      const TrmvHistory& prev, const FloatPlane& alpha, const TrmvParams& params,
                                      int x, int y, Probe* probe = nullptr);

// Throws rtdr::Error unless the mesh, motion and (when given) validity, alpha and re-shaded planes have c~'s size
// and the previous id.mesh the history's: the checks of trmv_temporal_pass, which its port makes too
// (gpu/trmv_temporal_gpu.h).
void check_trmv_temporal_sizes(const RgbPlane& filtered, const UIntPlane& mesh, const TrmvMotion& motion,
                               const TrmvHistory& prev, const FloatPlane& alpha);

// trmv_temporal_pixel at every pixel (parallel over rows, deterministic). Throws rtdr::Error when the planes'
// sizes disagree.
TrmvTemporalOutput trmv_temporal_pass(const RgbPlane& filtered, const UIntPlane& mesh, const TrmvMotion& motion,
                                      const TrmvHistory& prev, const FloatPlane& alpha, const TrmvParams& params);

}  // namespace rtdr
