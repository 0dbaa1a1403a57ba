// TRMV's separable joint-bilateral spatial filter [TRMV21 Sec. 5, "Choice of spatial filters"]. What the pass
// computes, its inputs, outputs and choices: filters/trmv/spatial.h.
#include "filters/trmv/spatial.h"

#include "core/error.h"
#include "core/parallel.h"
#include "filters/svgf/edge_stopping.h"

#include <cmath>
#include <string>

namespace rtdr {
void check_trmv_surface_sizes(int w, int h, const SurfacePlanes& s, const char* what) {
  const bool ok = has_size(s.depth, w, h) && has_size(s.depth_grad, w, h) && has_size(s.normal, w, h) &&
                  has_size(s.mesh, w, h);
  if (!ok)
    throw Error(std::string(what) + ": the G-buffer planes are not all " + std::to_string(w) + "x" +
                std::to_string(h) + " like the filtered plane");
}

float trmv_spatial_weight(float k, float sigma) {
  // G(k; 0, sigma) with its peak normalised to 1 [TRMV21 Sec. 5: the joint bilateral's spatial Gaussian].
  return std::exp(-(k * k) / (2.0f * sigma * sigma));
}

template <class T>
T trmv_spatial_pixel(const Plane<T>& c, const SurfacePlanes& s, glm::ivec2 axis, int radius, float sigma,
                     const SvgfParams& edges, int x, int y, Probe* probe) {
  note(probe, "sigma", sigma, "[TRMV21 Sec. 5] spatial std, pixels");
  // No surface, nothing to compare with; and std 0 keeps every tap but the centre at weight 0: the identity.
  if (!s.covered(x, y) || !(sigma > 0.0f)) {
    note(probe, "passed through", 1.0f);
    return c.at(x, y);
  }
  const float z_p = s.depth.at(x, y);
  const glm::vec2 grad_z_p = s.depth_grad.at(x, y);
  const glm::vec3 n_p = s.normal.at(x, y);
  float sum_w = 1.0f;      // sum of the weights, the centre's 1 included
  T sum_wc = c.at(x, y);   // sum of the weighted values, the centre's included
  for (int k = -radius; k <= radius; ++k) {
    if (k == 0) continue;  // the centre, weight 1, is in the sums already (spatial.h)
    const glm::ivec2 q = glm::ivec2(x, y) + k * axis;  // the tap, k pixels along the axis
    // Off the image, or no surface there: skipped; the weights that remain renormalise.
    if (!inside(c, q.x, q.y) || !s.covered(q.x, q.y)) continue;
    const glm::vec2 offset_pq = glm::vec2(float(x - q.x), float(y - q.y));  // p - q in pixels [SVGF17 Eq. 3]
    // G(k; 0, sigma) w_z w_n: the spatial Gaussian times SVGF's depth and normal weights [SVGF17 Eq. 3, Eq. 4].
    const float g = trmv_spatial_weight(float(k), sigma);
    const float w_z = weight_depth(z_p, s.depth.at(q.x, q.y), grad_z_p, offset_pq, edges.sigma_z, edges.epsilon);
    const float w_n = weight_normal(n_p, s.normal.at(q.x, q.y), edges.sigma_n);
    const float w = g * w_z * w_n;
    if (probe) {
      note_group(probe, "tap " + std::to_string(k));
      note(probe, "G(k; 0, sigma)", g, "[TRMV21 Sec. 5] spatial Gaussian");
      note(probe, "w_z", w_z, "[SVGF17 Eq. 3]");
      note(probe, "w_n", w_n, "[SVGF17 Eq. 4]");
    }
    sum_w += w;
    sum_wc += w * c.at(q.x, q.y);
  }
  note_group(probe, "sum");
  note(probe, "sum w", sum_w, "[TRMV21 Sec. 5] joint bilateral normaliser");
  // c'(p) = sum_k G w_z w_n c(q) / sum_k G w_z w_n [TRMV21 Sec. 5: the joint bilateral, one axis].
  return sum_wc / sum_w;
}

template <class T>
Plane<T> trmv_spatial_axis(const Plane<T>& c, const SurfacePlanes& s, glm::ivec2 axis, int radius,
                           const FloatPlane& sigma, float sigma_all, const SvgfParams& edges) {
  check_trmv_surface_sizes(c.width, c.height, s, "trmv spatial filter");
  const bool per_pixel = sigma.width != 0;
  if (per_pixel && (sigma.width != c.width || sigma.height != c.height))
    throw Error("trmv spatial filter: the std plane is not the frame's size");
  Plane<T> out(c.width, c.height);
  parallel_rows(c.height, [&](int y) {
    for (int x = 0; x < c.width; ++x) {
      const float sigma_p = per_pixel ? sigma.at(x, y) : sigma_all;
      out.at(x, y) = trmv_spatial_pixel(c, s, axis, radius, sigma_p, edges, x, y);
    }
  });
  return out;
}

template <class T>
Plane<T> trmv_spatial_pass(const Plane<T>& c, const SurfacePlanes& s, int radius, float sigma,
                           const SvgfParams& edges) {
  // Horizontal, then vertical: the separable form of the 31x31 joint bilateral [TRMV21 Sec. 5].
  const Plane<T> rows = trmv_spatial_axis(c, s, kTrmvHorizontal, radius, FloatPlane(), sigma, edges);
  return trmv_spatial_axis(rows, s, kTrmvVertical, radius, FloatPlane(), sigma, edges);
}

template <class T>
Plane<T> trmv_spatial_pass(const Plane<T>& c, const SurfacePlanes& s, int radius, const FloatPlane& sigma_x,
                           const FloatPlane& sigma_y, const SvgfParams& edges) {
  // Horizontal with each pixel's std across, then vertical with its std down (the penumbra filter, penumbra.h).
  const Plane<T> rows = trmv_spatial_axis(c, s, kTrmvHorizontal, radius, sigma_x, 0.0f, edges);
  return trmv_spatial_axis(rows, s, kTrmvVertical, radius, sigma_y, 0.0f, edges);
}

// The two kinds of plane the pipeline filters: visibility (float) and illumination (RGB).
template float trmv_spatial_pixel(const FloatPlane&, const SurfacePlanes&, glm::ivec2, int, float, const SvgfParams&,
                                  int, int, Probe*);
template glm::vec3 trmv_spatial_pixel(const RgbPlane&, const SurfacePlanes&, glm::ivec2, int, float,
                                      const SvgfParams&, int, int, Probe*);
template FloatPlane trmv_spatial_axis(const FloatPlane&, const SurfacePlanes&, glm::ivec2, int, const FloatPlane&,
                                      float, const SvgfParams&);
template RgbPlane trmv_spatial_axis(const RgbPlane&, const SurfacePlanes&, glm::ivec2, int, const FloatPlane&, float,
                                    const SvgfParams&);
template FloatPlane trmv_spatial_pass(const FloatPlane&, const SurfacePlanes&, int, float, const SvgfParams&);
template RgbPlane trmv_spatial_pass(const RgbPlane&, const SurfacePlanes&, int, float, const SvgfParams&);
template FloatPlane trmv_spatial_pass(const FloatPlane&, const SurfacePlanes&, int, const FloatPlane&,
                                      const FloatPlane&, const SvgfParams&);
template RgbPlane trmv_spatial_pass(const RgbPlane&, const SurfacePlanes&, int, const FloatPlane&, const FloatPlane&,
                                    const SvgfParams&);

}  // namespace rtdr
