// Tests of trace/gradients.cpp, A-SVGF's gradient samples [ASVGF18 Sec. 3.1-3.3, Eq. 2-6]: seed reuse makes the
// gradient of an unchanged pixel exactly 0; at most one sample per stratum; the random selection is uniform; a
// merged pixel's motion returns to its source; no occluded sample is merged; any thread count gives the same
// frame; bad input is refused. Frames are rendered in memory at tiny sizes.
#include "trace/gradients.h"

#include "core/color.h"
#include "core/error.h"
#include "core/parallel.h"
#include "motion/forward_project.h"
#include "scenes/gltf_loader.h"

#include <catch2/catch.hpp>

#include <bit>
#include <functional>
#include <optional>
#include <cmath>
#include <vector>

using namespace rtdr;

namespace {

// Frames first..last of `scene` rendered with gradient samples, each from the one before.
std::vector<Frame> render_sequence(const Scene& scene, int first, int last, int width, int height,
                                   const GradientParams& params = {}) {
  std::vector<Frame> frames;
  for (int f = first; f <= last; ++f)
    frames.push_back(
        render_frame_with_gradients(scene, f, width, height, {}, params, frames.empty() ? nullptr : &frames.back()));
  return frames;
}

float luminance_at(const Frame& frame, const std::string& layer, size_t i) {
  return luminance(glm::vec3(frame.float_channel(layer + ".R").data[i], frame.float_channel(layer + ".G").data[i],
                             frame.float_channel(layer + ".B").data[i]));
}

// The pixels of `frame` that hold a gradient sample.
std::vector<size_t> gradient_pixels(const Frame& frame) {
  std::vector<size_t> pixels;
  const std::vector<uint32_t>& source = frame.uint_channel("gradient.source").data;
  for (size_t i = 0; i < source.size(); ++i)
    if (source[i] != kInvalidId) pixels.push_back(i);
  return pixels;
}

// A previous frame of `width` x `height` pixels that all see a surface, with luminance l(j) = j.
PreviousFrame covered_previous(int width, int height) {
  PreviousFrame p;
  p.vis = VisibilityBuffer(width, height);
  const size_t n = size_t(width) * size_t(height);
  p.vis.instance.assign(n, 0);
  p.vis.triangle.assign(n, 0);
  p.vis.depth.assign(n, 1.0f);
  p.seed.assign(n, 0);
  p.luminance_direct.resize(n);
  p.luminance_indirect.assign(n, 0.0f);
  for (size_t j = 0; j < n; ++j) p.luminance_direct[j] = float(j);
  p.was_gradient.assign(n, false);
  return p;
}

}  // namespace

TEST_CASE("static scene and camera: every gradient sample re-shades to its source's value bit for bit") {
  // Nothing moves, so G~ = G and, with the same seed, f_i(G~, xi) = f_{i-1}(G, xi): delta = 0 exactly [Eq. 2].
  const Scene scene = load_scene("static");
  const std::vector<Frame> frames = render_sequence(scene, 0, 1, 48, 27);
  CHECK(gradient_pixels(frames[0]).empty());  // frame 0 has no previous frame
  const std::vector<size_t> pixels = gradient_pixels(frames[1]);
  // One per 3x3 stratum of the covered area: 16 x 9 strata at 48x27; most of the frame sees a surface.
  INFO(pixels.size() << " gradient pixels");
  CHECK(pixels.size() >= 100);
  CHECK(pixels.size() <= 16 * 9);
  for (const size_t i : pixels) {
    INFO("pixel " << i);
    CHECK(frames[1].uint_channel("gradient.source").data[i] == i);  // a static camera projects j onto itself
    CHECK(std::bit_cast<uint32_t>(luminance_at(frames[1], "direct", i)) ==
          std::bit_cast<uint32_t>(frames[1].float_channel("gradient.prev_direct").data[i]));
    CHECK(std::bit_cast<uint32_t>(luminance_at(frames[1], "indirect", i)) ==
          std::bit_cast<uint32_t>(frames[1].float_channel("gradient.prev_indirect").data[i]));
    CHECK(frames[1].uint_channel("rng.seed").data[i] == frames[0].uint_channel("rng.seed").data[i]);
  }

  // Without seed reuse the two samples are independent [Eq. 4-5]: delta is non-zero on most lit gradient pixels.
  GradientParams fresh;
  fresh.seed_reuse = 0;
  const std::vector<Frame> independent = render_sequence(scene, 0, 1, 48, 27, fresh);
  int lit = 0, changed = 0;
  for (const size_t i : gradient_pixels(independent[1])) {
    const float before = independent[1].float_channel("gradient.prev_direct").data[i];
    const float now = luminance_at(independent[1], "direct", i);
    if (before <= 0.0f && now <= 0.0f) continue;
    ++lit;
    changed += before != now;
  }
  INFO(changed << " of " << lit << " lit gradient pixels changed");
  CHECK(lit >= 50);
  CHECK(changed >= lit * 3 / 4);
}

