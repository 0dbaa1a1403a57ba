// The edge-avoiding a-trous filter of Dammertz et al. 2010 [EAW10], the baseline SVGF compares against [SVGF17 Sec. 5.4,
// Table 1], and the origin of its spatial filter [SVGF17 Sec. 4.3]. At
// level i, pixel p gathers the 5 x 5 taps q = p + 2^i (dx, dy), dx, dy in -2..2, with the B3-spline kernel
// h(q) = h(dx) h(dy) (the same kernel SVGF took over, filters/svgf/atrous.h) and the weight
//   w(p, q) = w_rt w_n w_x,   w_j = exp(-||I_j(p) - I_j(q)||^2 / sigma_j^2)                     [EAW10]
// on the colour (rt, "ray traced"), the world normal (n) and the world position (x); the colour's sigma is
// halved every level, sigma_rt 2^-i, as the filtered colours grow smoother [EAW10]. The output is
//   c_{i+1}(p) = sum h w c_i(q) / sum h w                                                     [EAW10]
// Unlike SVGF there is no variance: the colour weight uses a fixed scale, not one adapted to the noise.
//
// Choices, shared with filters/svgf/atrous.cpp so the two compare fairly: taps outside the image and taps
// without a surface (id.mesh = kInvalidId) are skipped, a pixel without a surface passes through. The centre
// tap needs no special case here: its three differences are exactly 0, so its weight is exp(-0) = 1.
#include "filters/baselines/eaw.h"

#include "core/error.h"
#include "core/parallel.h"
#include "filters/svgf/atrous.h"

#include <cmath>
#include <string>

namespace rtdr {

std::vector<ParamInfo> eaw_param_table() { return {RTDR_EAW_PARAMS(RTDR_PARAM_ROW)}; }
std::vector<double> param_values(const EawParams& params) { return {RTDR_EAW_PARAMS(RTDR_PARAM_VALUE)}; }
void validate(const EawParams& p) { check_params("eaw", eaw_param_table(), param_values(p)); }
std::string describe(const EawParams& p) { return describe_params(eaw_param_table(), param_values(p)); }

float eaw_sigma_rt(const EawParams& p, int level) { return std::ldexp(p.sigma_rt, -level); }  // sigma_rt 2^-i

namespace {

// w_j = exp(-||I(p) - I(q)||^2 / sigma^2) [EAW10], the one Gaussian shape of all three weights.
float gaussian_weight(const glm::vec3& I_p, const glm::vec3& I_q, float sigma) {
  const glm::vec3 d = I_p - I_q;
  return std::exp(-glm::dot(d, d) / (sigma * sigma));
}

// w(p, q) = w_rt w_n w_x [EAW10 weights], each a Gaussian of a difference, each term recorded.
float eaw_weight(const RgbPlane& color, const RgbPlane& position, const SurfacePlanes& s, float sigma_rt_i,
                 const EawParams& p, int x, int y, int qx, int qy, Probe* probe) {
  const float w_rt = gaussian_weight(color.at(x, y), color.at(qx, qy), sigma_rt_i);
  note(probe, "w_rt", w_rt, "[EAW10] colour, sigma_rt 2^-i");
  const float w_n = gaussian_weight(s.normal.at(x, y), s.normal.at(qx, qy), p.sigma_n);
  note(probe, "w_n", w_n, "[EAW10] normal");
  const float w_x = gaussian_weight(position.at(x, y), position.at(qx, qy), p.sigma_x);
  note(probe, "w_x", w_x, "[EAW10] position");
  return w_rt * w_n * w_x;
}

}  // namespace

glm::vec3 eaw_pixel(const RgbPlane& color, const RgbPlane& position, const SurfacePlanes& s, int level,
                    const EawParams& p, int x, int y, Probe* probe) {
  note(probe, "level i", float(level), "[EAW10]");
  // No surface, no G-buffer to compare with: the input passes through.
  if (!s.covered(x, y)) {
    note(probe, "no surface: passed through", 1.0f);
    return color.at(x, y);
  }
  const AtrousKernel kernel = atrous_kernel(5);  // the B3 spline (1/16, 1/4, 3/8, 1/4, 1/16)
  const int step = 1 << level;                   // 2^i: the taps' spacing at level i
  const float sigma_rt_i = eaw_sigma_rt(p, level);
  note(probe, "step 2^i", float(step), "[EAW10]");
  note(probe, "sigma_rt 2^-i", sigma_rt_i, "[EAW10] colour sigma, halved per level");

  float sum_hw = 0.0f;      // sum h w, the normaliser
  glm::vec3 sum_hwc(0.0f);  // sum h w c_i(q)
  for (int j = -kernel.radius; j <= kernel.radius; ++j)
    for (int k = -kernel.radius; k <= kernel.radius; ++k) {
      const int qx = x + k * step, qy = y + j * step;  // the tap q, 2^i (k, j) away from p
      if (probe) note_group(probe, "tap (" + std::to_string(qx - x) + ", " + std::to_string(qy - y) + ")");
      // Off the image or off every surface: skipped; sum h w renormalises over the rest.
      if (!inside(color, qx, qy)) { note(probe, "skipped: outside the image", 1.0f); continue; }
      if (!s.covered(qx, qy)) { note(probe, "skipped: no surface", 1.0f); continue; }
      const float h = kernel.h[k + kernel.radius] * kernel.h[j + kernel.radius];  // h(q) = h(dx) h(dy)
      note(probe, "h(q)", h, "[EAW10] B3 spline");
      const float w = eaw_weight(color, position, s, sigma_rt_i, p, x, y, qx, qy, probe);
      note(probe, "w", w, "[EAW10] w_rt w_n w_x");
      note(probe, "h w", h * w, "[EAW10]");
      sum_hw += h * w;                      // the normaliser
      sum_hwc += h * w * color.at(qx, qy);  // the weighted colours
    }

  note_group(probe, "sum");
  note(probe, "sum h w", sum_hw, "[EAW10]");
  // c_{i+1}(p) = sum h w c_i(q) / sum h w [EAW10]; the centre's weight h(0) h(0) > 0 keeps it finite.
  const glm::vec3 c_next = sum_hwc / sum_hw;
  note(probe, "c_{i+1}(p)", c_next, "[EAW10]");
  return c_next;
}

RgbPlane eaw_level(const RgbPlane& color, const RgbPlane& position, const SurfacePlanes& s, int level,
                   const EawParams& p) {
  RgbPlane out(color.width, color.height);
  parallel_rows(color.height, [&](int y) {
    for (int x = 0; x < color.width; ++x) out.at(x, y) = eaw_pixel(color, position, s, level, p, x, y);
  });
  return out;
}

RgbPlane eaw_filter(const RgbPlane& color, const RgbPlane& position, const SurfacePlanes& s, const EawParams& p) {
  validate(p);
  RgbPlane c = color;  // c_0: the noisy input
  for (int i = 0; i < p.levels; ++i) c = eaw_level(c, position, s, i, p);  // c_{i+1} from c_i
  return c;
}

}  // namespace rtdr
