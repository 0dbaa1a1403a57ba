// Tests of filters/trmv/reshade.cpp, the cones at work [TRMV21 Sec. 4.3, Eq. 11], as the trmv method runs them: a
// disoccluded pixel's diffuse history re-shaded from the cones at x^O, the probe's terms, and nothing changed
// elsewhere. The cones' own equations are tested in tests/trmv_cones_test.cpp.
#include "filters/trmv/reshade.h"

#include "filters/method.h"
#include "filters/trmv/trmv.h"
#include "scenes/gltf_loader.h"
#include "trace/render_frame.h"

#include <catch2/catch.hpp>

#include <memory>
#include <vector>

using namespace rtdr;

TEST_CASE("occlusion: disoccluded pixels take their diffuse history re-shaded from the cones, as the probe recomputes") {
  // Frames 40-41 at 128x72: the boxes uncover a band of the wall about a pixel wide (tests/motion_dual_test.cpp).
  // Two frames: at the second, both methods read the same history, so only the disoccluded pixels may differ.
  constexpr int w = 128, h = 72;
  const Scene scene = load_scene("occlusion");
  RenderSettings settings;  // trmv's input: with the shading term
  settings.trace.shading_samples = kTrmvShadingSamples;
  const std::vector<Frame> frames = {render_frame(scene, 40, w, h, settings), render_frame(scene, 41, w, h, settings)};
  const std::unique_ptr<Method> with_cones = make_method("trmv");
  MethodParams colour = method_defaults("trmv");
  colour.trmv.cones = 0;  // the colour at x^O instead
  const std::unique_ptr<Method> without = make_method("trmv", colour);
  Frame dump, dump_colour;
  for (const Frame& f : frames) with_cones->filter(f, &dump), without->filter(f, &dump_colour);
  const Frame& last = frames.back();
  const UIntPlane& disoccluded = last.uint_channel("motion.dual.valid");
  const RgbPlane reshaded = rgb_plane(dump, "filter.trmv.diffuse.reshaded");
  const RgbPlane temporal = rgb_plane(dump, "filter.trmv.diffuse.temporal");
  const RgbPlane temporal_colour = rgb_plane(dump_colour, "filter.trmv.diffuse.temporal");
  int checked = 0, differ = 0;
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      const size_t i = size_t(y * w + x);
      if (!disoccluded.data[i]) {  // elsewhere the cones change nothing
        CHECK(reshaded.data[i] == glm::vec3(0.0f));
        CHECK(temporal.data[i] == temporal_colour.data[i]);
        continue;
      }
      // The probe's L_o is the dumped re-shaded history.
      const Probe p = with_cones->probe("trmv_reshade", x, y, "diffuse", 0);
      for (const Probe::Term& t : p.terms())
        if (t.name == "L_o") {
          CHECK(glm::vec3(t.value[0], t.value[1], t.value[2]) == reshaded.data[i]);
          ++checked;
        }
      differ += temporal.data[i] != temporal_colour.data[i];
    }
  INFO(checked << " disoccluded pixels re-shaded, " << differ << " of them blend a history other than the colour's");
  CHECK(checked > 0);
  CHECK(differ > 0);
}
