// Tests of trace/shading.cpp, the noise-free shading term S = direct.shading [TRMV21 Sec. 4.3]:
// - S from a square emitter over a floor matches the quadrature of our own BRDF over the emitter;
// - with a Lambertian reflectance through the same estimator, S = (rho / pi) E, E from Lambert's polygon formula,
//   on a floor, on a tilted receiver and under two lights of different power;
// - where nothing is in the way S is the whole direct integral, the mean of the path's `direct`, so S x V
//   replaces `direct` and must not be added to its BSDF-hit emission;
// - a frame's layer is the demodulated estimate of M ceil(sqrt(spp)) samples, bit for bit, and it changes no
//   other layer; with no lights it is 0.
//
// Tolerances. One estimate of M light samples is a deterministic function of its seed; estimates under distinct
// pixel seeds are independent. So each check takes K estimates under K seeds, their mean has the standard error
// sqrt(sample variance / K) of RunningMean, and the mean must lie within 4 of those of the exact value (plus
// 1e-5 relative for the quadrature, which agrees with Lambert's formula to 1e-5 in tests/trace_path_tracer_test.cpp).
// The spread of one estimate, sigma_M = standard error x sqrt(K), is the noise a 1-spp frame's S carries: the
// tests print it beside sigma_1 / sqrt(M), what M independent light samples would give, and check it is smaller.
#include "trace/shading.h"

#include "core/color.h"
#include "raster/gbuffer_frame.h"
#include "scenes/gltf_loader.h"
#include "trace/brdf.h"
#include "trace/render_frame.h"
#include "core/sampler.h"
#include "trace_fixtures.h"

#include <catch2/catch.hpp>

#include <cmath>
#include <cstring>
#include <numbers>
#include <string>
#include <utility>
#include <vector>

using namespace rtdr;
using namespace rtdr::test;

namespace {

constexpr double kPi = std::numbers::pi;
constexpr uint32_t kM = 64;        // TraceOptions::shading_samples' default
constexpr int kEstimates = 512;    // K independent estimates per check

// K estimates of one quantity, estimate(seed) for K distinct pixel seeds, and the spread of single-sample ones.
struct Estimates {
  RunningMean of_m;  // estimates of M samples each
  RunningMean of_1;  // estimates of 1 sample each: their spread is sigma_1
  double sigma_m() const { return of_m.standard_error() * std::sqrt(of_m.n); }
  double sigma_1() const { return of_1.standard_error() * std::sqrt(of_1.n); }
};

template <class Estimate>
Estimates estimate_many(uint32_t global_seed, Estimate estimate) {
  Estimates e;
  for (int k = 0; k < kEstimates; ++k) {
    const uint32_t seed = pixel_seed(global_seed, 0, k, 0);
    e.of_m.add(estimate(seed, kM));
    e.of_1.add(estimate(seed, 1u));
  }
  return e;
}

// The checks every comparison makes, with what they measured. `noise` bounds one estimate's spread relative to
// S: the claim behind "noise-free" (path_tracer.h, trace/README.md).
void check_against(const Estimates& e, double expected, double noise) {
  INFO("S = " << e.of_m.mean() << " +- " << e.of_m.standard_error() << " (mean of " << kEstimates
              << " estimates of M = " << kM << "), expected " << expected << "; one estimate's spread sigma_M = "
              << e.sigma_m() << " (" << 100.0 * e.sigma_m() / expected
              << " %), M independent samples: sigma_1 / sqrt(M) = " << e.sigma_1() / std::sqrt(double(kM)));
  CHECK(std::abs(e.of_m.mean() - expected) <= 4.0 * e.of_m.standard_error() + 1e-5 * expected);
  CHECK(e.sigma_m() < e.sigma_1() / std::sqrt(double(kM)));  // the net beats independent points
  CHECK(e.sigma_m() < noise * expected);
}

// A square emitter of side 0.5 m and radiance 10 at height 1 over a floor of albedo 0.5 (trace_fixtures.h).
constexpr float kRadiance = 10.0f;
LightOverPlane square_light() { return light_over_plane(0.5f, kRadiance, 0.5f, 1.0f); }
const glm::vec3 kEye(0.0f, 1.5f, 4.0f);
// One estimate's spread, relative to S: at most 0.22% under the square light when written (so 0.5%); 1.1% at the
// point that a weak but near light lights with few of the samples (power-proportional choice), so 2% there.
constexpr double kOneLightNoise = 0.005, kTwoLightNoise = 0.02;
const glm::vec3 kFloorPoints[] = {glm::vec3(0.0f), glm::vec3(0.6f, 0.0f, 0.3f), glm::vec3(1.5f, 0.0f, -1.0f)};

}  // namespace

