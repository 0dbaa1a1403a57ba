// SVGF variance estimation [SVGF17 Sec. 4.2]: the per-pixel variance of luminance that steers the a-trous
// luminance weight [SVGF17 Eq. 5].
//
// Pass: variance_pass(t, cur, params) -> sigma'^2 per pixel.
//   in:  the temporal pass's output t (integrated moments mu1', mu2' and history length n, temporal.h); the
//        current G-buffer planes (depth, depth gradient, normals, mesh ids)
//   out: sigma'^2 >= 0; 0 where no surface
//
// Where the history is long enough (n >= variance_min_history, 4 in the paper) the temporal estimate
//   sigma'^2 = mu2' - mu1'^2                                   [SVGF17 Sec. 4.2]
// Where it is shorter (the first frames after a disocclusion) the spatial estimate: the same formula on
// moments averaged over a 7x7 neighbourhood with bilateral weights w = w_z w_n [SVGF17 Sec. 4.2, Eq. 3, 4].
//
// Choices the paper leaves open (for filters/svgf/README.md):
// - The 7x7 filter averages the INTEGRATED MOMENTS mu1', mu2' (as Falcor does), not the luminance of the
//   integrated colour. Both estimates then estimate the same quantity, the variance of one sample's
//   luminance: at n = 1 the moments are l and l^2, and their spatial average is the sample variance of the
//   raw samples around p; at n = 2, 3 it averages short temporal moments. The integrated colour is the wrong
//   input: it is already averaged over n frames (its spread shrinks like 1/n) and, through the colour history,
//   over the previous frame's first a-trous level, so it would underestimate the noise.
// - No luminance weight (the paper names only "depths and world-space normals"), and no boost: Falcor
//   multiplies the spatial estimate by 4/n to filter harder just after a disocclusion. That factor is not in
//   the paper; it would overstate the variance 4x at n = 1 (tests/svgf_variance_test.cpp measures both
//   estimates against the true variance) and drop it by a quarter when n reaches 4.
#pragma once

#include "filters/image.h"
#include "filters/probe.h"
#include "filters/svgf/svgf_params.h"
#include "filters/surface_planes.h"
#include "filters/svgf/temporal.h"
#include "filters/svgf/variance_shared.h"  // kVarianceSpatialRadius, written once for C++ and GLSL

namespace rtdr {

// Which estimate a covered pixel with history length n takes: the spatial one where n < variance_min_history
// [SVGF17 Sec. 4.2]. variance_pixel branches on it; the dumps show it per pixel (filter.<s>.variance.spatial).
bool variance_is_spatial(float n, const SvgfParams& params);
// That choice at every pixel: 1 where the 7x7 spatial estimate was taken, 0 where mu2' - mu1'^2 or no surface.
FloatPlane variance_spatial_plane(const FloatPlane& length, const UIntPlane& mesh, const SvgfParams& params);

// The golden per-pixel function: sigma'^2 at (x, y), 0 where no surface.
float variance_pixel(const TemporalOutput& t, const SurfacePlanes& cur, const SvgfParams& params, int x, int y,
                     Probe* probe = nullptr);

// The spatial estimate alone, whatever n is (variance_pixel calls it where n < variance_min_history): for
// tests, and for comparing the two estimates at one pixel.
float variance_spatial_pixel(const TemporalOutput& t, const SurfacePlanes& cur, const SvgfParams& params, int x,
                             int y, Probe* probe = nullptr);

// variance_pixel at every pixel (parallel over rows, deterministic). Throws rtdr::Error when the planes'
// sizes disagree.
FloatPlane variance_pass(const TemporalOutput& t, const SurfacePlanes& cur, const SvgfParams& params);

}  // namespace rtdr
