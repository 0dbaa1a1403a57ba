// Tests of filters/trmv/trmv.cpp: the trmv method, its passes chained as trmv.h says, against the passes called
// one by one; the shadow and the surface motion on a still scene; determinism.
#include "filters/trmv/trmv.h"

#include "core/error.h"
#include "core/parallel.h"
#include "filters/passes.h"
#include "filters/svgf/modulate.h"
#include "filters/svgf/tonemap.h"
#include "filters/trmv/atrous.h"
#include "filters/trmv/footprint.h"
#include "filters/trmv/reflection.h"
#include "filters/trmv/spatial.h"
#include "scenes/gltf_loader.h"
#include "trace/render_frame.h"

#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <memory>
#include <vector>

using namespace rtdr;

namespace {

constexpr int kW = 48, kH = 27;

std::vector<Frame> scene_frames(const std::string& name, int first, int count, int width = kW, int height = kH) {
  const Scene scene = load_scene(name);
  std::vector<Frame> frames;
  RenderSettings settings;  // trmv's input: with the shading term
  settings.trace.shading_samples = kTrmvShadingSamples;
  for (int f = first; f < first + count; ++f) frames.push_back(render_frame(scene, f, width, height, settings));
  return frames;
}

std::vector<Frame> cornell_frames(int count) { return scene_frames("cornell", 0, count); }

RgbPlane sum(const RgbPlane& a, const RgbPlane& b) {
  RgbPlane out = a;
  for (size_t i = 0; i < out.data.size(); ++i) out.data[i] += b.data[i];
  return out;
}

double max_difference(const RgbPlane& a, const RgbPlane& b) {
  double d = 0.0;
  for (size_t i = 0; i < a.data.size(); ++i)
    d = std::max(d, double(glm::length(a.data[i] - b.data[i])));
  return d;
}

struct ThreadCountGuard {
  ~ThreadCountGuard() { set_thread_count(0); }
};

}  // namespace

TEST_CASE("trmv's first frame is each component's spatial filter, remodulated: no history yet") {
  // The glossy scene: its floor has a lobe footprint, the walls none (rough, wider than any window).
  const Frame in = scene_frames("glossy", 20, 1)[0];
  const MethodParams params = method_defaults("trmv");
  const std::unique_ptr<Method> method = make_method("trmv");
  const Frame out = method->filter(in);
  // By hand: no history gives alpha = 1, and no clamp and alpha^V = alpha give the clean-up std 0, the identity.
  // The windows at 27 rows (footprint.h): the shadow filter 3x3 (31 x 27/1080 = 0.78, the floor), std 5/15,
  // one a-trous level, the lobe filter's cap 3x3.
  const SurfacePlanes s = SurfacePlanes::from_frame(in);
  const TrmvWindows win = trmv_windows(params.trmv, kH);
  CHECK(win.shadow_radius == 1);
  CHECK(win.atrous_levels == 1);
  const FloatPlane v = in.float_channel("direct.visibility");
  RgbPlane v_rgb(kW, kH);
  for (size_t i = 0; i < v.data.size(); ++i) v_rgb.data[i] = glm::vec3(v.data[i]);
  const RgbPlane v_filtered = trmv_spatial_pass(v_rgb, s, win.shadow_radius, win.shadow_sigma, params.svgf);
  const RgbPlane diffuse = trmv_atrous_pass(rgb_plane(in, "indirect.diffuse"), s, win.atrous_levels, params.svgf);
  const RgbPlane glossy = trmv_reflection_pass(rgb_plane(in, "indirect.glossy"), s, TrmvFootprint::from_frame(in),
                                               win.glossy_radius, params.svgf);
  const RgbPlane indirect = sum(diffuse, glossy);
  RgbPlane direct = rgb_plane(in, "direct.shading");
  for (size_t i = 0; i < direct.data.size(); ++i) direct.data[i] *= v_filtered.data[i].x;  // shading x Vbar
  const RgbPlane expected = remodulate(direct, indirect, rgb_plane(in, "albedo"), rgb_plane(in, "emission"));
  CHECK(max_difference(rgb_plane(out, "color"), expected) == 0.0);
  CHECK(max_difference(rgb_plane(out, "display"), tonemap(expected, params.tonemap)) == 0.0);
}

