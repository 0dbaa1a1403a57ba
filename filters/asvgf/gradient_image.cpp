// The gradient image on the stratum grid [ASVGF18 Sec. 3.4, Eq. 3, Eq. 13]. See gradient_image.h.
#include "filters/asvgf/gradient_image.h"

#include "core/color.h"
#include "core/error.h"
#include "core/parallel.h"
#include "filters/asvgf/adaptive_alpha.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <string>

namespace rtdr {

glm::vec2 gradient_sample_values(float f_now, float f_before, const GradientForm& form, Probe* probe) {
  // delta = f_i(G~, xi_{i-1,j}) - f_{i-1}(G, xi_{i-1,j}) as luminance [ASVGF18 Eq. 3].
  const float delta = f_now - f_before;
  // Delta = max(f_i(G~, xi_{i-1,j}), f_{i-1}(G, xi_{i-1,j})) [ASVGF18 Eq. 13].
  const float norm = std::max(f_now, f_before);
  note(probe, "f_i - f_{i-1}", delta, "[ASVGF18 Eq. 3]");
  note(probe, "max(f_i, f_{i-1})", norm, "[ASVGF18 Eq. 13]");
  // Normalised per sample (Q2RTX, RTGL1): r = min(1, k (|delta| / Delta)^p), beside the sample-present weight 1.
  if (form.before) return {gradient_ratio(delta, norm, form.exponent, form.scale), 1.0f};
  // abs(delta): opposite changes cannot cancel in the reconstruction.
  if (form.absolute) return {std::abs(delta), norm};
  return {delta, norm};
}

GradientStratum gradient_stratum(const RgbPlane& noisy, const UIntPlane& source, const FloatPlane& prev_luminance,
                                 const SurfacePlanes& surface, int s, int sx, int sy, const GradientForm& form,
                                 Probe* probe) {
  GradientStratum out;
  // The stratum's pixels: s x s, fewer at the right and bottom edges.
  const int x0 = sx * s, y0 = sy * s;
  const int x1 = std::min(x0 + s, noisy.width), y1 = std::min(y0 + s, noisy.height);
  note(probe, "stratum size s", float(s), "[ASVGF18 Sec. 3.3]");

  // The representative pixel: the centre, else the first covered pixel in raster order (gradient_image.h).
  const glm::ivec2 centre(std::min(x0 + s / 2, x1 - 1), std::min(y0 + s / 2, y1 - 1));
  if (surface.covered(centre.x, centre.y)) out.representative = centre;
  for (int y = y0; y < y1 && out.representative.x < 0; ++y)
    for (int x = x0; x < x1 && out.representative.x < 0; ++x)
      if (surface.covered(x, y)) out.representative = {x, y};
  note(probe, "representative pixel", glm::vec2(out.representative), "its z, grad z, n [ASVGF18 Eq. 9-10]");

  // l^(0)(p): the mean luminance of the covered pixels; Var(l^(0)(p)): their population variance [Sec. 3.4].
  int count = 0;
  float sum = 0.0f, sum_squares = 0.0f;
  int samples = 0;
  for (int y = y0; y < y1; ++y)
    for (int x = x0; x < x1; ++x) {
      if (!surface.covered(x, y)) continue;
      const float l = luminance(noisy.at(x, y));
      ++count;
      sum += l;
      sum_squares += l * l;
      const uint32_t j = source.at(x, y);
      if (j == kInvalidId) continue;
      if (++samples > 1)
        throw Error("stratum (" + std::to_string(sx) + ", " + std::to_string(sy) + ") holds two gradient samples");
      // jbar = (x, y): this frame's luminance there, and the previous frame's at j [ASVGF18 Eq. 2].
      const float f_now = l, f_before = prev_luminance.at(x, y);
      note(probe, "gradient sample jbar", glm::vec2(float(x), float(y)), "[ASVGF18 Sec. 3.3]");
      note(probe, "f_i(G~, xi_{i-1,j})", f_now, "[ASVGF18 Eq. 2] this frame's luminance at jbar");
      note(probe, "f_{i-1}(G, xi_{i-1,j})", f_before, "[ASVGF18 Eq. 2] gradient.prev_<stream>");
      const glm::vec2 values = gradient_sample_values(f_now, f_before, form, probe);
      out.delta = values.x;
      out.norm = values.y;
    }
  note(probe, form.before ? "r (the sample's ratio)" : form.absolute ? "abs(delta)" : "delta", out.delta,
       form.before ? "min(1, k (|delta| / Delta)^p) per sample; 0 without a sample"
                   : "[ASVGF18 Eq. 3] 0 without a sample");
  note(probe, form.before ? "sample-present weight" : "Delta", out.norm,
       form.before ? "1 where a sample is, 0 without" : "[ASVGF18 Eq. 13] 0 without a sample");
  if (count > 0) {
    out.luminance = sum / float(count);
    out.variance = std::max(0.0f, sum_squares / float(count) - out.luminance * out.luminance);
  }
  note(probe, "covered pixels", float(count));
  note(probe, "l^(0)", out.luminance, "[ASVGF18 Sec. 3.4] mean luminance of the stratum");
  note(probe, "Var(l^(0))", out.variance, "[ASVGF18 Sec. 3.4] variance of the luminance in the stratum");
  return out;
}

GradientImage gradient_image_grid(const RgbPlane& noisy, const UIntPlane& source, const FloatPlane& prev_luminance,
                                  const SurfacePlanes& surface, int s) {
  const int w = noisy.width, h = noisy.height;
  if (s < 1) throw Error("gradient image: stratum size " + std::to_string(s) + " < 1");
  const auto sized = [&](const auto& p) { return p.width == w && p.height == h; };
  if (!sized(source) || !sized(prev_luminance) || !sized(surface.depth) || !sized(surface.mesh) ||
      !sized(surface.depth_grad) || !sized(surface.normal))
    throw Error("gradient image: the gradient planes and the G-buffer are not all " + std::to_string(w) + "x" +
                std::to_string(h));
  const int sw = (w + s - 1) / s, sh = (h + s - 1) / s;  // partial strata at the right and bottom
  GradientImage g;
  g.stratum_size = s;
  g.values = {FloatPlane(sw, sh), FloatPlane(sw, sh), FloatPlane(sw, sh), FloatPlane(sw, sh)};
  g.surface.depth = FloatPlane(sw, sh);
  g.surface.depth_grad = Vec2Plane(sw, sh);
  g.surface.normal = RgbPlane(sw, sh);
  g.surface.mesh = UIntPlane(sw, sh);
  return g;
}

GradientImage gradient_image(const RgbPlane& noisy, const UIntPlane& source, const FloatPlane& prev_luminance,
                             const SurfacePlanes& surface, int s, const GradientForm& form) {
  GradientImage g = gradient_image_grid(noisy, source, prev_luminance, surface, s);
  const int sw = g.values.delta.width, sh = g.values.delta.height;
  parallel_rows(sh, [&](int sy) {
    for (int sx = 0; sx < sw; ++sx) {
      const GradientStratum r = gradient_stratum(noisy, source, prev_luminance, surface, s, sx, sy, form);
      g.values.delta.at(sx, sy) = r.delta;
      g.values.norm.at(sx, sy) = r.norm;
      g.values.luminance.at(sx, sy) = r.luminance;
      g.values.variance.at(sx, sy) = r.variance;
      const bool covered = r.representative.x >= 0;
      const int rx = r.representative.x, ry = r.representative.y;
      g.surface.mesh.at(sx, sy) = covered ? surface.mesh.at(rx, ry) : kInvalidId;
      g.surface.depth.at(sx, sy) = covered ? surface.depth.at(rx, ry) : 0.0f;
      g.surface.depth_grad.at(sx, sy) = covered ? surface.depth_grad.at(rx, ry) : glm::vec2(0.0f);
      g.surface.normal.at(sx, sy) = covered ? surface.normal.at(rx, ry) : glm::vec3(0.0f);
    }
  });
  return g;
}

std::string stratum_size_problem(const Frame& frame, int* s) {
  const auto it = frame.attributes.find("rtdr.gradient.stratum_size");
  if (it == frame.attributes.end())
    return "no header attribute rtdr.gradient.stratum_size: not rendered with gradient samples (rtdr render "
           "--gradients)";
  int size = 0;
  const char *first = it->second.data(), *last = first + it->second.size();
  const auto [end, ec] = std::from_chars(first, last, size);
  if (ec != std::errc() || end != last || size < 1 || size > 64)
    return "rtdr.gradient.stratum_size '" + it->second + "' is not a stratum size (1 to 64)";
  if (s) *s = size;
  return "";
}

int frame_stratum_size(const Frame& frame, const std::string& method) {
  int s = 0;
  const std::string problem = stratum_size_problem(frame, &s);
  if (!problem.empty())
    throw Error((frame.source.empty() ? std::string("the input frame") : frame.source) + ": method " + method +
                " reads gradient samples: " + problem);
  return s;
}

FloatPlane replicate_strata(const FloatPlane& strata, int s, int width, int height) {
  FloatPlane out(width, height);
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x) out.at(x, y) = strata.at(x / s, y / s);
  return out;
}

}  // namespace rtdr
