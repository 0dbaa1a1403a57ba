// Tests of the asvgf method on rendered frames with gradient samples [ASVGF18 Sec. 3-5]: the paper's oracles that
// have exact answers. A static scene gives lambda = 0 and alpha_i = alpha; every emitter scaled by k at one frame
// gives lambda = abs(k - 1) / max(k, 1) wherever a gradient sample reaches; emitters switching on from 0 give
// lambda = 1, and the temporal output is then the frame's own sample: no lag.
#include "filters/method.h"

#include "core/color.h"
#include "core/error.h"
#include "filters/image.h"
#include "scenes/gltf_loader.h"
#include "trace/gradients.h"

#include <catch2/catch.hpp>

#include <cmath>
#include <memory>
#include <vector>

using namespace rtdr;

namespace {

constexpr int kWidth = 48, kHeight = 27;

// Frames 0..last of `scene` with gradient samples, each filtered by asvgf with its dump; the dumps are returned.
std::vector<Frame> asvgf_dumps(const Scene& scene, int last, std::vector<Frame>* inputs = nullptr,
                               const MethodParams& params = method_defaults("asvgf")) {
  const std::unique_ptr<Method> asvgf = make_method("asvgf", params);
  std::vector<Frame> frames, dumps;
  for (int f = 0; f <= last; ++f) {
    frames.push_back(render_frame_with_gradients(scene, f, kWidth, kHeight, {}, {}, f ? &frames.back() : nullptr));
    Frame dump(kWidth, kHeight);
    asvgf->filter(frames.back(), &dump);
    dumps.push_back(std::move(dump));
  }
  if (inputs) *inputs = std::move(frames);
  return dumps;
}

// cornell (static camera, one light) with every emitter's strength multiplied by `before` until frame 2 and by
// `after` from frame 2 on (a STEP track).
Scene switched_cornell(float before, float after) {
  Scene scene = load_scene("cornell");
  for (Material& m : scene.materials) {
    if (m.emissive == glm::vec3(0.0f)) continue;
    m.emissive_strength_track.times = {0.0f, float(scene.time_of_frame(2) - 0.5 / scene.fps)};  // between 1 and 2
    m.emissive_strength_track.values = {m.emissive_strength * before, m.emissive_strength * after};
    m.emissive_strength_track.interpolation = Interpolation::Step;
  }
  return scene;
}

}  // namespace

TEST_CASE("asvgf on a static scene: lambda = 0 and alpha_i = alpha exactly, in both streams") {
  const std::vector<Frame> dumps = asvgf_dumps(load_scene("static"), 3);
  for (const char* stream : {"direct", "indirect"}) {
    INFO(stream);
    const std::string s(stream);
    for (size_t f = 1; f < dumps.size(); ++f) {
      for (float lambda : dumps[f].float_channel("filter." + s + ".lambda").data) CHECK(lambda == 0.0f);
      for (float alpha : dumps[f].float_channel("filter." + s + ".alpha").data) CHECK(alpha == 0.1f);
    }
  }
}

TEST_CASE("asvgf: every emitter scaled by k at one frame gives lambda = abs(k - 1) / max(k, 1) wherever Delta^ > 0") {
  for (const float k : {2.0f, 0.5f, 3.0f}) {
    INFO("k = " << k);
    const std::vector<Frame> dumps = asvgf_dumps(switched_cornell(1.0f, k), 2);
    const Frame& d = dumps[2];
    const float expected = std::abs(k - 1.0f) / std::max(k, 1.0f);
    int reached = 0;
    for (const char* stream : {"direct", "indirect"}) {
      const std::string s(stream);
      const FloatPlane& norm = d.float_channel("filter." + s + ".gradient.level4.norm");
      const FloatPlane& lambda = d.float_channel("filter." + s + ".lambda");
      const FloatPlane& alpha = d.float_channel("filter." + s + ".alpha");
      for (size_t i = 0; i < norm.data.size(); ++i) {
        if (norm.data[i] <= 0.0f) continue;
        ++reached;
        CHECK(lambda.data[i] == Approx(expected).epsilon(1e-5));
        CHECK(alpha.data[i] == Approx(0.1f + 0.9f * expected).epsilon(1e-5));  // k = 2: 0.55
      }
    }
    CHECK(reached > kWidth * kHeight);  // most of both streams' pixels
    // The frame before the change is static: lambda = 0.
    for (float lambda : dumps[1].float_channel("filter.direct.lambda").data) CHECK(lambda == 0.0f);
  }
}

