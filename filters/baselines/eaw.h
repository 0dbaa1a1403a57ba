// The edge-avoiding a-trous wavelet filter of Dammertz et al. 2010 [EAW10] ("Edge-avoiding a-trous wavelet
// transform for fast global illumination filtering", HPG 2010): the baseline SVGF builds on. The same a-trous
// scheme and B3-spline kernel as SVGF [SVGF17 Eq. 1], with Gaussian edge-stopping weights on colour, normal and
// world position, a colour sigma halved every level, and no variance guidance.
// Inputs: noisy colour, world position (G-buffer position.X/Y/Z), SurfacePlanes (normal, id.mesh), EawParams.
// Output: the filtered colour after `levels` levels (eaw_filter), or one level (eaw_level, eaw_pixel).
#pragma once

#include "filters/image.h"
#include "filters/probe.h"
#include "filters/surface_planes.h"

#include <vector>

// Every EAW tunable, declared once, in the format of filters/svgf/svgf_params.h:
// X(type, name, default, min, max, symbol, source)
//
// In [EAW10] sigma_rt, sigma_n and sigma_x are inputs of the filter (uniforms of its shader); their right values
// depend on a scene's units and radiance scale, so ours are derived from our scenes (scenes/README.md: metres;
// a Cornell box 2 m wide seen from 3.9 m, a 16 x 11 m floor; demodulated radiance of order 0..10):
// - sigma_rt = 1 (radiance units): at level 0 a colour difference of 1 keeps weight exp(-1) = 0.37, so 1 spp
//   noise of that size is smoothed while a jump of 3 (exp(-9) = 1e-4) is kept; halved per level, at level 4 it
//   is 1/16, since the colours being compared have been smoothed by then [EAW10].
// - sigma_n = 0.3: with unit normals ||n_p - n_q||^2 = 2 (1 - cos theta), so a 10 degree bend keeps 0.71, a
//   30 degree bend 0.05 and a 90 degree crease exp(-22) ~ 0.
// - sigma_x = 0.25 m: neighbours on one surface are a pixel footprint apart, about 7 to 14 mm at 512 to 256
//   pixels wide in the Cornell box, so level 4's farthest tap (32 pixels, 0.2 to 0.45 m) still weighs 0.5 to
//   0.04, while a 1 m jump in depth (the tall block in front of the back wall) weighs exp(-16) ~ 1e-7.
// - levels = 5: the five levels of SVGF17 Sec. 4.3, so both filters reach equally far.
#define RTDR_EAW_PARAMS(X)                                                                                     \
  X(float, sigma_rt, 1.0f, 1e-6f, 1e9f, "sigma_rt", "EAW10 w_rt; radiance units, halved per level (see eaw.h)") \
  X(float, sigma_n, 0.3f, 1e-6f, 1e9f, "sigma_n", "EAW10 w_n; on ||n_p - n_q|| of unit normals (see eaw.h)")   \
  X(float, sigma_x, 0.25f, 1e-6f, 1e9f, "sigma_x", "EAW10 w_x; metres, world position (see eaw.h)")             \
  X(int, levels, 5, 0, 10, "", "five a-trous levels as in SVGF17 Sec. 4.3")

#include "filters/params.h"

namespace rtdr {

struct EawParams {
  RTDR_EAW_PARAMS(RTDR_PARAM_FIELD)
};

// One row per parameter, for the CLI and the printed configuration (filters/params.h).
std::vector<ParamInfo> eaw_param_table();
std::vector<double> param_values(const EawParams& params);
// Throws rtdr::Error naming the first parameter outside its range.
void validate(const EawParams& p);
std::string describe(const EawParams& p);

// The level-i colour sigma: sigma_rt 2^-i [EAW10].
float eaw_sigma_rt(const EawParams& p, int level);

// The golden per-pixel function: level `level` at (x, y). Taps outside the image and taps without a surface are
// skipped; a pixel without a surface returns its input.
glm::vec3 eaw_pixel(const RgbPlane& color, const RgbPlane& position, const SurfacePlanes& s, int level,
                    const EawParams& p, int x, int y, Probe* probe = nullptr);

// One level over the frame, parallel over rows.
RgbPlane eaw_level(const RgbPlane& color, const RgbPlane& position, const SurfacePlanes& s, int level,
                   const EawParams& p);

// Levels 0 .. p.levels - 1, each on the previous one's output; the result is the last, smoothest level c_N
// (the detail coefficients are discarded).
RgbPlane eaw_filter(const RgbPlane& color, const RgbPlane& position, const SurfacePlanes& s, const EawParams& p);

}  // namespace rtdr