TEST_CASE("Sec. 5.4: a switched light changes every pixel's light choice, unless the seed's frame chooses") {
  // flicker with its camera and red light frozen: only the blue panel changes, on at frame 14 and off at 15.
  Scene scene = load_scene("flicker");
  for (Node& node : scene.nodes) node.translation_track = {}, node.rotation_track = {}, node.scale_track = {};
  uint32_t blue = kInvalidId;
  for (size_t i = 0; i < scene.instances.size(); ++i)
    if (!scene.material_of_mesh(scene.instances[i].mesh).emissive_strength_track.times.empty()) blue = uint32_t(i);
  REQUIRE(blue != kInvalidId);

  // A gradient sample that met the blue light (its light sample, or its BSDF ray hit it) changes for sure. Every
  // other one sees the same light with the same radiance and MIS weights when its light is chosen as before.
  const auto count = [&](const GradientParams& params, int& unaffected, int& changed) {
    const std::vector<Frame> frames = render_sequence(scene, 13, 15, 64, 36, params);
    const Frame& f = frames[2];
    unaffected = changed = 0;
    for (const size_t i : gradient_pixels(f)) {
      if (f.uint_channel("path.light.instance").data[i] == blue ||
          f.uint_channel("path.secondary.instance").data[i] == blue)
        continue;
      ++unaffected;
      changed += luminance_at(f, "direct", i) != f.float_channel("gradient.prev_direct").data[i];
      // The seed's frame travels with the seed: a chained seed keeps the frame it was made in.
      const uint32_t j = f.uint_channel("gradient.source").data[i];
      CHECK(f.uint_channel("rng.seed_frame").data[i] == frames[1].uint_channel("rng.seed_frame").data[j]);
    }
  };
  GradientParams current, seed_frame;
  seed_frame.light_cdf = 1;
  int unaffected_current = 0, changed_current = 0, unaffected_seed = 0, changed_seed = 0;
  count(current, unaffected_current, changed_current);
  count(seed_frame, unaffected_seed, changed_seed);
  INFO("light_cdf 0: " << changed_current << " of " << unaffected_current
                       << " gradient pixels away from the blue light changed; light_cdf 1: " << changed_seed << " of "
                       << unaffected_seed);
  CHECK(unaffected_seed >= 100);
  CHECK(changed_seed == 0);                            // the seed's frame chooses: exactly the old light
  CHECK(changed_current * 10 >= unaffected_current);   // this frame's powers: many choices move
}

TEST_CASE("at most one gradient sample per stratum of the current frame, for stratum sizes 2, 3 and 4") {
  const Scene scene = load_scene("pillars");
  for (const int s : {2, 3, 4}) {
    INFO("stratum size " << s);
    GradientParams params;
    params.stratum_size = s;
    const int width = 48, height = 24;  // multiples of 2, 3 and 4
    const std::vector<Frame> frames = render_sequence(scene, 10, 11, width, height, params);
    std::vector<int> per_stratum(size_t(width / s) * size_t(height / s), 0);
    const std::vector<size_t> pixels = gradient_pixels(frames[1]);
    for (const size_t i : pixels) ++per_stratum[(i / width / s) * size_t(width / s) + (i % width) / s];
    for (const int count : per_stratum) CHECK(count <= 1);
    CHECK(pixels.size() <= size_t(width * height / (s * s)));  // at most 1/s^2 of the pixels
    CHECK(pixels.size() >= size_t(width * height / (s * s)) / 4);  // and not none: pillars covers the frame
  }
}

