// One level i of SVGF's edge-avoiding a-trous wavelet filter [SVGF17 Sec. 4.3, Eq. 1, 2 and the unnumbered
// variance equation], with the 5x5 B3-spline kernel of SVGF or the 3x3 box of A-SVGF [ASVGF18 Sec. 4].
// Inputs: the level's colour c_i (demodulated illumination), its luminance variance Var(c_i), the G-buffer
// (SurfacePlanes), the level i (taps 2^i pixels apart) and SvgfParams. Outputs: c_{i+1}, Var(c_{i+1}), and the
// prefiltered variance g3x3(Var(c_i)) that steered the luminance weight (kept for dumps and probes).
// The pipeline (filters/svgf/svgf.cpp) runs levels 0 .. atrous_levels - 1, feeding each output to the next.
#pragma once

#include "filters/image.h"
#include "filters/probe.h"
#include "filters/surface_planes.h"
#include "filters/svgf/svgf_params.h"

namespace rtdr {

// The 1D a-trous kernel h, taps k = -radius .. radius at h[k + radius]; the 2D kernel is h(dx) h(dy).
// kernel_size 5: the B3 spline h = (1/16, 1/4, 3/8, 1/4, 1/16) [SVGF17 Eq. 1]. kernel_size 3: "a simple 3x3
// box filter" [ASVGF18 Sec. 4], h = (1/3, 1/3, 1/3). Both sum to 1. Throws rtdr::Error for any other size.
struct AtrousKernel {
  int radius = 0;
  float h[5] = {};
};
AtrousKernel atrous_kernel(int kernel_size);

// The result at one pixel: c_{i+1}(p) [SVGF17 Eq. 1] and Var(c_{i+1}(p)) [SVGF17 Sec. 4.3].
struct AtrousPixel {
  glm::vec3 color{0.0f};
  float variance = 0.0f;
};

struct AtrousOutput {
  RgbPlane color;                   // c_{i+1}
  FloatPlane variance;              // Var(c_{i+1}): steers level i + 1
  FloatPlane prefiltered_variance;  // g3x3(Var(c_i)): steered w_l at this level [SVGF17 Eq. 5]
};

// The golden per-pixel function: level `level` at pixel (x, y). prefiltered_variance is g3x3(variance)
// (filters/svgf/prefilter.h). Taps outside the image and taps without a surface are skipped; a pixel without a
// surface returns its input. With a probe attached, every term of every tap is recorded.
AtrousPixel atrous_pixel(const RgbPlane& color, const FloatPlane& variance, const FloatPlane& prefiltered_variance,
                         const SurfacePlanes& s, int level, const SvgfParams& params, int x, int y,
                         Probe* probe = nullptr);

// One level over the whole frame: prefilters the variance, then runs atrous_pixel on every pixel.
AtrousOutput atrous_level(const RgbPlane& color, const FloatPlane& variance, const SurfacePlanes& s, int level,
                          const SvgfParams& params);

}  // namespace rtdr
