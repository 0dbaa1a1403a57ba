// One level of the edge-avoiding a-trous wavelet filter [SVGF17 Sec. 4.3]. At level i, pixel p gathers the taps
// q = p + 2^i (dx, dy), dx, dy in -2..2 (kernel_size 5) or -1..1 (kernel_size 3): the same 25 or 9 taps at
// every level, spread twice as far apart each time ("a-trous", with holes). Each tap is weighted by the kernel
// h(q) = h(dx) h(dy) and by the edge-stopping weight w(p, q) = w_z w_n w_l [SVGF17 Eq. 2, Eq. 3-5]:
//   c_{i+1}(p)      = sum h w c_i(q) / sum h w                       [SVGF17 Eq. 1]
//   Var(c_{i+1}(p)) = sum h^2 w^2 Var(c_i(q)) / (sum h w)^2          [SVGF17 Sec. 4.3, unnumbered]
// The second line is the variance of the first when the Var(c_i(q)) are uncorrelated and the weights are held
// fixed, as the paper assumes. w_l compares luminances of this level's input c_i against the prefiltered
// variance g3x3(Var(c_i)) at p (filters/svgf/prefilter.h); the propagated variance is the unfiltered one.
//
// Choices the paper leaves open:
// - Taps outside the image are skipped, not clamped: a clamped tap would count the border pixel again, with
//   the weight of a pixel that does not exist. The normalisation by sum h w makes up for the missing taps.
// - Taps without a surface (id.mesh = kInvalidId) are skipped: there is no G-buffer to compare against, and the
//   background's radiance (0, docs/buffers.md) is not illumination of any surface.
// - A pixel without a surface passes its colour and variance through unchanged.
// - The centre tap gets w = 1 directly. Eq. 3-5 all give 1 at q = p (zero differences; 0 / epsilon = 0 in
//   Eq. 3 and 5, n . n = 1 in Eq. 4), but a unit normal stored in float can have n . n = 1 - 6e-8, whose
//   128th power is 1 - 8e-6. Falcor's SVGF likewise accumulates the centre before its tap loop.
// - Since the centre always contributes h(0) h(0) > 0, sum h w > 0 and the divisions are safe.
#include "filters/svgf/atrous.h"

#include "core/color.h"
#include "core/error.h"
#include "core/parallel.h"
#include "filters/svgf/atrous_shared.h"
#include "filters/svgf/edge_stopping.h"
#include "filters/svgf/prefilter.h"

#include <algorithm>
#include <cmath>
#include <string>