TEST_CASE("asvgf: emitters switching on from 0 give lambda = 1, and the temporal output is the new sample: no lag") {
  std::vector<Frame> inputs;
  const std::vector<Frame> dumps = asvgf_dumps(switched_cornell(0.0f, 1.0f), 2, &inputs);
  const Frame& d = dumps[2];
  const RgbPlane noisy = rgb_plane(inputs[2], "direct"), temporal = rgb_plane(d, "filter.direct.temporal");
  const FloatPlane& norm = d.float_channel("filter.direct.gradient.level4.norm");
  const FloatPlane& alpha = d.float_channel("filter.direct.alpha");
  const FloatPlane& length = d.float_channel("filter.direct.history_length");
  const UIntPlane& mesh = inputs[2].uint_channel("id.mesh");
  int reached = 0;
  for (size_t i = 0; i < norm.data.size(); ++i) {
    if (norm.data[i] <= 0.0f || mesh.data[i] == kInvalidId) continue;  // a surface a gradient sample reaches
    ++reached;
    CHECK(d.float_channel("filter.direct.lambda").data[i] == 1.0f);
    CHECK(alpha.data[i] == 1.0f);
    CHECK(length.data[i] == 1.0f);  // the dropped history restarts (history_rule 0)
    CHECK(d.float_channel("filter.direct.variance.spatial").data[i] == 1.0f);  // so the variance is spatial
    CHECK(temporal.data[i] == noisy.data[i]);
  }
  INFO(reached << " pixels reached");
  CHECK(reached > kWidth * kHeight / 3);
  // history_rule 1 keeps SVGF's count: the dump shows n = 3 there at frame 2, the history not restarted.
  MethodParams keep = method_defaults("asvgf");
  keep.asvgf.history_rule = 1;
  const Frame kept = asvgf_dumps(switched_cornell(0.0f, 1.0f), 2, nullptr, keep)[2];
  int counted = 0;
  for (size_t i = 0; i < norm.data.size(); ++i) {
    if (norm.data[i] <= 0.0f || mesh.data[i] == kInvalidId) continue;
    counted += kept.float_channel("filter.direct.history_length").data[i] == 3.0f;
  }
  CHECK(counted > reached / 2);  // all but the pixels whose history was disoccluded
}

TEST_CASE("a-eaw is EAW followed by the adaptive EMA: on a static scene frame 1 is the mean of EAW's frames 0 and 1") {
  // lambda = 0 on a static scene, and n = 2 at frame 1: alpha_eff = max(alpha_i, 1/n) = 1/2 [ASVGF18 Eq. 1, 15].
  const Scene scene = load_scene("cornell");
  const std::unique_ptr<Method> eaw = make_method("eaw"), a_eaw = make_method("a-eaw");
  std::vector<Frame> frames, eaw_dumps, a_eaw_dumps;
  for (int f = 0; f <= 1; ++f) {
    frames.push_back(render_frame_with_gradients(scene, f, kWidth, kHeight, {}, {}, f ? &frames.back() : nullptr));
    eaw_dumps.emplace_back(kWidth, kHeight);
    a_eaw_dumps.emplace_back(kWidth, kHeight);
    eaw->filter(frames.back(), &eaw_dumps.back());
    a_eaw->filter(frames.back(), &a_eaw_dumps.back());
  }
  const UIntPlane& mesh = frames[1].uint_channel("id.mesh");
  int covered = 0;
  for (const char* stream : {"direct", "indirect"}) {
    const std::string s(stream);
    // Its spatial filter is EAW's, bit for bit.
    CHECK(a_eaw_dumps[1].float_channel("filter." + s + ".filtered.G").data ==
          eaw_dumps[1].float_channel("filter." + s + ".filtered.G").data);
    const FloatPlane &ema = a_eaw_dumps[1].float_channel("filter." + s + ".ema.G"),
                     &now = eaw_dumps[1].float_channel("filter." + s + ".filtered.G"),
                     &before = eaw_dumps[0].float_channel("filter." + s + ".filtered.G");
    for (size_t i = 0; i < ema.data.size(); ++i) {
      if (mesh.data[i] == kInvalidId) continue;
      ++covered;
      CHECK(ema.data[i] == Approx(0.5f * (now.data[i] + before.data[i])).epsilon(1e-4).margin(1e-6));
    }
  }
  CHECK(covered > kWidth * kHeight);
}

