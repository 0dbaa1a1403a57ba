// TRMV's spatial filter of glossy indirect light: the BRDF lobe's footprint [TRMV21 Sec. 5, after LLK*19].
// TRMV21 Sec. 5: "For glossy reflections, we refer to the filtering method in [LLK*19]" (Liu et al., "Cinematic
// Rendering in UE4 with Real-Time Ray Tracing and Denoising", Ray Tracing Gems 2019): a reflection filter whose
// kernel is the footprint of the surface's BRDF lobe, projected into screen space from the hit distance and the
// roughness, so that a mirror is hardly filtered and a rough reflector is filtered widely.
//
// Pass: trmv_reflection_pass(c, s, footprint, radius, edges) -> c~, the spatially filtered glossy light.
//   in:  the 1-spp glossy light (indirect.glossy); the current G-buffer planes; the lobe's footprint per pixel,
//        Sigma_i = b1 b1^T + b2 b2^T in pixels^2 (glossy.footprint, motion/glossy.h: the cone of the GGX lobe's
//        angular std from the reflected point's virtual image to the reflector, cut by the reflector's plane and
//        projected by the current camera: [TRMV21 Eq. 5]'s construction, with this frame's camera), where it has
//        one; the window's radius (15 at 1080p, the shadow filter's, scaled: filters/trmv/footprint.h)
//   out: at pixel p, over the (2r + 1)^2 taps q = p + d:
//          c~(p) = sum_q g(d) w_z(p, q) w_n(p, q) c(q) / sum_q g(d) w_z(p, q) w_n(p, q)
//          g(d) = exp(-d^T S^-1 d / 2),  S = Sigma_i(p) + I / 12
//        w_z and w_n SVGF's depth and normal weights [SVGF17 Eq. 3, Eq. 4] (filters/svgf/edge_stopping.h).
//
// What is ours, not Liu et al.'s description:
// - The footprint is the one Eq. 5 already tracks: "the intersected region is a Gaussian in positions as well as in
//   the image space" [TRMV21 Sec. 4.2]. Its width is motion/glossy.h's choice (the angle holding 68 % of GGX's
//   half-vectors, doubled). The distance d = |v - s^C| is this pixel's own hit distance (its one sample's), not a
//   filtered one.
// - S adds a pixel's own spread, I / 12 (the variance of a box of one pixel), so that a mirror's footprint of a
//   fraction of a pixel keeps the centre and S stays invertible.
// - Where the pixel has no footprint (no secondary hit, the lobe reaching past the plane's horizon, a reflector
//   seen from behind: glossy.footprint.valid = 0) the lobe is wider than any window, and the filter is the window's
//   round Gaussian of std r / 3, the shadow filter's.
// - No BRDF ratio weights (Liu et al. weigh the neighbours' samples by the pixel's BRDF): the glossy light is
//   demodulated and the footprint already holds the lobe's extent.
// - The kernel is not separable (the ellipse is tilted), so it is a 2-D gather of (2r + 1)^2 taps.
// - Taps outside the image or without a surface are skipped and the weights renormalised; the centre tap gets
//   weight 1 directly (g(0) = 1, w_z = w_n = 1 at q = p); a pixel without a surface passes through.
#pragma once

#include "filters/image.h"
#include "filters/probe.h"
#include "filters/surface_planes.h"
#include "filters/svgf/svgf_params.h"

#include <glm/glm.hpp>

namespace rtdr {

// The lobe's footprint per pixel: Sigma_i's entries (pixels^2) and where it has one.
struct TrmvFootprint {
  FloatPlane xx, xy, yy;
  UIntPlane valid;

  static TrmvFootprint from_frame(const Frame& frame);  // glossy.footprint.*; throws rtdr::Error when missing
};

// S^-1 of the filter at one pixel: (Sigma_i + I / 12)^-1 with a footprint, else (sigma^2 I)^-1, sigma = radius / 3.
glm::mat2 trmv_reflection_precision(const TrmvFootprint& f, int radius, int x, int y);
// g(d) = exp(-d^T S^-1 d / 2).
float trmv_reflection_weight(const glm::mat2& precision, glm::vec2 d);

// The golden per-pixel function.
glm::vec3 trmv_reflection_pixel(const RgbPlane& c, const SurfacePlanes& s, const TrmvFootprint& f, int radius,
                                const SvgfParams& edges, int x, int y, Probe* probe = nullptr);

// Throws rtdr::Error unless the G-buffer and footprint planes have c's size.
void check_trmv_reflection_sizes(const RgbPlane& c, const SurfacePlanes& s, const TrmvFootprint& f);

// trmv_reflection_pixel at every pixel (parallel over rows, deterministic).
RgbPlane trmv_reflection_pass(const RgbPlane& c, const SurfacePlanes& s, const TrmvFootprint& f, int radius,
                              const SvgfParams& edges);

// A pixel's own spread, the variance of a box one pixel wide: 1/12 px^2 per axis.
inline constexpr float kTrmvPixelVariance = 1.0f / 12.0f;

}  // namespace rtdr