namespace rtdr {

AtrousKernel atrous_kernel(int kernel_size) {
  // The weights are written once, in atrous_shared.h, which the Vulkan port (atrous.comp) includes too.
  if (kernel_size == 5) return {2, {kAtrousB3Outer, kAtrousB3Inner, kAtrousB3Centre, kAtrousB3Inner, kAtrousB3Outer}};
  // A-SVGF names a "simple 3x3 box filter" [ASVGF18 Sec. 4, Sec. 3.4]: equal weights. Their scale cancels in
  // Eq. 1 and in the variance equation (h^2 over (h)^2); 1/3 makes h sum to 1 like the B3 kernel.
  // (The paper quotes a 49 x 49 region for five levels. Counting taps: the last level alone spans 2 * 16 + 1 = 33
  // pixels, the five levels chained reach 1 + 2 + 4 + 8 + 16 = 31 pixels each way, 63 x 63. SVGF's "65 x 65"
  // [SVGF17 Sec. 4.3] is the last 5x5 level alone, 2 * 2 * 16 + 1.)
  if (kernel_size == 3) return {1, {kAtrousBox, kAtrousBox, kAtrousBox}};
  throw Error("svgf a-trous kernel_size must be 3 or 5, got " + std::to_string(kernel_size));
}

namespace {

// What the weights need to know about p, read once per pixel.
struct Centre {
  int x, y;
  float z;            // z(p), linear view depth
  glm::vec2 grad_z;   // grad z(p), per pixel [SVGF17 Eq. 3]
  glm::vec3 n;        // n(p), world space [SVGF17 Eq. 4]
  float l;            // l_i(p), luminance of this level's input [SVGF17 Eq. 5]
  float var_g3x3;     // g3x3(Var(l_i))(p) [SVGF17 Eq. 5]
};

Centre read_centre(const RgbPlane& color, const FloatPlane& prefiltered_variance, const SurfacePlanes& s, int x,
                   int y, Probe* probe) {
  const Centre c{x,  y, s.depth.at(x, y), s.depth_grad.at(x, y), s.normal.at(x, y), luminance(color.at(x, y)),
                 prefiltered_variance.at(x, y)};
  note(probe, "z(p)", c.z, "[SVGF17 Eq. 3]");
  note(probe, "grad z(p)", c.grad_z, "[SVGF17 Eq. 3]");
  note(probe, "n(p)", c.n, "[SVGF17 Eq. 4]");
  note(probe, "l(p)", c.l, "[SVGF17 Eq. 5]");
  note(probe, "g3x3(Var)(p)", c.var_g3x3, "[SVGF17 Eq. 5]");
  return c;
}

// w(p, q) = w_z w_n w_l [SVGF17 Eq. 2] for a tap q != p.
float tap_weight(const Centre& p, const RgbPlane& color, const SurfacePlanes& s, const SvgfParams& params, int qx,
                 int qy, Probe* probe) {
  // p - q in pixels, at the tap's real distance (the step 2^i included) [SVGF17 Eq. 3].
  const glm::vec2 offset_pq(float(p.x - qx), float(p.y - qy));
  note(probe, "p - q", offset_pq, "[SVGF17 Eq. 3]");
  const float z_q = s.depth.at(qx, qy);
  note(probe, "z(q)", z_q, "[SVGF17 Eq. 3]");
  const glm::vec3 n_q = s.normal.at(qx, qy);
  note(probe, "n(q)", n_q, "[SVGF17 Eq. 4]");
  const float l_q = luminance(color.at(qx, qy));
  note(probe, "l(q)", l_q, "[SVGF17 Eq. 5]");
  const float w_z = weight_depth(p.z, z_q, p.grad_z, offset_pq, params.sigma_z, params.epsilon);
  note(probe, "w_z", w_z, "[SVGF17 Eq. 3]");
  const float w_n = weight_normal(p.n, n_q, params.sigma_n);
  note(probe, "w_n", w_n, "[SVGF17 Eq. 4]");
  const float w_l = weight_luminance(p.l, l_q, p.var_g3x3, params.sigma_l, params.epsilon);
  note(probe, "w_l", w_l, "[SVGF17 Eq. 5]");
  // w(p, q) = w_z w_n w_l [SVGF17 Eq. 2]. (atrous.comp fuses the three into one exp and one log, GPU-only.)
  return w_z * w_n * w_l;
}

// w(p, p) = 1: Eq. 3-5 at q = p, written down rather than computed (see the banner).
float centre_weight(Probe* probe) {
  note(probe, "p - q", glm::vec2(0.0f), "[SVGF17 Eq. 3]");
  note(probe, "w_z", 1.0f, "[SVGF17 Eq. 3] at q = p: exp(-0 / epsilon)");
  note(probe, "w_n", 1.0f, "[SVGF17 Eq. 4] at q = p: (n . n)^sigma_n");
  note(probe, "w_l", 1.0f, "[SVGF17 Eq. 5] at q = p: exp(-0 / (sigma_l sqrt(g3x3 Var) + epsilon))");
  return 1.0f;
}

std::string tap_label(int dx, int dy) { return "tap (" + std::to_string(dx) + ", " + std::to_string(dy) + ")"; }

}  // namespace

AtrousPixel atrous_pixel(const RgbPlane& color, const FloatPlane& variance, const FloatPlane& prefiltered_variance,
                         const SurfacePlanes& s, int level, const SvgfParams& params, int x, int y, Probe* probe) {
  note(probe, "level i", float(level), "[SVGF17 Sec. 4.3]");
  // No surface, nothing to compare with: the input passes through.
  if (!s.covered(x, y)) {
    note(probe, "no surface: passed through", 1.0f);
    return {color.at(x, y), variance.at(x, y)};
  }
  const AtrousKernel kernel = atrous_kernel(params.kernel_size);
  const int step = 1 << level;  // 2^i: the taps' spacing at level i
  note(probe, "step 2^i", float(step), "[SVGF17 Sec. 4.3]");
  const Centre centre = read_centre(color, prefiltered_variance, s, x, y, probe);

  float sum_hw = 0.0f;              // sum h w        [SVGF17 Eq. 1, denominator]
  glm::vec3 sum_hwc(0.0f);          // sum h w c_i(q) [SVGF17 Eq. 1, numerator]
  float sum_h2w2_var = 0.0f;        // sum h^2 w^2 Var(c_i(q)) [SVGF17 Sec. 4.3]
  for (int j = -kernel.radius; j <= kernel.radius; ++j)
    for (int k = -kernel.radius; k <= kernel.radius; ++k) {
      const int qx = x + k * step, qy = y + j * step;  // the tap q, 2^i (k, j) away from p
      if (probe) note_group(probe, tap_label(qx - x, qy - y));
      // Off the image: skipped; sum h w renormalises over the taps that remain.
      if (!inside(color, qx, qy)) { note(probe, "skipped: outside the image", 1.0f); continue; }
      // No surface at q: nothing to filter there.
      if (!s.covered(qx, qy)) { note(probe, "skipped: no surface", 1.0f); continue; }
      const float h = kernel.h[k + kernel.radius] * kernel.h[j + kernel.radius];  // h(q) = h(dx) h(dy)
      note(probe, "h(q)", h, params.kernel_size == 5 ? "[SVGF17 Eq. 1] B3 spline" : "[ASVGF18 Sec. 4] 3x3 box");
      // w(p, q) [SVGF17 Eq. 2]; 1 at the centre tap, where every edge-stopping weight is 1 (see the banner).
      const float w = (k == 0 && j == 0) ? centre_weight(probe) : tap_weight(centre, color, s, params, qx, qy, probe);
      note(probe, "w", w, "[SVGF17 Eq. 2]");
      note(probe, "h w", h * w, "[SVGF17 Eq. 1]");
      const float var_q = variance.at(qx, qy);
      note(probe, "Var(q)", var_q, "[SVGF17 Sec. 4.3]");
      sum_hw += h * w;                            // the normaliser
      sum_hwc += h * w * color.at(qx, qy);        // the weighted colours
      sum_h2w2_var += h * h * w * w * var_q;      // the weighted variances, weights squared
    }

  note_group(probe, "sum");
  note(probe, "sum h w", sum_hw, "[SVGF17 Eq. 1]");
  note(probe, "sum h^2 w^2 Var", sum_h2w2_var, "[SVGF17 Sec. 4.3]");
  // c_{i+1}(p) = sum h w c_i(q) / sum h w [SVGF17 Eq. 1].
  const glm::vec3 c_next = sum_hwc / sum_hw;
  note(probe, "c_{i+1}(p)", c_next, "[SVGF17 Eq. 1]");
  // Var(c_{i+1}(p)) = sum h^2 w^2 Var(c_i(q)) / (sum h w)^2 [SVGF17 Sec. 4.3].
  const float var_next = sum_h2w2_var / (sum_hw * sum_hw);
  note(probe, "Var(c_{i+1}(p))", var_next, "[SVGF17 Sec. 4.3]");
  return {c_next, var_next};
}

AtrousOutput atrous_level(const RgbPlane& color, const FloatPlane& variance, const SurfacePlanes& s, int level,
                          const SvgfParams& params) {
  atrous_kernel(params.kernel_size);  // throws on a bad kernel_size here, before the rows run in parallel
  AtrousOutput out{RgbPlane(color.width, color.height), FloatPlane(color.width, color.height),
                   prefilter_variance(variance)};  // g3x3(Var(c_i)), steering w_l [SVGF17 Eq. 5]
  parallel_rows(color.height, [&](int y) {
    for (int x = 0; x < color.width; ++x) {
      const AtrousPixel r = atrous_pixel(color, variance, out.prefiltered_variance, s, level, params, x, y);
      out.color.at(x, y) = r.color;
      out.variance.at(x, y) = r.variance;
    }
  });
  return out;
}

}  // namespace rtdr
