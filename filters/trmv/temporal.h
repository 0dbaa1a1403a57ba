// TRMV's temporal blend [TRMV21 Eq. 2] with the neighbourhood clamp of the history [TRMV21 Sec. 5].
//
// Pass: trmv_temporal_pass(c~, cur, motion, prev, alpha, params) -> cbar_i, the fetched and the clamped history.
//   in:  c~_i, the spatially filtered current frame (spatial.h); the current G-buffer planes (which pixels see a
//        surface, and what the history tests compare); one component's motion vectors m (previous position =
//        pixel centre + m, the convention of motion/backproject.h) with their validity and, per pixel, the test
//        a history tap must pass (TrmvMotion::test); the previous history cbar_{i-1} and the previous G-buffer
//        (empty history: the first frame); alpha per pixel (alpha^V of falloff.h for visibility, else the
//        constant alpha of trmv_params.h, which an empty alpha plane stands for); SVGF's consistency thresholds
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
// - Resampling: bilinear, the 2x2 pixel centres around x_{i-1}. A tap outside the previous image, without a
//   surface there (previous id.mesh = kInvalidId), or failing the pixel's history test is dropped, and the
//   remaining bilinear weights are renormalised by their sum (as SVGF's temporal pass does with failed taps).
// - The history test (TrmvMotion::test, per pixel): a history fetched along a vector is used only where the
//   previous pixel it reads is what that vector claims. The surface vector claims the same surface point: SVGF's
//   consistency test (mesh id, depth, normal; filters/svgf/temporal.h's temporal_tap_consistent, its thresholds).
//   The dual vector [TRMV21 Eq. 6] and the glossy vector [Eq. 5] claim the same mesh (the background beside the
//   occluder, the reflector): its normal and depth differ by design. The shadow vector [Eq. 3] claims a point of
//   the moving shadow, on whatever receiver: no test (Eq. 4 handles a different receiver), or the same mesh as an
//   option. kTrmvTestNone is also the paper's "Trad. (No clamp)" row, forced reuse.
// - No history (first frame, invalid vector, x_{i-1} off the previous image, every tap dropped): alpha = 1, so
//   cbar_i = c~_i, the spatial result alone; the fetched and clamped histories are 0 there, which gives w_C = 0
//   in Eq. 8.
// - A pixel without a surface passes c~ through with alpha = 1.
// - The clamp's window: c~ at the pixels of the (2r+1)^2 window inside the image that see a surface (the centre
//   always does) and, with `same_surface`, only those on the centre's surface (SVGF's consistency test between
//   two current pixels, so that the statistics of a slat do not bound the floor's history); mu and sigma are
//   their mean and population standard deviation, per RGB channel.
// - gamma = 0 switches the clamp off ("Trad. (No clamp)"), it does not clamp to mu.
#pragma once

#include "filters/image.h"
#include "filters/probe.h"
#include "filters/surface_planes.h"
#include "filters/svgf/svgf_params.h"
#include "filters/trmv/temporal_shared.h"  // kTrmvTestNone, kTrmvTestMesh, kTrmvTestSurface
#include "filters/trmv/trmv_params.h"

#include <glm/glm.hpp>