TEST_CASE("random selection is uniform over a full stratum's pixels (chi-square, 100 frames)") {
  // 16 x 16 full strata of 3 x 3 pixels, 100 frames: 25600 draws over 9 positions, 2844 expected each.
  const int s = 3, strata = 16;
  const PreviousFrame prev = covered_previous(strata * s, strata * s);
  GradientParams params;
  std::vector<double> counts(size_t(s * s), 0.0);
  for (int frame = 1; frame <= 100; ++frame)
    for (int sy = 0; sy < strata; ++sy)
      for (int sx = 0; sx < strata; ++sx) {
        const uint32_t j = select_gradient_source(prev, sx, sy, params, 7u, frame);
        REQUIRE(j != kInvalidId);
        const int x = int(j % uint32_t(strata * s)), y = int(j / uint32_t(strata * s));
        REQUIRE(x / s == sx);
        REQUIRE(y / s == sy);
        counts[size_t((y % s) * s + x % s)] += 1.0;
      }
  const double expected = 100.0 * strata * strata / (s * s);
  double chi2 = 0.0;
  for (const double c : counts) chi2 += (c - expected) * (c - expected) / expected;
  INFO("chi-square " << chi2 << " (8 degrees of freedom; 26.1 is the 0.1% critical value)");
  CHECK(chi2 < 26.1);
}

TEST_CASE("brightest selection, partial strata and seed chains") {
  const PreviousFrame prev = covered_previous(10, 7);  // strata of 3: the last column and row are partial
  GradientParams brightest;
  brightest.selection = 1;
  // l(j) = j: the brightest pixel of a stratum is its last, bottom-right one.
  CHECK(select_gradient_source(prev, 0, 0, brightest, 0u, 1) == uint32_t(2 * 10 + 2));
  CHECK(select_gradient_source(prev, 3, 2, brightest, 0u, 1) == uint32_t(6 * 10 + 9));  // a 1 x 1 stratum
  // A random pick in a partial stratum stays inside it.
  const GradientParams random;
  for (int frame = 0; frame < 50; ++frame) {
    const uint32_t j = select_gradient_source(prev, 3, 1, random, 0u, frame);  // column 9, rows 3-5
    CHECK(j % 10 == 9);
    CHECK(j / 10 >= 3);
    CHECK(j / 10 <= 5);
  }
  // Without chains a pixel that was a gradient sample is not picked again.
  PreviousFrame chained = prev;
  chained.was_gradient.assign(chained.was_gradient.size(), true);
  GradientParams no_chains;
  no_chains.seed_chains = 0;
  CHECK(select_gradient_source(chained, 1, 1, no_chains, 0u, 3) == kInvalidId);
  no_chains.selection = 1;
  CHECK(select_gradient_source(chained, 1, 1, no_chains, 0u, 3) == kInvalidId);
  CHECK(select_gradient_source(chained, 1, 1, GradientParams{}, 0u, 3) != kInvalidId);  // chains allowed
}

TEST_CASE("a merged pixel's motion returns to its source pixel, and no occluded sample is merged") {
  // pillars: eleven pillars move in front of a lit wall, so samples move, leave and get hidden.
  const Scene scene = load_scene("pillars");
  const int width = 160, height = 90;  // large enough that the pillars move by pixels from frame to frame
  const std::vector<Frame> frames = render_sequence(scene, 20, 21, width, height);
  const Frame& cur = frames[1];
  const std::vector<size_t> pixels = gradient_pixels(cur);
  REQUIRE(pixels.size() >= 50);
  // Frame 21 as rasterized, before the merge: what the occlusion test saw.
  const FrameGeometry plain = rasterize_frame(scene, 21, width, height);
  const PreviousFrame prev = PreviousFrame::from_frame(frames[0]);
  int moved = 0;
  for (const size_t i : pixels) {
    const uint32_t j = cur.uint_channel("gradient.source").data[i];
    const glm::vec2 target(float(i % width) + 0.5f, float(i / width) + 0.5f);
    const glm::vec2 source(float(j % width) + 0.5f, float(j / width) + 0.5f);
    const glm::vec2 motion(cur.float_channel("motion.X").data[i], cur.float_channel("motion.Y").data[i]);
    INFO("pixel " << i << " from " << j);
    CHECK(std::abs(target.x + motion.x - source.x) <= 1e-3f);
    CHECK(std::abs(target.y + motion.y - source.y) <= 1e-3f);
    moved += i != j;
    const ForwardProjection f =
        forward_project(scene, plain.pose, plain.view, plain.vis, prev.vis.sample(int(j % width), int(j / width)));
    CHECK(f.on_screen);
    CHECK_FALSE(f.occluded);
    CHECK(size_t(f.pixel.y) * width + size_t(f.pixel.x) == i);
    CHECK(plain.vis.instance[i] != kInvalidId);
  }
  CHECK(moved > 0);  // the scene moves: some samples land elsewhere
}