TEST_CASE("on a still scene trmv along the shadow motion and along the surface motion agree") {
  const std::vector<Frame> frames = cornell_frames(4);
  MethodParams shadow = method_defaults("trmv"), traditional = shadow;
  shadow.trmv.motion = 1;  // the shadow vector alone
  traditional.trmv.motion = 0;
  const std::unique_ptr<Method> a = make_method("trmv", shadow), b = make_method("trmv", traditional);
  double worst = 0.0;
  for (const Frame& f : frames) worst = std::max(worst, max_difference(rgb_plane(a->filter(f), "color"),
                                                                        rgb_plane(b->filter(f), "color")));
  // The shadow motion equals the surface motion to float precision there (tests/motion_shadow_test.cpp), and
  // alpha^V = alpha exactly (a static shadow, theta = pi/2): only the bilinear weights' last bits differ.
  INFO("largest colour difference over 4 frames: " << worst);
  CHECK(worst < 1e-4);
}

TEST_CASE("trmv's output is the same, bit for bit, for any thread count, and reset() forgets the history") {
  ThreadCountGuard guard;
  const std::vector<Frame> frames = cornell_frames(3);
  std::vector<RgbPlane> colours[2];
  for (int threads : {1, 0}) {
    set_thread_count(threads);
    const std::unique_ptr<Method> m = make_method("trmv");
    for (const Frame& f : frames) colours[threads == 0].push_back(rgb_plane(m->filter(f), "color"));
  }
  for (size_t k = 0; k < frames.size(); ++k) CHECK(max_difference(colours[0][k], colours[1][k]) == 0.0);

  const std::unique_ptr<Method> m = make_method("trmv");
  const RgbPlane first = rgb_plane(m->filter(frames[0]), "color");
  m->filter(frames[1]);
  m->reset();
  CHECK(max_difference(rgb_plane(m->filter(frames[0]), "color"), first) == 0.0);
}

TEST_CASE("trmv's dump holds exactly its declared layers, and its probe recomputes the dumped values") {
  const std::vector<Frame> frames = cornell_frames(3);
  const std::unique_ptr<Method> m = make_method("trmv");
  Frame dump;
  Frame out;
  for (const Frame& f : frames) out = m->filter(f, &dump);
  std::vector<std::string> channels;
  for (const auto& [name, plane] : dump.float_channels()) channels.push_back(name);
  std::vector<std::string> declared = m->dump_channels();
  std::sort(declared.begin(), declared.end());
  CHECK(channels == declared);
  CHECK(declared.size() == 43);  // 13 scalar layers (3 of the splat), 9 RGB ones and filter.tonemapped

  // The colour is the filtered visibility times the shading term, plus the filtered diffuse and glossy light,
  // remodulated.
  const FloatPlane v = dump.float_channel("filter.trmv.visibility.cleaned");
  RgbPlane direct = rgb_plane(frames.back(), "direct.shading");
  for (size_t i = 0; i < direct.data.size(); ++i) direct.data[i] *= v.data[i];
  const RgbPlane indirect =
      sum(rgb_plane(dump, "filter.trmv.diffuse.cleaned"), rgb_plane(dump, "filter.trmv.glossy.cleaned"));
  const RgbPlane expected =
      remodulate(direct, indirect, rgb_plane(frames.back(), "albedo"), rgb_plane(frames.back(), "emission"));
  CHECK(max_difference(rgb_plane(out, "color"), expected) == 0.0);

  // The probe re-runs a pass's per-pixel function on the inputs it saw: its terms are the dumped values.
  // The value of the first term called `name` or `other` (falloff says "alpha^V = alpha" where it has no evidence).
  const auto term = [](const Probe& p, const std::string& name, const std::string& other = "-") {
    for (const Probe::Term& t : p.terms())
      if (t.name == name || t.name == other) return t.value;
    FAIL("no term " << name);
    return std::vector<float>{};
  };
  CHECK(m->probe_passes() == std::vector<std::string>{"trmv_splat", "trmv_spatial", "trmv_falloff", "trmv_atrous",
                                                      "trmv_reshade", "trmv_reflection", "trmv_temporal",
                                                      "trmv_cleanup", "tonemap"});
  int covered = 0;
  for (int y = 2; y < kH; y += 6)
    for (int x = 3; x < kW; x += 7) {
      if (frames.back().uint_channel("id.mesh").data[size_t(y * kW + x)] == kInvalidId) continue;
      ++covered;
      const size_t i = size_t(y * kW + x);
      CHECK(term(m->probe("trmv_falloff", x, y, "visibility", 0), "alpha^V", "alpha^V = alpha")[0] ==
            dump.float_channel("filter.trmv.visibility.alpha").data[i]);
      CHECK(term(m->probe("trmv_temporal", x, y, "visibility", 0), "cbar_i")[0] ==
            dump.float_channel("filter.trmv.visibility.temporal").data[i]);
      CHECK(term(m->probe("trmv_cleanup", x, y, "diffuse", 0), "w_C")[0] ==
            dump.float_channel("filter.trmv.diffuse.w_c").data[i]);
      CHECK(term(m->probe("trmv_temporal", x, y, "glossy", 0), "cbar_i", "cbar_i = c~_i")[1] ==
            dump.float_channel("filter.trmv.glossy.temporal.G").data[i]);
      CHECK_FALSE(m->probe("trmv_spatial", x, y, "direct", 0).terms().empty());
      CHECK(term(m->probe("trmv_splat", x, y, "visibility", 0), "window side")[0] == 3.0f);  // 27 rows: 3x3
      CHECK(term(m->probe("trmv_atrous", x, y, "diffuse", -1), "c_{i+1}(p)")[0] ==
            dump.float_channel("filter.trmv.diffuse.spatial.R").data[i]);
      CHECK(term(m->probe("trmv_reflection", x, y, "glossy", 0), "c~")[2] ==
            dump.float_channel("filter.trmv.glossy.spatial.B").data[i]);
      CHECK(term(m->probe("tonemap", x, y, "", -1), "display colour")[1] ==
            dump.float_channel("filter.tonemapped.G").data[i]);
    }
  CHECK(covered > 10);
  CHECK_THROWS_AS(m->probe("atrous", 1, 1, "visibility", 0), Error);      // not one of trmv's passes
  CHECK_THROWS_AS(m->probe("trmv_cleanup", 1, 1, "indirect", 0), Error);  // not one of its components
  CHECK_THROWS_AS(m->probe("trmv_cleanup", kW, 1, "diffuse", 0), Error);  // outside the frame
}

