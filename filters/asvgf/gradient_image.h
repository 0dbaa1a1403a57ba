// A-SVGF's gradient image: one value per stratum of the frame [ASVGF18 Sec. 3.4, Eq. 3, Eq. 13].
//
// Pass: gradient_image(noisy, gradient samples, surface, s) -> per-stratum planes of ceil(W/s) x ceil(H/s).
//   in:  one stream's noisy (demodulated) colour C_i; the frame's gradient samples (gradient.source, and the
//        previous frame's luminance at each source, gradient.prev_<stream>; trace/gradients.h); the G-buffer;
//        the stratum size s of the render (its header's rtdr.gradient.stratum_size)
//   out: per stratum p
//        delta(p) = l(C_i(jbar)) - f_{i-1}(j)               the temporal gradient [ASVGF18 Eq. 3]
//        Delta(p) = max(l(C_i(jbar)), f_{i-1}(j))           its normalisation [ASVGF18 Eq. 13]
//          both 0 where no gradient sample landed in the stratum
//          (with GradientForm's variants: abs(delta), or the per-sample ratio r and the sample-present weight, below)
//        l^(0)(p) the mean luminance of the stratum's pixels, Var(l^(0)(p)) their variance [ASVGF18 Sec. 3.4]
//        z, grad z, n and the mesh id of the stratum's representative pixel: the geometry the reconstruction's
//        edge-stopping functions compare [ASVGF18 Eq. 9-10]
//
// Choices the paper leaves open (filters/asvgf/README.md, "Deviations and choices"):
// - A stratum's geometry is that of its centre pixel (s/2, s/2), clipped to a partial stratum; when the centre
//   sees no surface, the first pixel in raster order that does. A stratum where no pixel sees a surface has
//   mesh kInvalidId: the reconstruction skips it, as SVGF's a-trous skips surfaceless pixels.
// - l^(0) and Var(l^(0)) are over the stratum's pixels that see a surface; Var is the population variance of
//   those luminances ("the variance of the luminance inside of one stratum"), not the variance of their mean.
// - A stratum holds at most one gradient sample (trace/gradients.cpp keeps one per stratum); a second one is a
//   malformed frame and throws.
#pragma once

#include "core/frame.h"
#include "filters/image.h"
#include "filters/probe.h"
#include "filters/surface_planes.h"

#include <string>

namespace rtdr {

// How a gradient sample enters the values the reconstruction filters (asvgf_params.h's last rows; README.md,
// "Deviations and choices"). With f_now and f_before its two luminances:
//   after (the paper)     delta = f_now - f_before [Eq. 3], abs(f_now - f_before) with `absolute`;
//                         Delta = max(f_now, f_before) [Eq. 13]; both are reconstructed, and the adaptive_alpha pass
//                         forms lambda = min(1, k (abs(delta^) / Delta^)^p) [Eq. 14 for k = p = 1]
//   before (Q2RTX, RTGL1) delta = r = min(1, k (abs(f_now - f_before) / max(f_now, f_before))^p), 0 where both are 0;
//                         Delta = 1, the sample-present weight; lambda = delta^ / Delta^: the mean of r over the
//                         samples in reach, weighted by the reconstruction's weights. Empty strata hold (0, 0), so the
//                         density of samples still cancels in the quotient [ASVGF18 Sec. 3.5].
struct GradientForm {
  bool before = false;    // gradient_normalize 1
  bool absolute = false;  // gradient_abs 1 (after only: r is unsigned already)
  int exponent = 1;       // p, gradient_exponent
  float scale = 1.0f;     // k, gradient_scale
};

// The four values the reconstruction filters, per stratum [ASVGF18 Eq. 7, Eq. 12].
struct GradientValues {
  FloatPlane delta;      // delta: the temporal gradient of luminance [ASVGF18 Eq. 3] (before: the ratio r)
  FloatPlane norm;       // Delta: max of the two luminances [ASVGF18 Eq. 13] (before: 1 where a sample is)
  FloatPlane luminance;  // l^: the stratum's mean luminance [ASVGF18 Eq. 7]
  FloatPlane variance;   // Var(l^) [ASVGF18 Eq. 11]
};

struct GradientImage {
  int stratum_size = 0;
  GradientValues values;
  SurfacePlanes surface;  // per stratum: depth, depth_grad (per pixel, as depth.dX/dY), normal, mesh; no motion
};

// One stratum's values and geometry.
struct GradientStratum {
  float delta = 0.0f, norm = 0.0f, luminance = 0.0f, variance = 0.0f;
  glm::ivec2 representative{-1};  // the pixel whose geometry the stratum takes; (-1, -1) when none sees a surface
};

// The values one gradient sample with luminances f_now (this frame's, at jbar) and f_before (the previous frame's,
// at j) adds to the gradient image, (delta, Delta) as `form` makes them (above).
glm::vec2 gradient_sample_values(float f_now, float f_before, const GradientForm& form = {}, Probe* probe = nullptr);

// The golden per-stratum function: stratum (sx, sy) of s x s pixels.
GradientStratum gradient_stratum(const RgbPlane& noisy, const UIntPlane& source, const FloatPlane& prev_luminance,
                                 const SurfacePlanes& surface, int s, int sx, int sy, const GradientForm& form = {},
                                 Probe* probe = nullptr);

// The stratum grid's planes for these inputs, all 0, with s: ceil(w / s) x ceil(h / s) strata. Throws rtdr::Error
// when the planes' sizes disagree or s < 1: the checks of gradient_image, which its port makes too
// (gpu/asvgf_gradient_gpu.h).
GradientImage gradient_image_grid(const RgbPlane& noisy, const UIntPlane& source, const FloatPlane& prev_luminance,
                                  const SurfacePlanes& surface, int s);

// Every stratum (parallel over stratum rows, deterministic). Throws rtdr::Error when the planes' sizes disagree
// or s < 1.
GradientImage gradient_image(const RgbPlane& noisy, const UIntPlane& source, const FloatPlane& prev_luminance,
                             const SurfacePlanes& surface, int s, const GradientForm& form = {});

// The stratum size s the frame's gradient samples were made with, from the render's header
// (rtdr.gradient.stratum_size, trace/gradients.h) [ASVGF18 Sec. 3.3]. Throws rtdr::Error naming the frame and
// `method` when it is missing or not a stratum size (1 to 64).
int frame_stratum_size(const Frame& frame, const std::string& method);
// The same rule as a problem for filters/input_check.h: "" when the header holds a stratum size (then *s is set
// to it), else what is wrong, without the frame's name.
std::string stratum_size_problem(const Frame& frame, int* s);

// A per-stratum plane replicated to the frame's pixels (pixel (x, y) takes stratum (x / s, y / s)), so that
// dumps stay frame-sized layers.
FloatPlane replicate_strata(const FloatPlane& strata, int s, int width, int height);

}  // namespace rtdr
