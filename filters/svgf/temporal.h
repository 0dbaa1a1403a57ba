// SVGF temporal accumulation [SVGF17 Sec. 4.1] and temporal moments [SVGF17 Sec. 4.2].
//
// Pass: temporal_pass(noisy, cur, prev, params) -> integrated colour C', moments mu1', mu2', history length n.
//   in:  the noisy (demodulated) colour C_i; the current G-buffer planes (depth, normals, mesh ids, motion);
//        the previous frame's history: colour C'_{i-1} (the previous first a-trous level's output, which
//        the pipeline supplies [SVGF17 Sec. 4.3]), moments mu1', mu2', length n and its G-buffer planes
//   out: C'_i = alpha C_i + (1 - alpha) C'_{i-1}, the same EMA for mu1' (of l) and mu2' (of l^2), where l is
//        the luminance of C_i, and the history length n (1 after a disocclusion)
//
// Each pixel back-projects along its motion vector to p' = pixel centre + motion, resamples the history
// with a 2x2 bilinear filter whose taps each pass or fail a consistency test (same mesh, depth, normal),
// falls back to a 3x3 search when every tap fails, and resets its history when that fails too.
//
// Deviations from the paper (for filters/svgf/README.md):
// - alpha_eff = max(alpha, 1/n) (Falcor's history-length ramp): the first frames after a disocclusion are
//   an exact running mean instead of an EMA started from one sample. SVGF17 Sec. 4.1 uses a fixed alpha.
// - The paper compares object-space normals; the G-buffer holds world-space normals (docs/buffers.md), so
//   a rotating object changes its normals between frames; temporal_normal_cosine leaves room for that.
// - "its weight is uniformly redistributed over consistent taps" [SVGF17 Sec. 4.1] is read as renormalising
//   the bilinear weights by the sum of the consistent taps' weights (as Falcor does): each consistent tap
//   keeps its share relative to the others. Adding equal shares of the lost weight to each consistent tap
//   is the other reading; it is not bilinear any more when the taps are unequal.
// - The history length is resampled like the colour, then rounded to whole frames (temporal.cpp says why).
#pragma once

#include "filters/image.h"
#include "filters/probe.h"
#include "filters/svgf/svgf_params.h"
#include "filters/surface_planes.h"

#include <glm/glm.hpp>

namespace rtdr {

// Consistency-test thresholds. SVGF17 Sec. 4.1 calls its tests "empirical similarity metrics" and gives no
// numbers, so these are ours; both are rows of svgf_params.h's table (defaults 0.1 and 0.9).
//
// Depth: a tap q is on the current surface when |z - z'| <= temporal_depth_relative * max(z, z') +
// |grad z(p) . (q - p')|. The relative term is the test of merian's reprojection_valid (LDAP/merian,
// src/merian-nodes/common/reprojection.glsl: a fraction of the larger depth) and absorbs the depth change of a camera moving along its axis: 10 % is a
// camera moving a tenth of the distance to the surface per frame. Distinct objects are told apart by the mesh
// id, so the depth test only has to split a mesh from itself (folds, far walls of a room), which are
// usually further apart. The gradient term is the depth change along the surface from p' to the tap
// centre under SVGF17 Eq. 3's local linear model; without it a surface seen at a grazing angle, whose depth
// changes by much more than 10 % per pixel, would fail its own taps (Falcor divides by fwidth(z) for the same
// reason).
// Normal: a tap is on the current surface when n(p) . n'(q) >= temporal_normal_cosine = 0.9 = cos(25.8 deg).
// Two faces of one mesh meeting at a right angle (dot 0) fail; the shading normals of one smooth surface a
// pixel apart, or a surface rotating by less than ~25 degrees per frame, pass.

// The previous frame's history. An empty history (color.width == 0) means "first frame": every pixel is a
// disocclusion. When not empty every plane has the size of `surface`.
struct TemporalHistory {
  RgbPlane color;        // C'_{i-1}: the previous frame's colour history (first a-trous level's output)
  FloatPlane moment1;    // mu1'_{i-1}: integrated first raw moment of luminance
  FloatPlane moment2;    // mu2'_{i-1}: integrated second raw moment of luminance
  FloatPlane length;     // n_{i-1}: history length in frames (0 where no surface)
  SurfacePlanes surface; // the previous frame's G-buffer planes, for the consistency tests
};

struct TemporalOutput {
  RgbPlane color;      // C'_i
  FloatPlane moment1;  // mu1'_i
  FloatPlane moment2;  // mu2'_i
  FloatPlane length;   // n_i
};

// A-SVGF's adaptive temporal weights, in place of the constant alpha and alpha_mu [ASVGF18 Sec. 4]: per pixel,
// alpha_i for the colour and alpha_mu_i for the moments, both made by A-SVGF's adaptive_alpha pass
// (filters/asvgf/adaptive_alpha.h, [ASVGF18 Eq. 15]), and the lambda they were made from. With restart_history the
// history length falls with the history's weight, n_{i-1} <- (1 - lambda) n_{i-1}, so that a dropped history
// (lambda = 1) counts as a disocclusion: n = 1, and the variance is estimated spatially, as the paper says
// ("When the history is dropped, A-SVGF performs the variance estimate spatially" [ASVGF18 Sec. 4]).
struct TemporalAdaptive {
  const FloatPlane* lambda = nullptr;         // lambda_max per pixel
  const FloatPlane* alpha = nullptr;          // alpha_i per pixel
  const FloatPlane* alpha_moments = nullptr;  // alpha_mu_i per pixel
  bool restart_history = true;                // filters/asvgf/asvgf_params.h, history_rule 0
};

// One pixel of TemporalOutput.
struct TemporalPixel {
  glm::vec3 color{0.0f};
  float moment1 = 0.0f;
  float moment2 = 0.0f;
  float length = 0.0f;
};

// The consistency test of one history tap: does previous-frame pixel q show the surface that current pixel
// (x, y) shows, back-projected to p_prev? q must lie inside the previous image and match in mesh id, depth
// and normal (thresholds above) [SVGF17 Sec. 4.1].
bool temporal_tap_consistent(const SurfacePlanes& cur, const SurfacePlanes& prev, int x, int y, glm::ivec2 q,
                             glm::vec2 p_prev, const SvgfParams& params, Probe* probe = nullptr);

// The golden per-pixel function. Where (x, y) sees no surface every output is 0.
// With `adaptive`, alpha and alpha_mu are A-SVGF's per pixel (above).
TemporalPixel temporal_pixel(const RgbPlane& noisy, const SurfacePlanes& cur, const TemporalHistory& prev,
                             const SvgfParams& params, int x, int y, Probe* probe = nullptr,
                             const TemporalAdaptive* adaptive = nullptr);

// temporal_pixel at every pixel (parallel over rows, deterministic). Throws rtdr::Error when the planes'
// sizes disagree.
TemporalOutput temporal_pass(const RgbPlane& noisy, const SurfacePlanes& cur, const TemporalHistory& prev,
                             const SvgfParams& params, const TemporalAdaptive* adaptive = nullptr);

}  // namespace rtdr
