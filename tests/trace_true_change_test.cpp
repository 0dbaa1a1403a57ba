// Tests of trace/true_change.h, the yardstick of A-SVGF's gradient: a frame's surface samples shaded under the previous
// frame's poses and lights with the same seeds. On a static scene nothing changed, bit for bit; when every emitter
// is scaled by k between the two frames (the light choice unchanged: its CDF scales alike), every path's radiance is
// scaled by k, so the frame's light is k times the truth's, the ratio A-SVGF's lambda oracle uses
// (tests/asvgf_asvgf_test.cpp).
#include "trace/true_change.h"

#include "scenes/gltf_loader.h"
#include "trace/render_key.h"

#include <catch2/catch.hpp>

using namespace rtdr;

TEST_CASE("true change: nothing on a static scene, bit for bit, and a factor k where every emitter is scaled by k") {
  const Frame still = render_true_change_frame(load_scene("static"), 3, 40, 24, RenderSettings{.spp = 2});
  for (const char* c : {"direct.R", "direct.G", "indirect.B"})
    CHECK(still.float_channel(c).data == still.float_channel(std::string("truth.prev_") + c).data);
  CHECK(still.attributes.at("rtdr.true_change") == "1");
  CHECK(checksum_mismatch(still).empty());  // stamped over the added layers

  Scene scene = load_scene("cornell");
  const float k = 3.0f;
  for (Material& m : scene.materials) {
    if (m.emissive == glm::vec3(0.0f)) continue;
    m.emissive_strength_track.times = {0.0f, float(scene.time_of_frame(2) - 0.5 / scene.fps)};  // between 1 and 2
    m.emissive_strength_track.values = {m.emissive_strength, m.emissive_strength * k};
    m.emissive_strength_track.interpolation = Interpolation::Step;
  }
  const Frame step = render_true_change_frame(scene, 2, 40, 24, RenderSettings{.spp = 2});
  int lit = 0;
  for (const char* stream : {"direct", "indirect"})
    for (const char* c : {".R", ".G", ".B"}) {
      const FloatPlane &now = step.float_channel(std::string(stream) + c),
                       &before = step.float_channel(std::string("truth.prev_") + stream + c);
      for (size_t i = 0; i < now.data.size(); ++i) {
        if (before.data[i] <= 1e-6f) continue;
        ++lit;
        CHECK(now.data[i] == Approx(k * before.data[i]).epsilon(1e-4));
      }
    }
  CHECK(lit > 40 * 24);
}
