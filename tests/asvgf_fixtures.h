// Synthetic stratum grids for the tests of A-SVGF's filter side (asvgf_gradient_atrous_test.cpp,
// asvgf_adaptive_alpha_test.cpp), and the rendered frame the ports of its passes are checked on (gpu_*_test.cpp).
#pragma once

#include "filters/asvgf/gradient_atrous.h"
#include "filters/surface_planes.h"
#include "scenes/gltf_loader.h"
#include "trace/gradients.h"

#include <string>

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

// Frame 4 of pillars at 50x29 with gradient samples from frame 3: 3x3 strata, so a 17x10 grid with a partial
// stratum column and row at the border.
struct GradientFrame {
  Frame frame;
  int stratum_size = 0;
  SurfacePlanes surface;
};
inline GradientFrame pillars_gradient_frame() {
  const Scene scene = load_scene("pillars");
  const Frame previous = render_frame_with_gradients(scene, 3, 50, 29, {}, {}, nullptr);
  GradientFrame g;
  g.frame = render_frame_with_gradients(scene, 4, 50, 29, {}, {}, &previous);
  g.stratum_size = std::stoi(g.frame.attributes.at("rtdr.gradient.stratum_size"));
  g.surface = SurfacePlanes::from_frame(g.frame);
  return g;
}

}  // namespace rtdr::test
