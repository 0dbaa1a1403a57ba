// Synthetic stratum grids for the tests of A-SVGF's filter side (asvgf_gradient_atrous_test.cpp,
// asvgf_adaptive_alpha_test.cpp).
#pragma once

#include "filters/asvgf/gradient_atrous.h"

namespace rtdr::test {

// A w x h stratum grid on a plane facing the camera: every stratum covered, depth 1, constant luminance, no
// variance, and no gradient sample anywhere (delta = Delta = 0).
inline GradientImage flat_grid(int w, int h, int s = 3) {
  GradientImage g;
  g.stratum_size = s;
  g.values = {FloatPlane(w, h), FloatPlane(w, h), FloatPlane(w, h, 1.0f), FloatPlane(w, h)};
  g.surface.depth = FloatPlane(w, h, 1.0f);
  g.surface.depth_grad = Vec2Plane(w, h);
  g.surface.normal = RgbPlane(w, h, glm::vec3(0.0f, 0.0f, 1.0f));
  g.surface.mesh = UIntPlane(w, h, 0u);
  return g;
}

// `iterations` reconstruction iterations, as A-SVGF runs them (five) [ASVGF18 Sec. 3.4].
inline GradientValues reconstruct(const GradientImage& g, int iterations = 5) {
  GradientValues v = g.values;
  for (int k = 0; k < iterations; ++k) v = gradient_atrous_level(v, g, k, SvgfParams{});
  return v;
}

}  // namespace rtdr::test