TEST_CASE("a sample never replaces another instance: the light panel under the ceiling keeps its emission") {
  // falling-light's panel hangs 2 cm under the ceiling, well within the depth test's 1 %: ceiling samples once
  // passed it and replaced the panel's pixels. Merged samples must land on their own instance, so the emission
  // layer (uniform per emitter) is the plain render's at every pixel.
  const Scene scene = load_scene("falling-light");
  const std::vector<Frame> frames = render_sequence(scene, 26, 30, 96, 54);
  for (size_t k = 1; k < frames.size(); ++k) {
    const Frame plain = render_frame(scene, 26 + int(k), 96, 54, {});
    INFO("frame " << 26 + k);
    CHECK(frames[k].float_channel("emission.G").data == plain.float_channel("emission.G").data);
  }
  CHECK(gradient_pixels(frames[4]).size() >= 400);
}

TEST_CASE("gradient frames are bit-identical with 1 and 2 threads") {
  const Scene scene = load_scene("pillars");
  std::vector<std::vector<Frame>> runs;
  for (const int threads : {1, 2}) {
    set_thread_count(threads);
    runs.push_back(render_sequence(scene, 5, 7, 40, 24));
  }
  set_thread_count(0);
  for (size_t f = 0; f < runs[0].size(); ++f) {
    INFO("frame " << f);
    for (const auto& [name, plane] : runs[0][f].float_channels()) {
      INFO(name);
      const std::vector<float>& other = runs[1][f].float_channel(name).data;
      REQUIRE(other.size() == plane.data.size());
      for (size_t i = 0; i < other.size(); ++i)
        CHECK(std::bit_cast<uint32_t>(other[i]) == std::bit_cast<uint32_t>(plane.data[i]));
    }
    for (const auto& [name, plane] : runs[0][f].uint_channels()) CHECK(runs[1][f].uint_channel(name).data == plane.data);
  }
}