// S = int_light Le f(wo, wi) cos_p cos_l / r^2 dA with f = bsdf_eval (both glTF lobes: our "diffuse" material is
// not Lambertian), against the emitter quadrature of tests/trace_path_tracer_test.cpp, at three floor points.
TEST_CASE("direct_shading matches the quadrature of our BRDF over a square emitter") {
  const LightOverPlane s = square_light();
  const TraceWorld world(s.scene);
  const TraceContext c = world.context(TraceOptions{});
  const auto light = world_corners(s.scene, world.pose, s.light);
  const SurfaceBsdf floor_bsdf{glm::vec3(0.5f), 1.0f, 0.0f};
  for (const glm::vec3 point : kFloorPoints) {
    const SurfaceSample g = floor_sample(world.embree, point);
    REQUIRE(g.instance == uint32_t(s.floor));
    const SurfacePoint x = world.surfaces.at(g, kEye);
    const glm::vec3 wo = glm::normalize(kEye - x.position);
    auto brdf = [&](const glm::dvec3& wi) { return grey(bsdf_eval(floor_bsdf, x.normal, wo, glm::vec3(wi)).total()); };
    const double expected =
        emitter_quadrature(glm::dvec3(x.position), glm::dvec3(x.normal), light, kRadiance, 256, brdf);
    INFO("floor point (" << point.x << ", " << point.z << ")");
    auto estimate = [&](uint32_t seed, uint32_t m) { return grey(direct_shading(c, g, kEye, seed, m)); };
    check_against(estimate_many(11u, estimate), expected, kOneLightNoise);
  }
}

// Lambert's formula gives the irradiance E exactly; a Lambertian reflectance rho / pi reflects (rho / pi) E. The
// estimator (unshadowed_direct, the code direct_shading runs) gets f = rho / pi: on the floor; on a receiver tilted
// by 20 degrees (the light stays wholly above its tangent plane, as the formula needs); and with a second, weaker
// and smaller light, where the power-proportional choice and sample reuse matter (E is then the sum of both).
TEST_CASE("a Lambertian reflectance through the same estimator gives (rho / pi) E, E by Lambert's polygon formula") {
  constexpr float kRho = 0.5f;
  auto lambertian = [](const glm::vec3&) { return glm::vec3(kRho / float(kPi)); };
  LightOverPlane two = square_light();
  const int second = add_quad(two.scene, 0.3f, glm::vec3(0.8f, 1.5f, -0.4f), about_x(90.0f),
                              add_material(two.scene, emissive_material(4.0f)));
  const LightOverPlane one = square_light();
  const float tilt = glm::radians(20.0f);
  const glm::vec3 tilted_normal(std::sin(tilt), std::cos(tilt), 0.0f);
  struct Case {
    const LightOverPlane* scene;
    glm::vec3 position, normal;
  };
  const Case cases[] = {{&one, kFloorPoints[1], glm::vec3(0, 1, 0)}, {&one, kFloorPoints[2], glm::vec3(0, 1, 0)},
                        {&one, kFloorPoints[1], tilted_normal},      {&two, kFloorPoints[0], glm::vec3(0, 1, 0)},
                        {&two, kFloorPoints[2], tilted_normal}};
  for (const Case& k : cases) {
    const TraceWorld world(k.scene->scene);
    SurfacePoint x;
    x.position = k.position;
    x.normal = x.geo_normal = k.normal;
    const glm::dvec3 p(x.position), n(x.normal);
    const auto corners = world_corners(k.scene->scene, world.pose, k.scene->light);
    double irradiance = lambert_polygon_irradiance(p, n, corners, kRadiance);
    if (k.scene == &two)
      irradiance += lambert_polygon_irradiance(p, n, world_corners(two.scene, world.pose, second), 4.0);
    INFO((k.scene == &two ? "two lights" : "one light") << ", point (" << p.x << ", " << p.z << "), normal ("
                                                         << n.x << ", " << n.y << ")");
    check_against(estimate_many(12u, [&](uint32_t seed, uint32_t m) {
                    return grey(unshadowed_direct(world.lights, x, hash_combine(seed, kShadingStream), m, lambertian));
                  }),
                  kRho / kPi * irradiance, k.scene == &two ? kTwoLightNoise : kOneLightNoise);
  }
}