TEST_CASE("with the penumbra-sized shadow filter the dump holds W and the std per axis, and the probe recomputes them") {
  const std::vector<Frame> frames = cornell_frames(2);
  MethodParams params = method_defaults("trmv");
  params.trmv.shadow_filter = 1;
  const std::unique_ptr<Method> m = make_method("trmv", params);
  Frame dump;
  for (const Frame& f : frames) m->filter(f, &dump);
  std::vector<std::string> channels;
  for (const auto& [name, plane] : dump.float_channels()) channels.push_back(name);
  std::vector<std::string> declared = m->dump_channels();
  std::sort(declared.begin(), declared.end());
  CHECK(channels == declared);
  CHECK(declared.size() == 46);  // the default's 43, and W, sigma_x, sigma_y
  CHECK(m->probe_passes().front() == "trmv_penumbra");
  const auto term = [](const Probe& p, const std::string& name) {
    for (const Probe::Term& t : p.terms())
      if (t.name == name) return t.value[0];
    return -1.0f;  // not noted: a lit pixel has no W
  };
  const FloatPlane& width = dump.float_channel("filter.trmv.visibility.penumbra");
  const FloatPlane& sigma_y = dump.float_channel("filter.trmv.visibility.sigma_y");
  int blocked = 0;
  for (int y = 0; y < kH; ++y)
    for (int x = 0; x < kW; ++x) {
      const size_t i = size_t(y * kW + x);
      if (frames.back().uint_channel("id.mesh").data[i] == kInvalidId) continue;
      const float w = term(m->probe("trmv_penumbra", x, y, "visibility", 0), "W");
      if (w >= 0.0f) {
        ++blocked;
        CHECK(w == width.data[i]);
      } else {
        CHECK(width.data[i] == 0.0f);
      }
      // The spatial pass's vertical 1-D pass takes the pixel's own std down the image.
      CHECK(term(m->probe("trmv_spatial", x, y, "visibility", 0), "sigma") == sigma_y.data[i]);
    }
  CHECK(blocked > 20);  // the cornell box's shadows
}