TEST_CASE("gradient samples refuse a previous frame of another size, more than 1 spp and bad parameters") {
  const Scene scene = load_scene("cornell");
  const Frame small = render_frame_with_gradients(scene, 0, 16, 9, {}, {}, nullptr);
  CHECK_THROWS_AS(render_frame_with_gradients(scene, 1, 18, 9, {}, {}, &small), Error);
  RenderSettings many;
  many.spp = 4;
  CHECK_THROWS_AS(render_frame_with_gradients(scene, 1, 16, 9, many, {}, &small), Error);
  GradientParams bad;
  bad.stratum_size = 1;
  CHECK_THROWS_AS(render_frame_with_gradients(scene, 1, 16, 9, {}, bad, &small), Error);
  Frame no_seeds = Frame(16, 9);
  no_seeds.attributes = small.attributes;
  CHECK_THROWS_AS(render_frame_with_gradients(scene, 1, 16, 9, {}, {}, &no_seeds), Error);
  // The previous frame records its scene, seed and parameters; another sequence is refused, naming what differs.
  CHECK(small.attributes.at("rtdr.scene") == "cornell");
  CHECK(small.attributes.at("rtdr.gradient.stratum_size") == "3");
  GradientParams other;
  other.stratum_size = 4;
  CHECK_THROWS_WITH(render_frame_with_gradients(scene, 1, 16, 9, {}, other, &small),
                    Catch::Contains("rtdr.gradient.stratum_size is 3, not 4"));
  RenderSettings reseeded;
  reseeded.seed = 9;
  CHECK_THROWS_WITH(render_frame_with_gradients(scene, 1, 16, 9, reseeded, {}, &small), Catch::Contains("rtdr.seed"));
  CHECK_THROWS_WITH(render_frame_with_gradients(load_scene("static"), 1, 16, 9, {}, {}, &small),
                    Catch::Contains("rtdr.scene is cornell, not static"));
  Frame unrecorded = small;
  unrecorded.attributes.clear();
  CHECK_THROWS_WITH(render_frame_with_gradients(scene, 1, 16, 9, {}, {}, &unrecorded),
                    Catch::Contains("does not record"));
  // Every setting of the tracer changes f(G, seed), so each is part of the sequence: the bounces, the regularized
  // roughness and the shading term (issue: a sequence rendered with one bounce was continued with none, and every
  // indirect delta became the whole previous indirect light).
  RenderSettings direct_only;
  direct_only.trace.max_bounces = 0;
  CHECK_THROWS_WITH(render_frame_with_gradients(scene, 1, 16, 9, direct_only, {}, &small),
                    Catch::Contains("rtdr.max_bounces is 1, not 0"));
  RenderSettings rough;
  rough.trace.regularized_roughness = 0.5f;
  CHECK_THROWS_WITH(render_frame_with_gradients(scene, 1, 16, 9, rough, {}, &small),
                    Catch::Contains("rtdr.regularized_roughness is 0.300000012, not 0.5"));
  RenderSettings shaded;
  shaded.trace.shading_samples = 4;
  CHECK_THROWS_WITH(render_frame_with_gradients(scene, 1, 16, 9, shaded, {}, &small),
                    Catch::Contains("rtdr.shading_samples is 0, not 4"));
  // Frame i continues frame i-1, not another frame of the sequence.
  CHECK_THROWS_WITH(render_frame_with_gradients(scene, 2, 16, 9, {}, {}, &small),
                    Catch::Contains("is frame 0, not frame 1"));
  // A scene is its content, not its name: the same stem with other content is another scene.
  Scene edited = scene;
  edited.content_hash = "0123456789abcdef";
  CHECK_THROWS_WITH(render_frame_with_gradients(edited, 1, 16, 9, {}, {}, &small),
                    Catch::Contains("rtdr.scene.hash is " + scene.content_hash + ", not 0123456789abcdef"));
  // The control: frame 1 of the same sequence continues it.
  CHECK(render_frame_with_gradients(scene, 1, 16, 9, {}, {}, &small).attributes.at("rtdr.frame") == "1");
}

TEST_CASE("Eq. 4-5: without seed reuse Var(delta) = 2 Var(f) on a static scene, with reuse it is lower") {
  // Static scene, independent seeds: f_i and f_{i-1} are independent samples of the same pixel, so
  // Var(delta) = Var(f_i) + Var(f_{i-1}) - 2 Cov = 2 Var(f) [ASVGF18 Eq. 4-5]. Var(f) is each pixel's own 1-spp
  // variance across frames (plain renders of the same frames), averaged over the pixels in proportion to how
  // often each was a gradient pixel; E[delta] = 0, so Var(delta) is the mean of delta^2. The direct stream only:
  // its luminance is far less heavy-tailed than the indirect one's.
  const Scene scene = load_scene("static");
  const int width = 24, height = 18, frames = 400;
  const size_t n = size_t(width) * size_t(height);
  GradientParams fresh;
  fresh.seed_reuse = 0;
  std::vector<double> sum(n, 0.0), sum2(n, 0.0);
  std::vector<int> picked(n, 0);
  double delta2 = 0.0;
  long deltas = 0;
  std::optional<Frame> prev;
  for (int f = 0; f < frames; ++f) {
    Frame frame = render_frame_with_gradients(scene, f, width, height, {}, fresh, prev ? &*prev : nullptr);
    const Frame plain = render_frame(scene, f, width, height, {});
    for (size_t i = 0; i < n; ++i) {
      const double l = luminance_at(plain, "direct", i);
      sum[i] += l;
      sum2[i] += l * l;
    }
    for (const size_t i : gradient_pixels(frame)) {
      const double d = double(luminance_at(frame, "direct", i)) - frame.float_channel("gradient.prev_direct").data[i];
      delta2 += d * d;
      ++deltas;
      ++picked[i];
    }
    prev = std::move(frame);
  }
  double var_f = 0.0;
  for (size_t i = 0; i < n; ++i) {
    const double mean = sum[i] / frames;
    var_f += picked[i] * (sum2[i] / frames - mean * mean) * frames / (frames - 1);
  }
  var_f /= double(deltas);
  const double ratio = delta2 / double(deltas) / (2.0 * var_f);
  INFO(deltas << " gradient samples: Var(delta) = " << delta2 / double(deltas) << ", 2 Var(f) = " << 2.0 * var_f
              << ", ratio " << ratio);
  CHECK(deltas >= 10000);
  CHECK(ratio == Approx(1.0).margin(0.1));
  WARN("Eq. 4-5 on static, " << deltas << " samples: Var(delta) / (2 Var(f)) = " << ratio);

  // With reuse, on the slowly moving pillars, the two samples share their random numbers: Var(delta) falls.
  double with_reuse = 0.0, without_reuse = 0.0;
  for (const int reuse : {1, 0}) {
    GradientParams params;
    params.seed_reuse = reuse;
    const Scene pillars = load_scene("pillars");
    double d2 = 0.0;
    long count = 0;
    const std::vector<Frame> run = render_sequence(pillars, 0, 20, 48, 27, params);
    for (const Frame& frame : run)
      for (const size_t i : gradient_pixels(frame)) {
        const double d = double(luminance_at(frame, "direct", i)) - frame.float_channel("gradient.prev_direct").data[i];
        d2 += d * d;
        ++count;
      }
    (reuse ? with_reuse : without_reuse) = d2 / double(count);
  }
  WARN("Eq. 4-5 on pillars: Var(delta) with seed reuse " << with_reuse << ", without " << without_reuse);
  CHECK(with_reuse < 0.5 * without_reuse);
}