// With nothing between the floor and the light, `direct` (NEE x V with MIS + BSDF-hit emission with MIS) and S
// estimate the same integral: S x V (V = 1 here) is all of the direct light. Under a large emitter (4 m square at
// 1 m, radiance 1) BSDF sampling is the better strategy and carries most of `direct`, so S plus the BSDF-hit part
// would miss by far more than the noise. 8192 paths per point (B = 1: the BSDF ray and its MIS weight take part).
TEST_CASE("unoccluded, S equals the mean of the path's direct light: it replaces direct, it is not added to it") {
  constexpr int kPaths = 8192;
  const LightOverPlane s = light_over_plane(0.5f, 1.0f, 4.0f, 1.0f);
  const TraceWorld world(s.scene);
  const TraceContext c = world.context(TraceOptions{});
  for (const glm::vec3 point : kFloorPoints) {
    const SurfaceSample g = floor_sample(world.embree, point);
    REQUIRE(g.instance == uint32_t(s.floor));
    RunningMean direct, bsdf_part, shading;
    for (int i = 0; i < kPaths; ++i) {
      const uint32_t seed = pixel_seed(13u, 0, i, 0);
      const PathSample path = trace_path(c, g, kEye, seed, 0);
      direct.add(grey(path.direct));
      bsdf_part.add(grey(path.direct - path.direct_unshadowed * path.direct_visibility));
      if (i < kEstimates) shading.add(grey(direct_shading(c, g, kEye, seed, kM)));
    }
    INFO("floor point (" << point.x << ", " << point.z << "): direct " << direct.mean() << " +- "
                         << direct.standard_error() << " (of which BSDF-hit emission " << bsdf_part.mean() << "), S "
                         << shading.mean() << " +- " << shading.standard_error());
    const double tolerance = 4.0 * std::hypot(direct.standard_error(), shading.standard_error());
    CHECK(std::abs(direct.mean() - shading.mean()) <= tolerance);
    CHECK(bsdf_part.mean() > 0.5 * direct.mean());  // not vacuous: S + that part would be 1.5 x too bright
  }
}

// ---------------------------------------------------------------------------------------------------------
// The layer in a frame.

namespace {

RenderSettings settings_with(int spp, int shading_samples) {
  RenderSettings s;
  s.spp = spp;
  s.seed = 3u;
  s.trace.max_bounces = 2;
  s.trace.shading_samples = shading_samples;
  return s;
}

}  // namespace

