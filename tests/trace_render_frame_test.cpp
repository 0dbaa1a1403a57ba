// Tests of trace/render_frame.cpp, the radiance layers of a frame:
// - the layers are bit-identical for any thread count;
// - spp = N is the mean of trace_path over sample indices 0 .. N-1 with the pixel's seed, demodulated;
// - re-tracing a pixel with its stored rng.seed reproduces it exactly [ASVGF18 Sec. 3.2];
// - seeds are new every frame and differ between pixels;
// - background pixels carry no radiance and no path;
// - the reference converges: its error falls with the sample count.
#include "trace/render_frame.h"

#include "core/color.h"
#include "core/parallel.h"
#include "raster/gbuffer_frame.h"
#include "scenes/gltf_loader.h"
#include "core/sampler.h"
#include "trace_fixtures.h"

#include <catch2/catch.hpp>

#include <cmath>
#include <cstring>
#include <set>
#include <string>
#include <vector>

using namespace rtdr;
using namespace rtdr::test;

namespace {

RenderSettings settings_with(int spp, int max_bounces, uint32_t seed = 0) {
  RenderSettings s;
  s.spp = spp;
  s.seed = seed;
  s.trace.max_bounces = max_bounces;
  return s;
}

// The radiance layers and their demodulated path components, read back from a frame.
struct Layers {
  std::vector<glm::vec3> direct, indirect, unshadowed, diffuse, glossy;
  explicit Layers(const Frame& f)
      : direct(f.get_rgb("direct")), indirect(f.get_rgb("indirect")), unshadowed(f.get_rgb("direct.unshadowed")),
        diffuse(f.get_rgb("indirect.diffuse")), glossy(f.get_rgb("indirect.glossy")) {}
};

// Equal to within float rounding: the layers are (sum of N samples) * (1 / (N * albedo)), the tests form
// (sum / N) / albedo: a few roundings of 2^-24 each apart, well inside 1e-6 relative. (Sums of non-negative
// terms: no cancellation, so the relative bound holds for every value, and zeros must match exactly.)
void check_close(const glm::vec3& actual, const glm::vec3& expected) {
  for (int k = 0; k < 3; ++k) CHECK(actual[k] == Approx(expected[k]).epsilon(1e-6));
}

// Every channel of two frames, bit for bit (names, sizes, and values compared as bytes).
void check_identical_frames(const Frame& a, const Frame& b) {
  REQUIRE(a.float_channels().size() == b.float_channels().size());
  REQUIRE(a.uint_channels().size() == b.uint_channels().size());
  for (const auto& [name, plane] : a.float_channels()) {
    INFO("float channel " << name);
    REQUIRE(b.has(name));
    const std::vector<float>& other = b.float_channel(name).data;
    REQUIRE(other.size() == plane.data.size());
    CHECK(std::memcmp(plane.data.data(), other.data(), plane.data.size() * sizeof(float)) == 0);
  }
  for (const auto& [name, plane] : a.uint_channels()) {
    INFO("uint channel " << name);
    REQUIRE(b.has(name));
    CHECK(plane.data == b.uint_channel(name).data);
  }
}

// Restores the default thread count (all cores) when a test ends, even when it fails.
struct ThreadCountGuard {
  ~ThreadCountGuard() { set_thread_count(0); }
};

}  // namespace

// Rows run in parallel and each pixel's samples depend only on its seed, so the split of rows between
// threads must not matter [render_frame.h]. Pillars at frame 10 (the pillars are moving), spp 2, 3 bounces.
TEST_CASE("the frame is bit-identical for 1 and 2 threads") {
  const ThreadCountGuard guard;
  const Scene scene = load_scene("pillars");
  RenderSettings settings = settings_with(2, 3, 11u);
  settings.trace.shading_samples = kTrmvShadingSamples;
  set_thread_count(1);
  const Frame one = render_frame(scene, 10, 48, 27, settings);
  set_thread_count(2);
  const Frame two = render_frame(scene, 10, 48, 27, settings);
  REQUIRE(one.has("direct.R"));
  REQUIRE(one.has("direct.shading.R"));  // TRMV's shading term (trace/shading.h) is compared too
  REQUIRE(one.has("rng.seed"));
  check_identical_frames(one, two);
}