TEST_CASE("a previous frame whose ids, barycentrics, seed frames or light do not fit the scene is refused") {
  // render --gradients continues from frame A-1 read from a file: every value that indexes the scene or memory is
  // checked before any is used (PreviousFrame::require_fits); an id beyond the scene read past its arrays.
  const Scene scene = load_scene("cornell");
  const std::vector<Frame> frames = render_sequence(scene, 0, 1, 16, 9);
  const PreviousFrame prev = PreviousFrame::from_frame(frames[1]);
  CHECK_NOTHROW(prev.require_fits(scene, 2, "f.exr"));  // as rendered
  size_t i = 0;
  while (prev.vis.instance[i] == kInvalidId) ++i;
  const uint32_t triangles = uint32_t(scene.meshes[size_t(scene.instances[prev.vis.instance[i]].mesh)].triangles.size());
  const auto refused = [&](const std::function<void(PreviousFrame&)>& change, const std::string& part) {
    PreviousFrame p = prev;
    change(p);
    INFO(part);
    CHECK_THROWS_WITH(p.require_fits(scene, 2, "f.exr"),
                      Catch::StartsWith("'f.exr' (frame 1, which frame 2 continues): " + part));
  };
  refused([&](PreviousFrame& p) { p.vis.instance[i] = uint32_t(scene.instances.size()); },
          "id.instance is " + std::to_string(scene.instances.size()) + ", but scene 'cornell' has " +
              std::to_string(scene.instances.size()) + " instances");
  refused([&](PreviousFrame& p) { p.vis.triangle[i] = triangles; },
          "id.triangle is " + std::to_string(triangles) + ", but instance");
  refused([&](PreviousFrame& p) { p.vis.bary[i].y = NAN; }, "bary.U or bary.V is not finite");
  refused([&](PreviousFrame& p) { p.seed_frame[0] = 2; }, "rng.seed_frame is 2, not a frame before 2");
  refused([&](PreviousFrame& p) { p.luminance_indirect[3] = INFINITY; }, "the luminance of direct or indirect");
  // Where no surface is seen, the triangle and barycentrics are never read: anything goes.
  PreviousFrame background = prev;
  size_t b = 0;
  while (b < background.vis.instance.size() && background.vis.instance[b] != kInvalidId) ++b;
  if (b < background.vis.instance.size()) {
    background.vis.triangle[b] = 0xFFFFFFF0u;
    background.vis.bary[b] = glm::vec2(NAN);
    CHECK_NOTHROW(background.require_fits(scene, 2, "f.exr"));
  }
  // And render_frame_with_gradients checks before it selects: a frame with a triangle id past the mesh.
  Frame damaged = frames[1];
  damaged.source = "out/frame_0001.exr";
  damaged.uint_channel("id.triangle").data[i] = 4'000'000;
  CHECK_THROWS_WITH(render_frame_with_gradients(scene, 2, 16, 9, {}, {}, &damaged),
                    Catch::StartsWith("'out/frame_0001.exr' (frame 1, which frame 2 continues): id.triangle is 4000000"));
}
