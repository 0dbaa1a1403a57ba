// The gradient's reconstruction on the stratum grid [ASVGF18 Sec. 3.4, Eq. 7-12]. See gradient_atrous.h.
#include "filters/asvgf/gradient_atrous.h"

#include "core/parallel.h"
#include "filters/svgf/atrous.h"
#include "filters/svgf/edge_stopping.h"
#include "filters/svgf/prefilter.h"

#include <string>

namespace rtdr {

GradientPixel gradient_atrous_pixel(const GradientValues& in, const FloatPlane& prefiltered_variance,
                                    const GradientImage& image, int level, const SvgfParams& params, int sx, int sy,
                                    Probe* probe) {
  const SurfacePlanes& g = image.surface;
  const GradientPixel centre_values{in.delta.at(sx, sy), in.norm.at(sx, sy), in.luminance.at(sx, sy),
                                    in.variance.at(sx, sy)};
  note(probe, "iteration k", float(level), "[ASVGF18 Eq. 7]");
  if (!g.covered(sx, sy)) {
    note(probe, "no surface in the stratum: passed through", 1.0f);
    return centre_values;
  }
  const int step = 1 << level;  // 2^k strata between taps
  const AtrousKernel box = atrous_kernel(3);  // the 3x3 box h [ASVGF18 Sec. 3.4]
  const float z_p = g.depth.at(sx, sy), l_p = centre_values.luminance, var_p = prefiltered_variance.at(sx, sy);
  const glm::vec2 grad_z_p = g.depth_grad.at(sx, sy);
  const glm::vec3 n_p = g.normal.at(sx, sy);
  note(probe, "step 2^k (strata)", float(step), "[ASVGF18 Sec. 3.4]");
  note(probe, "z(p)", z_p, "[ASVGF18 Eq. 10]");
  note(probe, "n(p)", n_p, "[ASVGF18 Eq. 9]");
  note(probe, "l^(k)(p)", l_p, "[ASVGF18 Eq. 11]");
  note(probe, "g3x3(Var(l^(k)))(p)", var_p, "[ASVGF18 Eq. 11]");

  float sum_hw = 0.0f, sum_h2w2_var = 0.0f;
  GradientPixel sum;  // the weighted sums of delta, Delta and l^
  for (int j = -1; j <= 1; ++j)
    for (int k = -1; k <= 1; ++k) {
      const int qx = sx + k * step, qy = sy + j * step;
      if (probe) note_group(probe, "tap (" + std::to_string(qx - sx) + ", " + std::to_string(qy - sy) + ")");
      if (!inside(g.depth, qx, qy)) { note(probe, "skipped: outside the grid", 1.0f); continue; }
      if (!g.covered(qx, qy)) { note(probe, "skipped: no surface in the stratum", 1.0f); continue; }
      const float h = box.h[k + 1] * box.h[j + 1];
      float w = 1.0f;  // the centre tap: every edge-stopping weight is 1 there
      if (k != 0 || j != 0) {
        // p - q in pixels: the depth gradient is per pixel, a stratum step is s pixels.
        const glm::vec2 offset_pq = float(image.stratum_size) * glm::vec2(float(sx - qx), float(sy - qy));
        const float w_z = weight_depth(z_p, g.depth.at(qx, qy), grad_z_p, offset_pq, params.sigma_z, params.epsilon);
        const float w_n = weight_normal(n_p, g.normal.at(qx, qy), params.sigma_n);
        const float w_l = weight_luminance(l_p, in.luminance.at(qx, qy), var_p, params.sigma_l, params.epsilon);
        note(probe, "w_z", w_z, "[ASVGF18 Eq. 10] = [SVGF17 Eq. 3]");
        note(probe, "w_n", w_n, "[ASVGF18 Eq. 9] = [SVGF17 Eq. 4]");
        note(probe, "w_l", w_l, "[ASVGF18 Eq. 11] = [SVGF17 Eq. 5]");
        // w^(k)(p, q) = w_z w_n w_l^(k) [ASVGF18 Eq. 8].
        w = w_z * w_n * w_l;
      }
      note(probe, "h w", h * w, "[ASVGF18 Eq. 7]");
      note(probe, "delta(q), Delta(q)", glm::vec2(in.delta.at(qx, qy), in.norm.at(qx, qy)), "[ASVGF18 Eq. 12]");
      sum_hw += h * w;
      sum.luminance += h * w * in.luminance.at(qx, qy);
      sum.delta += h * w * in.delta.at(qx, qy);  // with the luminance's weights [ASVGF18 Eq. 12]
      sum.norm += h * w * in.norm.at(qx, qy);
      sum_h2w2_var += h * h * w * w * in.variance.at(qx, qy);
    }
  // l^(k+1)(p) = sum h w l^(k)(q) / sum h w [ASVGF18 Eq. 7]; delta^, Delta^ alike [ASVGF18 Eq. 12].
  GradientPixel out;
  out.luminance = sum.luminance / sum_hw;
  out.delta = sum.delta / sum_hw;
  out.norm = sum.norm / sum_hw;
  // Var(l^(k+1)) = sum h^2 w^2 Var(l^(k)) / (sum h w)^2 [SVGF17 Sec. 4.3].
  out.variance = sum_h2w2_var / (sum_hw * sum_hw);
  note_group(probe, "sum");
  note(probe, "sum h w", sum_hw, "[ASVGF18 Eq. 7]");
  note(probe, "l^(k+1)(p)", out.luminance, "[ASVGF18 Eq. 7]");
  note(probe, "delta^(k+1)(p)", out.delta, "[ASVGF18 Eq. 12]");
  note(probe, "Delta^(k+1)(p)", out.norm, "[ASVGF18 Eq. 12]");
  note(probe, "Var(l^(k+1))(p)", out.variance, "[SVGF17 Sec. 4.3]");
  return out;
}

GradientValues gradient_atrous_level(const GradientValues& in, const GradientImage& image, int level,
                                     const SvgfParams& params) {
  const int w = in.luminance.width, h = in.luminance.height;
  GradientValues out{FloatPlane(w, h), FloatPlane(w, h), FloatPlane(w, h), FloatPlane(w, h)};
  const FloatPlane prefiltered = prefilter_variance(in.variance);  // g3x3(Var(l^(k))) [ASVGF18 Eq. 11]
  parallel_rows(h, [&](int sy) {
    for (int sx = 0; sx < w; ++sx) {
      const GradientPixel r = gradient_atrous_pixel(in, prefiltered, image, level, params, sx, sy);
      out.delta.at(sx, sy) = r.delta;
      out.norm.at(sx, sy) = r.norm;
      out.luminance.at(sx, sy) = r.luminance;
      out.variance.at(sx, sy) = r.variance;
    }
  });
  return out;
}

}  // namespace rtdr
