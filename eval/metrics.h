// Image metrics of the evaluation: how far a filtered frame is from the reference, and how much a sequence
// flickers and lags. Every function takes (test, reference) in that order; images are RgbPlanes of equal size
// (rtdr::Error otherwise).
//
//   rmse, relmse     linear HDR radiance, all pixels and channels
//   ssim             display values in [0, 1] (data range L = 1), per channel, then averaged  [Wang04]
//   flip             linear display RGB in [0, 1]: the mean and the per-pixel map of LDR-FLIP  [FLIP20]
//   temporal_error   two consecutive frames: mean luminance of |a - b|  [SVGF17 Sec. 5.4]
//   lag_frames       a per-frame error series: frames after a sudden change until the error recovers
//
// Sources (paper keys as used in the comments):
//   [Wang04]    Wang, Bovik, Sheikh, Simoncelli 2004, "Image Quality Assessment: From Error Visibility to
//               Structural Similarity", IEEE TIP 13(4). Eq. 13 (SSIM with C1 = (K1 L)^2, C2 = (K2 L)^2),
//               Sec. III-C (the 11x11 circular-symmetric Gaussian window of sigma 1.5 normalised to unit sum,
//               Eq. 14-16 the weighted statistics, K1 = 0.01, K2 = 0.03, Eq. 17 the mean SSIM).
//   [FLIP20]    Andersson, Nilsson, Akenine-Moller, Oskarsson, Astrom, Fairchild 2020, "FLIP: A Difference
//               Evaluator for Alternating Images", Proc. ACM CGIT 3(2) (HPG 2020), with the authors' errata
//               (research.nvidia.com/publication/2020-07_FLIP): p. 10 "division by 100" should read 116.
//   [Rousselle11] Rousselle, Knaus, Zwicker 2011, "Adaptive Sampling and Reconstruction using Greedy Error
//               Minimization", ACM TOG 30(6): the relative MSE (x - y)^2 / (y^2 + eps).
//   [SVGF17]    Schied et al. 2017, Sec. 5.4: "average luminance of the difference between consecutive frames".
//
// SSIM choice: per channel (R, G, B separately, then the mean of the three), as scikit-image does with
// channel_axis, on the display values it is given (the evaluation passes the tone-mapped display frames,
// linear, in [0, 1]; see eval/experiment.h). The mean is taken over the pixels whose 11x11 window lies inside
// the image (scikit-image crops a 5-pixel border), so no border rule is needed. tests/eval_metrics_test.cpp
// checks ssim against scikit-image 0.19.3 on the stored pairs in tests/data/ssim/ (eval/make_ssim_fixtures.py).
//
// FLIP constants and where they were checked: the constants in metrics.cpp (the CSF Gaussians, q_c, p_c, p_t,
// w, q_f, the kernel radii) and the 67 PPD default here match the authors' reference implementation
// (NVlabs/flip, cpp/FLIP.h); the PPD formula and 67 also match the docs of the nv-flip bindings. The paper's
// own text could not be read through the search tool (only its abstract and errata), so the equation and
// section numbers of [FLIP20] are not cited below: the pipeline is described by its steps instead. No
// published reference value (a FLIP mean for a stored image pair) was found that the tests could check;
// they check closed forms (uniform images, where the feature term vanishes) and properties instead.
// Deviations from the reference implementation, none of which changes the method: RGB <-> XYZ uses the
// 4-decimal matrix of IEC 61966-2-1 and its exact inverse (the authors use a rational form of the same
// matrix; the two differ by about 1e-4), and the white point is that matrix times (1, 1, 1). The filters are
// applied separably, as the authors' current code does; a one-off comparison with an unseparated 2D
// implementation of the same pipeline (numpy/scipy, 40 x 30 random pair) agreed to 2e-6 per pixel.
#pragma once

#include "filters/image.h"

#include <vector>