namespace rtdr {

// One component's motion vectors: m = x_{i-1} - x_i in pixels, and 1 where the vector is valid. An empty
// validity plane (width 0) means every vector is valid (the back-projected `motion` has none of its own).
// `test`: the history test of each pixel's vector, kTrmvTest* (temporal_shared.h); empty: kTrmvTestNone everywhere.
// At a pixel where `reshaded_valid` is 1 the history is `reshaded` instead of a fetch along m: the diffuse light
// re-shaded from the cones at the dual vector's target [TRMV21 Sec. 4.3, Eq. 11] (filters/trmv/reshade.h). Both
// empty: every history is fetched.
struct TrmvMotion {
  Vec2Plane motion;
  UIntPlane valid;
  UIntPlane test;
  RgbPlane reshaded;
  UIntPlane reshaded_valid;
};

// The previous frame's history of one component. An empty colour (width 0) means "first frame".
struct TrmvHistory {
  RgbPlane color;          // cbar_{i-1}
  SurfacePlanes surface;   // the previous frame's G-buffer: taps without a surface are dropped, the tests compare it
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

// Does previous pixel q pass current pixel (x, y)'s history test `test` (kTrmvTest*), reached at p_prev? q must
// lie inside the previous image and see a surface; kTrmvTestMesh adds the same mesh id, kTrmvTestSurface SVGF's
// consistency test (filters/svgf/temporal.h).
bool trmv_tap_passes(uint32_t test, const SurfacePlanes& cur, const SurfacePlanes& prev, int x, int y, glm::ivec2 q,
                     glm::vec2 p_prev, const SvgfParams& svgf, Probe* probe = nullptr);

// The bilinear taps of a fetch at p_prev = x_{i-1}: up to four previous pixels with their weights, renormalised to
// sum 1 over the taps kept.
struct TrmvHistoryTaps {
  glm::ivec2 q[4];
  float w[4] = {0.0f, 0.0f, 0.0f, 0.0f};
  int count = 0;
};
// The taps of pixel (x, y)'s history at p_prev in the previous image (`prev`, the previous G-buffer), the ones that
// fail `test` dropped; false when no tap carries weight.
bool trmv_history_taps(const SurfacePlanes& prev, glm::vec2 p_prev, const SurfacePlanes& cur, int x, int y,
                       uint32_t test, const SvgfParams& svgf, TrmvHistoryTaps& taps, Probe* probe = nullptr);
// sum_q w_q plane(q) over the taps.
glm::vec3 trmv_apply_taps(const RgbPlane& plane, const TrmvHistoryTaps& taps);

// The history of pixel (x, y) bilinearly at p_prev = x_{i-1} in the previous image, the taps that fail `test`
// dropped and the rest renormalised; false when no tap carries weight.
bool trmv_fetch_history(const TrmvHistory& prev, glm::vec2 p_prev, const SurfacePlanes& cur, int x, int y,
                        uint32_t test, const SvgfParams& svgf, glm::vec3& out, Probe* probe = nullptr);

// cbar*_{i-1}: `history` clamped per channel to [mu - gamma sigma, mu + gamma sigma] of c~ over the (2r+1)^2
// window around (x, y) [TRMV21 Sec. 5], with `same_surface` only its pixels on (x, y)'s surface; gamma = 0
// returns it unchanged.
glm::vec3 trmv_clamp_history(glm::vec3 history, const RgbPlane& filtered, const SurfacePlanes& cur, float gamma,
                             int radius, bool same_surface, const SvgfParams& svgf, int x, int y,
                             Probe* probe = nullptr);

// The golden per-pixel function.
TrmvTemporalPixel trmv_temporal_pixel(const RgbPlane& filtered, const SurfacePlanes& cur, const TrmvMotion& motion,
                                      const TrmvHistory& prev, const FloatPlane& alpha, const TrmvParams& params,
                                      const SvgfParams& svgf, int x, int y, Probe* probe = nullptr);

// Throws rtdr::Error unless the G-buffer, motion and (when given) validity, test, alpha and re-shaded planes have
// c~'s size and the previous G-buffer the history's: the checks of trmv_temporal_pass, which its port makes too
// (gpu/trmv_temporal_gpu.h).
void check_trmv_temporal_sizes(const RgbPlane& filtered, const SurfacePlanes& cur, const TrmvMotion& motion,
                               const TrmvHistory& prev, const FloatPlane& alpha);

// trmv_temporal_pixel at every pixel (parallel over rows, deterministic). Throws rtdr::Error when the planes'
// sizes disagree.
TrmvTemporalOutput trmv_temporal_pass(const RgbPlane& filtered, const SurfacePlanes& cur, const TrmvMotion& motion,
                                      const TrmvHistory& prev, const FloatPlane& alpha, const TrmvParams& params,
                                      const SvgfParams& svgf);

}  // namespace rtdr