// trace_layers with spp = 4 against the mean of trace_path over sample indices 0 .. 3, each pixel with its own
// seed, divided by core/color.h's demodulation_factor of the pixel's albedo; the path record is sample 0's.
TEST_CASE("spp = 4 is the demodulated mean of trace_path over sample indices 0..3") {
  constexpr int kSpp = 4;
  const Scene scene = load_scene("cornell");
  const FrameGeometry geometry = rasterize_frame(scene, 0, 32, 24);
  const RenderSettings settings = settings_with(kSpp, 2, 5u);
  Frame frame(32, 24);
  trace_layers(scene, geometry, settings, frame);
  const Layers layers(frame);
  const std::vector<float>& visibility = frame.float_channel("direct.visibility").data;
  const std::vector<glm::vec3> light = frame.get_vec3("path.light");
  const TraceWorld world(scene, geometry.pose);
  const TraceContext c = world.context(settings.trace);
  const glm::vec3 eye = geometry.view.eye;
  int pixels = 0;
  for (int y = 0; y < 24; ++y)
    for (int x = 0; x < 32; ++x) {
      const SurfaceSample g = geometry.vis.sample(x, y);
      if (!g.valid()) continue;
      ++pixels;
      INFO("pixel (" << x << ", " << y << ")");
      const size_t i = geometry.vis.index(x, y);
      const uint32_t seed = pixel_seed(settings.seed, geometry.index, x, y);
      PathSample sum;
      PathRecord first;
      for (uint32_t k = 0; k < kSpp; ++k) {
        const PathSample p = trace_path(c, g, eye, seed, k);
        sum.direct += p.direct;
        sum.indirect += p.indirect;
        sum.direct_unshadowed += p.direct_unshadowed;
        sum.indirect_diffuse += p.indirect_diffuse;
        sum.indirect_glossy += p.indirect_glossy;
        sum.direct_visibility += p.direct_visibility;
        if (k == 0) first = p.record;
      }
      const glm::vec3 albedo = demodulation_factor(world.surfaces.at(g, eye).albedo);
      check_close(layers.direct[i], sum.direct / float(kSpp) / albedo);
      check_close(layers.indirect[i], sum.indirect / float(kSpp) / albedo);
      check_close(layers.unshadowed[i], sum.direct_unshadowed / float(kSpp) / albedo);
      check_close(layers.diffuse[i], sum.indirect_diffuse / float(kSpp) / albedo);
      check_close(layers.glossy[i], sum.indirect_glossy / float(kSpp) / albedo);
      // The visibility is a mean of 0s and 1s over 4 samples: one of 0, 1/4, 1/2, 3/4, 1, exactly.
      CHECK(visibility[i] == sum.direct_visibility / float(kSpp));
      CHECK(same_bits(light[i], first.light_position));
      CHECK(frame.uint_channel("path.light.instance").data[i] == first.light_instance);
    }
  CHECK(pixels > 500);  // 576 of the 768 pixels see the box
}

// [ASVGF18 Sec. 3.2]: a denoiser that forward-projects a sample re-shades it with the old seed, and must get
// the old value. At spp = 1 the layers are one sample, demodulated: times the demodulation factor it is
// trace_path(G, rng.seed, 0) again. Pillars at frame 3 (t = 0.1 s), global seed 7, every pixel.
TEST_CASE("re-tracing a pixel with its stored rng.seed and index 0 reproduces it (spp = 1)") {
  const Scene scene = load_scene("pillars");
  const RenderSettings settings = settings_with(1, 2, 7u);
  const FrameGeometry geometry = rasterize_frame(scene, 3, 48, 27);
  Frame frame(48, 27);
  trace_layers(scene, geometry, settings, frame);
  const Layers layers(frame);
  const UIntPlane& seeds = frame.uint_channel("rng.seed");
  const std::vector<glm::vec3> light = frame.get_vec3("path.light"), blocker = frame.get_vec3("path.blocker");
  const std::vector<glm::vec3> secondary = frame.get_vec3("path.secondary");
  const std::vector<glm::vec3> direction = frame.get_vec3("path.direction");
  const TraceWorld world(scene, geometry.pose);
  const TraceContext c = world.context(settings.trace);
  int pixels = 0;
  for (int y = 0; y < 27; ++y)
    for (int x = 0; x < 48; ++x) {
      const size_t i = geometry.vis.index(x, y);
      INFO("pixel (" << x << ", " << y << ")");
      CHECK(seeds.data[i] == pixel_seed(7u, 3, x, y));  // the seed render_frame.h documents
      const SurfaceSample g = geometry.vis.sample(x, y);
      if (!g.valid()) continue;
      ++pixels;
      const PathSample p = trace_path(c, g, geometry.view.eye, seeds.data[i], 0);
      const glm::vec3 albedo = demodulation_factor(world.surfaces.at(g, geometry.view.eye).albedo);
      check_close(layers.direct[i] * albedo, p.direct);
      check_close(layers.indirect[i] * albedo, p.indirect);
      // The record is copied, not computed: exact.
      CHECK(same_bits(light[i], p.record.light_position));
      CHECK(same_bits(blocker[i], p.record.blocker_position));
      CHECK(same_bits(secondary[i], p.record.secondary_position));
      CHECK(same_bits(direction[i], p.record.secondary_direction));
      CHECK(frame.uint_channel("path.light.instance").data[i] == p.record.light_instance);
      CHECK(frame.uint_channel("path.blocker.instance").data[i] == p.record.blocker_instance);
      CHECK(frame.uint_channel("path.secondary.instance").data[i] == p.record.secondary_instance);
    }
  CHECK(pixels == 48 * 27);  // pillars' camera sees only the floor, the wall and the pillars
}

