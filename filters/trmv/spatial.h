// TRMV's spatial filter of the current frame, step 1 of its pipeline [TRMV21 Sec. 5, "Choice of spatial
// filters"]: "For shadows, we simply implement a separable 31x31 joint bilateral filter [KCLU07]".
//
// Pass: trmv_spatial_pass(c, s, radius, sigma, edges) -> c~, the spatially filtered current frame (Eq. 2's c~_i).
//   in:  a scalar plane (visibility) or an RGB plane (illumination), the current G-buffer planes (depth, depth
//        gradient, normals, mesh ids), the radius and spatial std (trmv_params.h, scaled to the frame:
//        filters/trmv/footprint.h) or a std per pixel and axis, and SVGF's edge-stopping sigmas and epsilon
//        (svgf_params.h)
//   out: c~ after a horizontal, then a vertical 1-D pass. Each 1-D pass at pixel p over the taps q = p + k e,
//        k = -r .. r, e the pass's axis:
//          c'(p) = sum_k G(k; 0, sigma) w_z(p, q) w_n(p, q) c(q) / sum_k G(k; 0, sigma) w_z(p, q) w_n(p, q)
//        G(k; 0, sigma) = exp(-k^2 / (2 sigma^2)), w_z and w_n SVGF's depth and normal weights
//        [SVGF17 Eq. 3, Eq. 4], called from filters/svgf/edge_stopping.h as they are.
//
// Separable is an approximation, and it is the paper's: a joint bilateral's weights depend on p and q together,
// so the 2-D kernel is not the product of two 1-D kernels. Running a horizontal pass and then a vertical one
// (Pham and van Vliet 2005's separable bilateral) lets a tap reach p through a pixel of p's row, so an edge
// that crosses the row and the column away from p can leak through the corner; it costs 2 (2r + 1) taps instead
// of (2r + 1)^2, which is why the paper filters 31x31 this way. The clean-up filter (cleanup.h) runs the same
// 1-D pass with its own, per-pixel std.
//
// Choices the paper leaves open (filters/trmv/README.md, "Deviations and choices"):
// - The guides: the paper cites the joint bilateral [KCLU07] without naming its guide images; we use the
//   G-buffer's depth and normals, with SVGF's weights, as every other filter of this project does. There is no
//   range (colour) weight: the input is the noisy 1-spp frame, whose colour differences are mostly noise.
// - The spatial std is not given: spatial_sigma = 5 = radius / 3 (trmv_params.h).
// - Taps outside the image and taps without a surface are skipped (as filters/svgf/atrous.cpp does), and the
//   sum of the weights that remain renormalises. A pixel without a surface passes its value through.
// - The centre tap gets weight 1 directly: G(0) = 1, and w_z = w_n = 1 at q = p (atrous.cpp says why it is
//   written down rather than computed). So the sum of weights is >= 1 and the division is safe.
// - sigma = 0 is the identity, exactly (the 1-D pass returns its input).
#pragma once

#include "filters/image.h"
#include "filters/probe.h"
#include "filters/surface_planes.h"
#include "filters/svgf/svgf_params.h"
#include "filters/trmv/trmv_params.h"

#include <glm/glm.hpp>

namespace rtdr {

// The two axes of the separable filter: the step e from one tap to the next.
inline constexpr glm::ivec2 kTrmvHorizontal{1, 0};
inline constexpr glm::ivec2 kTrmvVertical{0, 1};

// G(k; 0, sigma) = exp(-k^2 / (2 sigma^2)): the spatial weight of a tap k pixels away, with peak 1 (not
// normalised: the filter divides by the sum of its weights).
float trmv_spatial_weight(float k, float sigma);

// The golden per-pixel function: one 1-D pass of the joint bilateral at pixel (x, y), taps (x, y) + k axis for
// k = -radius .. radius. T is float (visibility) or glm::vec3 (RGB).
template <class T>
T trmv_spatial_pixel(const Plane<T>& c, const SurfacePlanes& s, glm::ivec2 axis, int radius, float sigma,
                     const SvgfParams& edges, int x, int y, Probe* probe = nullptr);

// Throws rtdr::Error, naming `what`, unless the G-buffer planes are all w x h: the spatial filter's check, which
// the clean-up and their ports make too (gpu/trmv_spatial_gpu.h).
void check_trmv_surface_sizes(int w, int h, const SurfacePlanes& s, const char* what);

// One 1-D pass over the whole frame with a per-pixel std (parallel over rows, deterministic). `sigma` is the
// std at every pixel (the clean-up's std map, cleanup.h), or empty (width 0) for `sigma_all` everywhere.
template <class T>
Plane<T> trmv_spatial_axis(const Plane<T>& c, const SurfacePlanes& s, glm::ivec2 axis, int radius,
                           const FloatPlane& sigma, float sigma_all, const SvgfParams& edges);

// The spatial filter: the horizontal pass, then the vertical pass, with this radius and std (TrmvWindows'
// shadow_radius and shadow_sigma: spatial_radius and spatial_sigma scaled to the frame, filters/trmv/footprint.h);
// or with a std per pixel and axis (sigma_x for the horizontal pass, sigma_y for the vertical one: the penumbra
// filter, filters/trmv/penumbra.h). Throws rtdr::Error when the planes' sizes disagree.
template <class T>
Plane<T> trmv_spatial_pass(const Plane<T>& c, const SurfacePlanes& s, int radius, float sigma,
                           const SvgfParams& edges);
template <class T>
Plane<T> trmv_spatial_pass(const Plane<T>& c, const SurfacePlanes& s, int radius, const FloatPlane& sigma_x,
                           const FloatPlane& sigma_y, const SvgfParams& edges);

}  // namespace rtdr