// trace_pixel takes one estimate of M ceil(sqrt(spp)) samples under the pixel seed (shading.h), demodulated like
// the other layers; the same call again gives the same bits.
TEST_CASE("direct.shading is direct_shading of M ceil(sqrt(spp)) samples under the pixel seed, demodulated") {
  CHECK(shading_sample_count(16, 1) == 16);
  CHECK(shading_sample_count(16, 3) == 32);
  CHECK(shading_sample_count(16, 4) == 32);
  CHECK(shading_sample_count(16, 5) == 48);
  CHECK(shading_sample_count(64, 1 << 20) == 65536);  // the largest: M 1024 and 2^20 spp give 2^20
  CHECK(shading_sample_count(0, 9) == 0);
  const Scene scene = load_scene("cornell");
  const FrameGeometry geometry = rasterize_frame(scene, 0, 24, 18);
  for (const auto& [spp, samples] : {std::pair{1, 16u}, std::pair{3, 32u}}) {
    const RenderSettings settings = settings_with(spp, 16);
    Frame frame(24, 18);
    trace_layers(scene, geometry, settings, frame);
    const std::vector<glm::vec3> shading = frame.get_rgb("direct.shading");
    const TraceWorld world(scene, geometry.pose);
    const TraceContext c = world.context(settings.trace);
    int pixels = 0, lit = 0;
    for (int y = 0; y < 18; ++y)
      for (int x = 0; x < 24; ++x) {
        const SurfaceSample g = geometry.vis.sample(x, y);
        const size_t i = geometry.vis.index(x, y);
        if (!g.valid()) {
          CHECK(shading[i] == glm::vec3(0.0f));
          continue;
        }
        const uint32_t seed = pixel_seed(settings.seed, geometry.index, x, y);
        const glm::vec3 once = direct_shading(c, g, geometry.view.eye, seed, samples);
        const glm::vec3 albedo = demodulation_factor(world.surfaces.at(g, geometry.view.eye).albedo);
        INFO("spp " << spp << ", pixel (" << x << ", " << y << ")");
        CHECK(same_bits(shading[i], once / albedo));
        CHECK(same_bits(once, direct_shading(c, g, geometry.view.eye, seed, samples)));
        ++pixels;
        lit += luminance(shading[i]) > 0.0f;
      }
    CHECK(pixels > 300);
    CHECK(lit > pixels / 2);  // the box is lit almost everywhere (the light's own plane and its back are not)
  }
}

// The shading term draws from a sequence of its own, so its sample count (0 = off) changes no bit of any other
// layer; pillars at frame 10, spp 2, 2 bounces.
TEST_CASE("direct.shading changes no other layer: every other channel is bit-identical with it off, 7 or 64") {
  const Scene scene = load_scene("pillars");
  const Frame off = render_frame(scene, 10, 32, 18, settings_with(2, 0));
  CHECK_FALSE(off.has("direct.shading.R"));  // off (the default): the layer is left out
  int others = 0;
  for (const int m : {7, 64}) {
    const Frame on = render_frame(scene, 10, 32, 18, settings_with(2, m));
    REQUIRE(on.float_channels().size() == off.float_channels().size() + 3);
    REQUIRE(on.has("direct.shading.R"));
    for (const auto& [name, plane] : off.float_channels()) {
      INFO("M = " << m << ", channel " << name);
      const std::vector<float>& other = on.float_channel(name).data;
      CHECK(std::memcmp(plane.data.data(), other.data(), plane.data.size() * sizeof(float)) == 0);
      others += m == 64;
    }
    for (const auto& [name, plane] : off.uint_channels()) CHECK(plane.data == on.uint_channel(name).data);
  }
  CHECK(others > 20);  // the radiance, G-buffer and path-record channels were all compared
}

// No emitter at all: the layer exists, holds 0 everywhere, and nothing divides by zero.
TEST_CASE("a scene without lights: direct.shading is 0 at every pixel") {
  Scene s = camera_scene(kEye);
  add_quad(s, 20.0f, glm::vec3(0.0f), about_x(-90.0f), add_material(s, diffuse_material(0.5f)));
  const Frame frame = render_frame(s, 0, 16, 12, settings_with(2, 64));
  const std::vector<glm::vec3> shading = frame.get_rgb("direct.shading");
  int surface = 0;
  for (size_t i = 0; i < shading.size(); ++i) {
    surface += frame.uint_channel("id.instance").data[i] != kInvalidId;
    CHECK(shading[i] == glm::vec3(0.0f));
  }
  CHECK(surface > 50);  // the floor fills the lower half of the image
}