// Seeds come from pixel_seed(global, frame, x, y), a hash: new every frame, different at every pixel. (A
// 32-bit hash can collide: among the 1296 seeds of a frame that happens with probability about
// 1296^2 / 2^33 = 2e-4; these seeds are fixed, and they do not.)
TEST_CASE("pixel seeds change every frame and differ between pixels") {
  const Scene scene = load_scene("pillars");
  const RenderSettings settings = settings_with(1, 1);
  const Frame f0 = render_frame(scene, 0, 48, 27, settings);
  const Frame f1 = render_frame(scene, 1, 48, 27, settings);
  const std::vector<uint32_t>& s0 = f0.uint_channel("rng.seed").data;
  const std::vector<uint32_t>& s1 = f1.uint_channel("rng.seed").data;
  CHECK(std::set<uint32_t>(s0.begin(), s0.end()).size() == s0.size());  // every pixel its own seed
  CHECK(std::set<uint32_t>(s1.begin(), s1.end()).size() == s1.size());
  int same = 0;
  for (size_t i = 0; i < s0.size(); ++i) same += s0[i] == s1[i];
  CHECK(same == 0);  // frame 1 draws new numbers at every pixel
  // Another global seed gives another sequence of frames.
  const Frame other = render_frame(scene, 0, 48, 27, settings_with(1, 1, 1u));
  CHECK(other.uint_channel("rng.seed").data != s0);
}

// The light-over-a-floor fixture, seen from (0, 1.5, 4) looking down -Z: the floor below the horizon, sky
// above it. A background pixel has no surface, so nothing is traced there.
TEST_CASE("background pixels: every radiance layer 0, every path instance kInvalidId") {
  const LightOverPlane s = light_over_plane(0.5f, 10.0f, 0.5f, 1.0f);
  const Frame frame = render_frame(s.scene, 0, 32, 24, settings_with(2, 2));
  const UIntPlane& id = frame.uint_channel("id.instance");
  const Layers layers(frame);
  const std::vector<float>& visibility = frame.float_channel("direct.visibility").data;
  int background = 0, lit = 0;
  for (size_t i = 0; i < id.data.size(); ++i) {
    if (id.data[i] != kInvalidId) {
      lit += luminance(layers.direct[i]) > 0.0f;
      continue;
    }
    ++background;
    INFO("pixel " << i);
    for (const auto* layer : {&layers.direct, &layers.indirect, &layers.unshadowed, &layers.diffuse, &layers.glossy})
      CHECK((*layer)[i] == glm::vec3(0.0f));
    CHECK(visibility[i] == 0.0f);
    for (const char* channel : {"path.light.instance", "path.blocker.instance", "path.secondary.instance"})
      CHECK(frame.uint_channel(channel).data[i] == kInvalidId);
  }
  CHECK(background > 100);  // the upper half or so of the image is sky ...
  CHECK(lit > 100);         // ... and the lower half a lit floor
}

// The reference is the mean of N samples of the same estimator, so its error falls like 1 / sqrt(N) (or
// faster: the samples of one pixel are a scrambled Sobol' set). spp = 256 uses sample indices 0 .. 255 of the
// same sequence as spp = 1024, so their difference is (3/4) (mean of 0..255 - mean of 256..1023); for
// independent samples of standard deviation sigma its size is about 0.75 sigma sqrt(1/256 + 1/768) = 0.054
// sigma, against about sigma for spp = 1. We ask for less than 1/8, over the mean of |difference| of all
// covered pixels and channels of the demodulated direct + indirect light of the Cornell box.
TEST_CASE("the reference converges: the error falls with the sample count") {
  const Scene scene = load_scene("cornell");
  const FrameGeometry geometry = rasterize_frame(scene, 0, 32, 24);
  auto total_light = [&](int spp) {
    Frame frame(32, 24);
    trace_layers(scene, geometry, settings_with(spp, 1), frame);
    const Layers layers(frame);
    std::vector<glm::vec3> light(layers.direct.size());
    for (size_t i = 0; i < light.size(); ++i) light[i] = layers.direct[i] + layers.indirect[i];
    return light;
  };
  const std::vector<glm::vec3> reference = total_light(1024);
  auto mean_error = [&](const std::vector<glm::vec3>& image) {
    double sum = 0.0;
    int n = 0;
    for (size_t i = 0; i < image.size(); ++i) {
      if (geometry.vis.instance[i] == kInvalidId) continue;
      for (int k = 0; k < 3; ++k) sum += std::abs(double(image[i][k]) - double(reference[i][k]));
      n += 3;
    }
    return sum / n;
  };
  const double error_1 = mean_error(total_light(1)), error_16 = mean_error(total_light(16));
  const double error_256 = mean_error(total_light(256));
  INFO("mean |spp - spp 1024|: spp 1 " << error_1 << ", spp 16 " << error_16 << ", spp 256 " << error_256);
  CHECK(error_16 < error_1);
  CHECK(error_256 < error_16);
  CHECK(error_256 < error_1 / 8.0);
}
