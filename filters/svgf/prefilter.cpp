// g3x3: the 3x3 Gaussian prefilter of the luminance variance [SVGF17 Sec. 4.4, Eq. 5]. Each output pixel is
// sum g(dx) g(dy) Var(p + (dx, dy)) over dx, dy in {-1, 0, 1}, g = (1/4, 1/2, 1/4); the weights sum to 1, so a
// constant variance stays constant.
//
// Borders are clamped: a tap outside the image reads the nearest edge pixel, so the weights still sum to 1
// there.
// Pixels without a surface are not skipped: the paper describes a plain 3x3 Gaussian of the variance image,
// and Falcor blurs every pixel alike. Where a surface meets the background the background's variance (0,
// docs/buffers.md) is averaged in, which lowers g3x3(Var) there and so makes w_l stricter along silhouettes,
// never looser; the background taps themselves are skipped by the a-trous.
#include "filters/svgf/prefilter.h"

#include "core/parallel.h"

#include <string>

namespace rtdr {

float prefilter_variance_pixel(const FloatPlane& variance, int x, int y, Probe* probe) {
  float sum = 0.0f;
  for (int dy = -1; dy <= 1; ++dy)
    for (int dx = -1; dx <= 1; ++dx) {
      // The binomial weight of this tap, g(dx) g(dy): 1/4 at the centre, 1/8 at the edges, 1/16 at the corners.
      const float g = kGaussian3[dx + 1] * kGaussian3[dy + 1];
      // The neighbour's variance, the border pixel where (x + dx, y + dy) falls outside.
      const float var_q = at_clamped(variance, x + dx, y + dy);
      sum += g * var_q;
      if (probe) note_group(probe, "g3x3 tap (" + std::to_string(dx) + ", " + std::to_string(dy) + ")");
      note(probe, "g", g, "[SVGF17 Sec. 4.4] 3x3 Gaussian");
      note(probe, "Var(q)", var_q, "[SVGF17 Sec. 4.4]");
    }
  note_group(probe, "g3x3");
  note(probe, "g3x3(Var)(p)", sum, "[SVGF17 Eq. 5]");
  return sum;
}

FloatPlane prefilter_variance(const FloatPlane& variance) {
  FloatPlane out(variance.width, variance.height);
  parallel_rows(variance.height, [&](int y) {
    for (int x = 0; x < variance.width; ++x) out.at(x, y) = prefilter_variance_pixel(variance, x, y);
  });
  return out;
}

}  // namespace rtdr
