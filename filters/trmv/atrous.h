// TRMV's spatial filter of diffuse indirect light and of each cone [TRMV21 Sec. 5, "Choice of spatial filters"]:
// "For global illumination, we use a 4-level a-trous wavelet filter, essentially 32x32", and the cones are
// filtered "for each cone individually" [TRMV21 Sec. 4.3].
//
// Pass: trmv_atrous_pass(c, s, levels, edges) -> c~, the spatially filtered current frame.
//   in:  an RGB plane (the 1-spp diffuse light, or one cone's estimates), the current G-buffer planes, the number of
//        levels (4 at 1080p, scaled: filters/trmv/footprint.h) and SVGF's edge-stopping sigmas and epsilon
//   out: c after levels 0 .. L-1; level i at pixel p gathers the 3x3 taps q = p + 2^i (dx, dy), dx, dy in -1..1:
//          c_{i+1}(p) = sum h(q) w_z(p, q) w_n(p, q) c_i(q) / sum h(q) w_z(p, q) w_n(p, q)
//        h = (1/3, 1/3, 1/3) per axis, A-SVGF's "simple 3x3 box" [ASVGF18 Sec. 4] (filters/svgf/atrous.h's
//        atrous_kernel(3)), w_z and w_n SVGF's depth and normal weights [SVGF17 Eq. 3, Eq. 4] called from
//        filters/svgf/edge_stopping.h as they are.
//
// "Essentially 32x32": four levels of a 3x3 kernel, taps 1, 2, 4, 8 apart, reach 1 + 2 + 4 + 8 = 15 pixels each way,
// a 31x31 footprint. SVGF's 5x5 kernel would reach 30 each way (61x61), twice the paper's size.
//
// Choices the paper leaves open (filters/trmv/README.md, "Deviations and choices"):
// - SVGF's a-trous at level i is filters/svgf/atrous.cpp's atrous_pixel; it weighs luminance too (w_l), against the
//   variance that SVGF's temporal moments estimate. TRMV filters before it accumulates: there are no moments, and
//   the input is one path a pixel, whose luminance differences are the sample's noise (a 1-spp diffuse pixel is 0
//   or one bright path), so a luminance weight would keep the noise it is meant to remove. Ours weighs geometry
//   only, w_z w_n, and the a-trous is a geometry-aware blur of 31x31, as the shadow filter is.
// - Taps outside the image and taps without a surface are skipped, the centre tap gets w = 1 directly, a pixel
//   without a surface passes through: atrous_pixel's rules (filters/svgf/atrous.cpp says why).
#pragma once

#include "filters/image.h"
#include "filters/probe.h"
#include "filters/surface_planes.h"
#include "filters/svgf/svgf_params.h"

namespace rtdr {

// The golden per-pixel function: level `level` (taps 2^level apart) at pixel (x, y).
glm::vec3 trmv_atrous_pixel(const RgbPlane& c, const SurfacePlanes& s, int level, const SvgfParams& edges, int x, int y,
                            Probe* probe = nullptr);

// One level over the frame (parallel over rows, deterministic).
RgbPlane trmv_atrous_level(const RgbPlane& c, const SurfacePlanes& s, int level, const SvgfParams& edges);

// Levels 0 .. levels - 1, each on the one before. Throws rtdr::Error when the G-buffer is not c's size.
RgbPlane trmv_atrous_pass(const RgbPlane& c, const SurfacePlanes& s, int levels, const SvgfParams& edges);

}  // namespace rtdr