TEST_CASE("A-SVGF's passes are logged where they run: each probe re-computes its dumped value, on every stream") {
  // pillars moves, so delta != 0 somewhere; the passes are probed at covered pixels of frame 2, for the two streams
  // and for the one stream "combined" (streams = 1), every reconstruction iteration included.
  const Scene scene = load_scene("pillars");
  std::vector<Frame> frames;
  for (int f = 0; f <= 2; ++f)
    frames.push_back(render_frame_with_gradients(scene, f, kWidth, kHeight, {}, {}, f ? &frames.back() : nullptr));
  for (const int streams : {2, 1}) {
    MethodParams params = method_defaults("asvgf");
    params.svgf.streams = streams;
    const std::unique_ptr<Method> asvgf = make_method("asvgf", params);
    Frame dump(kWidth, kHeight);
    for (const Frame& frame : frames) asvgf->filter(frame, &dump);
    const std::vector<std::string> names =
        streams == 2 ? std::vector<std::string>{"direct", "indirect"} : std::vector<std::string>{"combined"};
    const UIntPlane& mesh = frames.back().uint_channel("id.mesh");
    for (const std::string& s : names)
      for (const auto& [x, y] : {std::pair{24, 13}, std::pair{10, 20}, std::pair{40, 5}}) {
        INFO("stream " << s << ", pixel (" << x << ", " << y << ")");
        REQUIRE(mesh.at(x, y) != kInvalidId);
        const auto dumped = [&](const std::string& layer) { return dump.float_channel("filter." + s + "." + layer).at(x, y); };
        const Probe gradient = asvgf->probe("gradient", x, y, s, 0);
        CHECK(gradient.find("delta").value[0] == Approx(dumped("gradient.delta")).margin(1e-7));
        CHECK(gradient.find("Delta").value[0] == Approx(dumped("gradient.norm")).margin(1e-7));
        CHECK(gradient.find("l^(0)").value[0] == Approx(dumped("gradient.luminance")).margin(1e-7));
        for (int k = 0; k < params.asvgf.gradient_levels; ++k) {
          INFO("iteration " << k);
          const Probe level = asvgf->probe("gradient_atrous", x, y, s, k);
          const std::string prefix = "gradient.level" + std::to_string(k) + ".";
          CHECK(level.find("delta^(k+1)(p)", "sum").value[0] == Approx(dumped(prefix + "delta")).margin(1e-7));
          CHECK(level.find("l^(k+1)(p)", "sum").value[0] == Approx(dumped(prefix + "luminance")).margin(1e-7));
        }
        const Probe alpha = asvgf->probe("adaptive_alpha", x, y, s, 0);
        CHECK(alpha.find("lambda(p)").value[0] == Approx(dumped("lambda")).margin(1e-7));
        CHECK(alpha.find("alpha_i").value[0] == Approx(dumped("alpha")).margin(1e-7));
      }
    // A stream that did not run is refused, naming those that did.
    if (streams == 1) CHECK_THROWS_WITH(asvgf->probe("adaptive_alpha", 24, 13, "direct", 0), Catch::Contains("combined"));
    CHECK_THROWS_AS(asvgf->probe("gradient_atrous", 24, 13, names.front(), params.asvgf.gradient_levels), Error);
  }
}
