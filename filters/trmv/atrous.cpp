// TRMV's a-trous filter of diffuse indirect light [TRMV21 Sec. 5]. What it computes and why w_z w_n only:
// filters/trmv/atrous.h.
#include "filters/trmv/atrous.h"

#include "core/parallel.h"
#include "filters/svgf/atrous.h"
#include "filters/svgf/edge_stopping.h"
#include "filters/trmv/spatial.h"

#include <string>

namespace rtdr {

glm::vec3 trmv_atrous_pixel(const RgbPlane& c, const SurfacePlanes& s, int level, const SvgfParams& edges, int x, int y,
                            Probe* probe) {
  note(probe, "level i", float(level), "[TRMV21 Sec. 5] 4-level a-trous");
  if (!s.covered(x, y)) return c.at(x, y);  // no surface: passed through
  const AtrousKernel kernel = atrous_kernel(3);  // the 3x3 box [ASVGF18 Sec. 4], h = 1/3 per axis
  const int step = 1 << level;                   // 2^i: the taps' spacing at level i
  const float z_p = s.depth.at(x, y);
  const glm::vec2 grad_z_p = s.depth_grad.at(x, y);
  const glm::vec3 n_p = s.normal.at(x, y);
  float sum_hw = 0.0f;      // sum h w
  glm::vec3 sum_hwc(0.0f);  // sum h w c_i(q)
  for (int j = -kernel.radius; j <= kernel.radius; ++j)
    for (int k = -kernel.radius; k <= kernel.radius; ++k) {
      const int qx = x + k * step, qy = y + j * step;  // the tap q, 2^i (k, j) away from p
      // Off the image, or no surface at q: skipped; sum h w renormalises over the taps that remain.
      if (!inside(c, qx, qy) || !s.covered(qx, qy)) continue;
      const float h = kernel.h[k + kernel.radius] * kernel.h[j + kernel.radius];  // h(q) = h(dx) h(dy)
      float w = 1.0f;  // the centre: w_z = w_n = 1 at q = p (filters/svgf/atrous.cpp says why it is written down)
      if (k != 0 || j != 0) {
        const glm::vec2 offset_pq(float(x - qx), float(y - qy));  // p - q at the tap's real distance [SVGF17 Eq. 3]
        const float w_z = weight_depth(z_p, s.depth.at(qx, qy), grad_z_p, offset_pq, edges.sigma_z, edges.epsilon);
        const float w_n = weight_normal(n_p, s.normal.at(qx, qy), edges.sigma_n);
        w = w_z * w_n;  // no w_l: the input is one path a pixel (atrous.h)
        if (probe) {
          note_group(probe, "tap (" + std::to_string(qx - x) + ", " + std::to_string(qy - y) + ")");
          note(probe, "w_z", w_z, "[SVGF17 Eq. 3]");
          note(probe, "w_n", w_n, "[SVGF17 Eq. 4]");
        }
      }
      sum_hw += h * w;
      sum_hwc += h * w * c.at(qx, qy);
    }
  note_group(probe, "sum");
  note(probe, "sum h w", sum_hw, "[SVGF17 Eq. 1] with w = w_z w_n");
  // c_{i+1}(p) = sum h w c_i(q) / sum h w [SVGF17 Eq. 1, the weights of atrous.h]; the centre keeps sum h w > 0.
  const glm::vec3 c_next = sum_hwc / sum_hw;
  note(probe, "c_{i+1}(p)", c_next, "[TRMV21 Sec. 5] a-trous level");
  return c_next;
}

RgbPlane trmv_atrous_level(const RgbPlane& c, const SurfacePlanes& s, int level, const SvgfParams& edges) {
  RgbPlane out(c.width, c.height);
  parallel_rows(c.height, [&](int y) {
    for (int x = 0; x < c.width; ++x) out.at(x, y) = trmv_atrous_pixel(c, s, level, edges, x, y);
  });
  return out;
}

RgbPlane trmv_atrous_pass(const RgbPlane& c, const SurfacePlanes& s, int levels, const SvgfParams& edges) {
  check_trmv_surface_sizes(c.width, c.height, s, "trmv a-trous");
  RgbPlane out = c;
  for (int level = 0; level < levels; ++level) out = trmv_atrous_level(out, s, level, edges);
  return out;
}

}  // namespace rtdr