namespace rtdr {

// Root mean squared error over all pixels and the three channels: sqrt(sum (x - y)^2 / (3 N)).
double rmse(const RgbPlane& test, const RgbPlane& reference);

// Relative MSE [Rousselle11]: mean over pixels and channels of (x - y)^2 / (y^2 + eps), y the reference.
// eps keeps dark reference pixels from dominating; 1e-2 is the value used across the MC-denoising
// literature (our choice; the eps printed in [Rousselle11] itself was not checked).
inline constexpr double kRelMseEpsilon = 1e-2;
double relmse(const RgbPlane& test, const RgbPlane& reference, double eps = kRelMseEpsilon);

// Mean SSIM [Wang04], per channel then averaged, data range L = 1. Images must be at least 11 x 11.
inline constexpr double kSsimK1 = 0.01, kSsimK2 = 0.03;  // [Wang04 Sec. III-C]
inline constexpr double kSsimSigma = 1.5;                // Gaussian window's sigma, pixels [Wang04 Sec. III-C]
inline constexpr int kSsimRadius = 5;  // int(3.5 * sigma + 0.5): 11 taps, scikit-image's truncation
double ssim(const RgbPlane& test, const RgbPlane& reference);

// LDR-FLIP [FLIP20]. Inputs: linear display RGB (e.g. filters/svgf/tonemap.h's output), clamped to [0, 1];
// FLIP's first step, sRGB -> linear, is therefore already done (sRGB-encoded images: decode them first).
// The viewing condition: pixels per degree = d * (R / W) * pi / 180 for a monitor of width W metres and R
// pixels seen from d metres; FLIP's default is d = 0.7 m, R = 3840, W = 0.7 m: 67.02, rounded to 67.
inline constexpr double kFlipDefaultPpd = 67.0;
struct FlipResult {
  double mean = 0.0;  // mean of the map: the single number FLIP's authors recommend reporting
  FloatPlane map;     // per-pixel FLIP error in [0, 1]
};
FlipResult flip(const RgbPlane& test, const RgbPlane& reference, double pixels_per_degree = kFlipDefaultPpd);

// Temporal error [SVGF17 Sec. 5.4] of two consecutive frames: mean over pixels of luminance(|a - b|), the
// absolute difference taken per channel, then Rec. 709 luminance (core/color.h). See metrics.cpp for why
// not |luminance(a) - luminance(b)|, which is never larger.
double temporal_error(const RgbPlane& current, const RgbPlane& previous);

// The relative error of the image's mean luminance, |mean L(test) - mean L(reference)| / mean L(reference):
// noise averages out over the image, bias does not, so after a sudden change in lighting (a light switched
// on) it shows how far a temporal method's history still lags, free of the per-pixel noise that dominates
// RMSE at 1 spp. 0 when the reference is black.
double brightness_error(const RgbPlane& test, const RgbPlane& reference);

// A region of an image: one byte per pixel, row-major, nonzero where the pixel belongs to the region.
using Region = std::vector<uint8_t>;
// rmse over the region's pixels only; NaN when the region is empty.
double rmse(const RgbPlane& test, const RgbPlane& reference, const Region& region);
// The signed brightness error of a region, (sum L(test) - sum L(reference)) / sum L(reference) over its
// pixels: > 0 too bright, < 0 too dark; 0 when the reference is black there. The image's brightness_error is
// |brightness_bias| over every pixel, and there a lagging history can hide: too bright where a light left
// and too dark where it arrived, the two cancel in the image's mean (filters/asvgf/README.md, falling-light).
double brightness_bias(const RgbPlane& test, const RgbPlane& reference, const Region& region);

// The moving umbrae of a sequence under a still camera, Fig. 5's "umbra" [ASVGF18 Sec. 5.2]: for each frame,
// the pixels whose reference direct light is below kUmbraFraction of the most that pixel receives in any
// frame of the sequence. Only pixels that see the same surface point throughout count (its world position
// within 1 % of its depth of where it was in the first frame, never empty), and only where some frame gives
// them direct light. Inputs, one plane per frame: the luminance of the reference's demodulated `direct` layer,
// its `position` and its `depth.Z`. Under a moving camera hardly a pixel keeps its point, and the regions are
// (nearly) empty.
inline constexpr double kUmbraFraction = 0.1;
std::vector<Region> umbra_regions(const std::vector<FloatPlane>& direct_luminance,
                                  const std::vector<RgbPlane>& position, const std::vector<FloatPlane>& depth);

// Lag of a per-frame error series after a sudden change at frame `change_frame` (the first frame that shows
// the change): the number of frames k >= 0 until error[change_frame + k] is at or below `threshold`, so 0
// means no lag at all. -1 if the series never gets back there.
int lag_frames(const std::vector<double>& error, int change_frame, double threshold);
// The same with threshold = (mean error over frames [0, change_frame)) * (1 + tolerance): back to the error
// level the method had before the change, within a relative tolerance. Needs change_frame >= 1.
int lag_frames_relative(const std::vector<double>& error, int change_frame, double tolerance);

}  // namespace rtdr
