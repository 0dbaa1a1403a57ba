// Tests of filters/svgf/temporal.cpp [SVGF17 Sec. 4.1, 4.2]: the running mean and EMA on a static scene,
// disocclusions, bilinear back-projection with failed taps, the 3x3 fallback for thin geometry.
#include "filters/svgf/temporal.h"

#include "core/color.h"
#include "core/error.h"
#include "core/parallel.h"

#include "svgf_fixtures.h"

#include <catch2/catch.hpp>

#include <cmath>
#include <random>

using namespace rtdr;

namespace {


// What the pipeline hands to the next frame; here the colour history is the integrated colour itself (no
// a-trous in between).
TemporalHistory history_of(const TemporalOutput& t, const SurfacePlanes& s) {
  return {t.color, t.moment1, t.moment2, t.length, s};
}

// A uniform history of length n over surface s.
TemporalHistory uniform_history(const SurfacePlanes& s, glm::vec3 c, float n) {
  const int w = s.width(), h = s.height();
  const float l = luminance(c);
  return {RgbPlane(w, h, c), FloatPlane(w, h, l), FloatPlane(w, h, l * l), FloatPlane(w, h, n), s};
}

// The history colour the temporal pass resampled at (x, y), read from its probe.
glm::vec3 probed_history(const RgbPlane& noisy, const SurfacePlanes& cur, const TemporalHistory& prev, int x, int y,
                         Probe& probe) {
  temporal_pixel(noisy, cur, prev, SvgfParams{}, x, y, &probe);
  const auto& v = probe.find("C'_{i-1}", "history").value;
  return {v[0], v[1], v[2]};
}

}  // namespace

TEST_CASE("static scene: exact running mean for n <= 1/alpha, then the EMA, converges to the mean") {
  const int w = 5, h = 4;
  const SurfacePlanes s = flat_surface(w, h);
  const SvgfParams params;  // alpha = alpha_moments = 0.2: alpha_eff = 1/n for n <= 5
  std::mt19937 rng(17);
  const double m = 0.5;
  std::uniform_real_distribution<float> noise(0.0f, float(2.0 * m));  // i.i.d., mean m

  TemporalHistory prev;  // empty: the first frame is a disocclusion
  std::vector<double> mean(size_t(w * h), 0.0), ema(size_t(w * h), 0.0), m2(size_t(w * h), 0.0);
  double mean_error_late = 0.0;
  for (int frame = 1; frame <= 400; ++frame) {
    RgbPlane noisy(w, h);
    for (auto& c : noisy.data) c = glm::vec3(noise(rng));  // grey: luminance = the value (weights sum to 1)
    const TemporalOutput out = temporal_pass(noisy, s, prev, params);
    for (size_t i = 0; i < noisy.data.size(); ++i) {
      const double c = noisy.data[i].x;
      REQUIRE(out.length.data[i] == float(frame));
      if (frame <= 5) {
        // The running mean: mean_n = mean_{n-1} + (c - mean_{n-1}) / n, in double.
        mean[i] += (c - mean[i]) / frame;
        m2[i] += (c * c - m2[i]) / frame;
        ema[i] = mean[i];
        CHECK(out.color.data[i].x == Approx(mean[i]).epsilon(1e-6));
        CHECK(out.moment1.data[i] == Approx(mean[i]).epsilon(1e-6));
        CHECK(out.moment2.data[i] == Approx(m2[i]).epsilon(1e-6));
      } else {
        // C'_i = alpha C_i + (1 - alpha) C'_{i-1} [SVGF17 Sec. 4.1], in double.
        ema[i] = 0.2 * c + 0.8 * ema[i];
        CHECK(out.color.data[i].x == Approx(ema[i]).margin(1e-5));
      }
      if (frame > 100) mean_error_late += (out.color.data[i].x - m) / (300.0 * w * h);
    }
    prev = history_of(out, s);
  }
  // Stationary EMA of uniform noise: std = sqrt(alpha / (2 - alpha)) * (2m / sqrt(12)) = 0.096 per sample;
  // the mean over 6000 correlated samples (~9 frames' correlation time) is within ~0.004 of m.
  INFO("mean of C' - m over frames 101-400: " << mean_error_late);
  CHECK(std::abs(mean_error_late) < 0.01);
}

TEST_CASE("static scene: a step from c1 to c2 decays like (1 - alpha)^j") {
  const int w = 3, h = 2;
  const SurfacePlanes s = flat_surface(w, h);
  const SvgfParams params;
  const float c1 = 2.0f, c2 = 0.25f;
  TemporalHistory prev;
  for (int k = 0; k < 12; ++k) {  // 12 > 1/alpha frames of c1: the output is c1 and alpha_eff = alpha
    const TemporalOutput out = temporal_pass(RgbPlane(w, h, glm::vec3(c1)), s, prev, params);
    prev = history_of(out, s);
  }
  for (int j = 1; j <= 20; ++j) {
    const TemporalOutput out = temporal_pass(RgbPlane(w, h, glm::vec3(c2)), s, prev, params);
    const double expected = c2 + (c1 - c2) * std::pow(1.0 - params.alpha, j);
    for (const glm::vec3& c : out.color.data) CHECK(c.y == Approx(expected).margin(1e-5));
    // The moments follow with alpha_moments: mu1' of luminance c, mu2' of c^2.
    const double expected_mu2 = c2 * c2 + (c1 * c1 - c2 * c2) * std::pow(1.0 - params.alpha_moments, j);
    for (float mu2 : out.moment2.data) CHECK(mu2 == Approx(expected_mu2).margin(1e-5));
    prev = history_of(out, s);
  }
}

TEST_CASE("max_history caps n, and alpha_eff with it") {
  const SurfacePlanes s = flat_surface(1, 1);
  SvgfParams params;
  params.alpha = 0.0f;  // alpha_eff = 1/n: the cap is the only thing that keeps it from falling
  params.max_history = 8;
  const TemporalHistory prev = uniform_history(s, glm::vec3(1.0f), 20.0f);
  const TemporalOutput out = temporal_pass(RgbPlane(1, 1, glm::vec3(9.0f)), s, prev, params);
  CHECK(out.length.data[0] == 8.0f);
  CHECK(out.color.data[0].x == Approx(1.0 + 8.0 / 8.0));  // 1/8 * 9 + 7/8 * 1 = 2
}

TEST_CASE("disocclusion resets the history: C' = C, mu1' = l, mu2' = l^2, n = 1") {
  const int w = 6, h = 5;
  const SvgfParams params;
  SurfacePlanes prev_s = flat_surface(w, h, 3, 2.0f);
  const TemporalHistory prev = uniform_history(prev_s, glm::vec3(0.5f), 6.0f);
  SurfacePlanes cur = flat_surface(w, h, 3, 2.0f);
  const glm::vec3 C(0.3f, 1.2f, 4.0f);
  const RgbPlane noisy(w, h, C);
  const int x = 2, y = 3;
  const float l = luminance(C);

  SECTION("mesh id change") { cur.mesh.at(x, y) = 4; }
  SECTION("depth jump beyond the relative tolerance") { cur.depth.at(x, y) = 2.0f * (1.0f + 2.5f * SvgfParams{}.temporal_depth_relative); }
  SECTION("normal turned by 90 degrees") { cur.normal.at(x, y) = glm::vec3(1.0f, 0.0f, 0.0f); }
  SECTION("motion pointing outside the image") { cur.motion.at(x, y) = glm::vec2(-3.5f, 0.0f); }
  SECTION("motion of a point behind the previous camera (1e6)") { cur.motion.at(x, y) = glm::vec2(1.0e6f); }
  SECTION("motion is NaN") { cur.motion.at(x, y) = glm::vec2(std::nanf("")); }
  SECTION("first frame: empty history") {
    const TemporalPixel p = temporal_pixel(noisy, cur, TemporalHistory{}, params, x, y);
    CHECK(p.length == 1.0f);
    CHECK(p.color == C);
    return;
  }

  Probe probe;
  const TemporalPixel p = temporal_pixel(noisy, cur, prev, params, x, y, &probe);
  CHECK(p.length == 1.0f);
  CHECK(p.color == C);
  CHECK(p.moment1 == l);
  CHECK(p.moment2 == l * l);
  CHECK(probe.find("found", "history").value[0] == 0.0f);
  // Its neighbours keep their history: n = 7, C' = 0.2 C + 0.8 * 0.5.
  const TemporalPixel q = temporal_pixel(noisy, cur, prev, params, x + 1, y);
  CHECK(q.length == 7.0f);
  CHECK(q.color.x == Approx(0.2 * C.x + 0.8 * 0.5));
}

TEST_CASE("consistency thresholds: small depth and normal changes keep the history") {
  const SvgfParams params;
  const SurfacePlanes prev_s = flat_surface(3, 3, 0, 10.0f);
  const TemporalHistory prev = uniform_history(prev_s, glm::vec3(1.0f), 3.0f);
  SurfacePlanes cur = flat_surface(3, 3, 0, 10.0f);
  const RgbPlane noisy(3, 3, glm::vec3(0.0f));
  // A camera moving towards the surface by half the relative tolerance.
  cur.depth.at(1, 1) = 10.0f * (1.0f - 0.5f * SvgfParams{}.temporal_depth_relative);
  CHECK(temporal_pixel(noisy, cur, prev, params, 1, 1).length == 4.0f);
  // A surface turned by half the normal threshold's angle.
  const float half_angle = 0.5f * std::acos(SvgfParams{}.temporal_normal_cosine);
  cur.normal.at(1, 1) = glm::vec3(std::sin(half_angle), 0.0f, std::cos(half_angle));
  CHECK(temporal_pixel(noisy, cur, prev, params, 1, 1).length == 4.0f);
  // A grazing surface, depth 10 + 3 (x - 1) in the previous frame, the camera panned by half a pixel: now
  // pixel 1 sees the point of x = 1.5, depth 11.5. The tap pixels 1 and 2 differ from it by 1.5, more than
  // 10 % of the depth, yet pass thanks to the gradient term |grad z . (q - p')| = 3 * 0.5.
  SurfacePlanes tilted_prev = flat_surface(3, 3, 0, 10.0f);
  SurfacePlanes tilted = flat_surface(3, 3, 0, 10.0f);
  for (int y = 0; y < 3; ++y)
    for (int x = 0; x < 3; ++x) {
      tilted_prev.depth.at(x, y) = 10.0f + 3.0f * float(x - 1);
      tilted.depth.at(x, y) = 11.5f + 3.0f * float(x - 1);
      tilted.depth_grad.at(x, y) = glm::vec2(3.0f, 0.0f);
      tilted.motion.at(x, y) = glm::vec2(0.5f, 0.0f);  // p' of pixel 1 halfway between pixels 1 and 2
    }
  const TemporalHistory tilted_history = uniform_history(tilted_prev, glm::vec3(1.0f), 3.0f);
  Probe probe;
  CHECK(temporal_pixel(noisy, tilted, tilted_history, params, 1, 1, &probe).length == 4.0f);
  CHECK(probe.find("consistent", "bilinear tap (0, 0)").value[0] == 1.0f);
  CHECK(probe.find("consistent", "bilinear tap (1, 0)").value[0] == 1.0f);
  CHECK(probe.find("|z - z'|", "bilinear tap (1, 0)").value[0] == 1.5f);
  CHECK(probe.find("depth tolerance", "bilinear tap (1, 0)").value[0] ==
        Approx(SvgfParams{}.temporal_depth_relative * 13.0 + 1.5));
  // Without the gradient term the tolerance would be 1.3 < 1.5: the surface would lose its own history.
  CHECK(SvgfParams{}.temporal_depth_relative * 13.0f < 1.5f);
}

TEST_CASE("bilinear back-projection is exact on a linear ramp, a failed tap's weight is renormalised away") {
  const int w = 8, h = 6;
  const SurfacePlanes prev_s = flat_surface(w, h);
  // The history is the ramp r(p) = 0.5 + 0.25 p.x + 0.125 p.y, sampled at pixel centres.
  const auto ramp = [](glm::vec2 p) { return 0.5f + 0.25f * p.x + 0.125f * p.y; };
  TemporalHistory prev = uniform_history(prev_s, glm::vec3(0.0f), 10.0f);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) prev.color.at(x, y) = glm::vec3(ramp({x + 0.5f, y + 0.5f}));
  SurfacePlanes cur = flat_surface(w, h);
  for (auto& m : cur.motion.data) m = glm::vec2(0.25f, 0.5f);
  const RgbPlane noisy(w, h, glm::vec3(1.0f));

  SECTION("all taps consistent: the history at p' is r(p')") {
    const TemporalOutput out = temporal_pass(noisy, cur, prev, SvgfParams{});
    for (int y = 0; y < h - 1; ++y)  // the last row and column have taps outside: checked below
      for (int x = 0; x < w - 1; ++x) {
        const glm::vec2 p_prev(x + 0.75f, y + 1.0f);
        // n = 11, alpha_eff = 0.2: C' = 0.2 * 1 + 0.8 r(p')
        CHECK(out.color.at(x, y).x == Approx(0.2 + 0.8 * ramp(p_prev)).margin(1e-5));
        CHECK(out.length.at(x, y) == 11.0f);
      }
    Probe probe;
    CHECK(probed_history(noisy, cur, prev, 3, 2, probe).x == Approx(ramp({3.75f, 3.0f})).margin(1e-6));
    CHECK(probe.find("w_bilinear", "bilinear tap (0, 0)").value[0] == 0.375f);  // (1 - 0.25)(1 - 0.5)
    CHECK(probe.find("w_bilinear", "bilinear tap (1, 1)").value[0] == 0.125f);  // 0.25 * 0.5
  }
  SECTION("the tap (1, 1) fails: weights 0.375, 0.125, 0.375 over their sum 0.875") {
    // p' of pixel (3, 2) is (3.75, 3.0): taps (3, 2), (4, 2), (3, 3), (4, 3). Tap (4, 3) is another mesh.
    prev.surface.mesh.at(4, 3) = 9;
    Probe probe;
    const float got = probed_history(noisy, cur, prev, 3, 2, probe).x;
    const double expected =
        (0.375 * ramp({3.5f, 2.5f}) + 0.125 * ramp({4.5f, 2.5f}) + 0.375 * ramp({3.5f, 3.5f})) / 0.875;
    CHECK(got == Approx(expected).margin(1e-6));
    CHECK(probe.find("consistent", "bilinear tap (1, 1)").value[0] == 0.0f);
    CHECK(probe.find("w (0, 0) / sum", "bilinear").value[0] == Approx(0.375 / 0.875));
    CHECK(probe.find("w (1, 1) / sum", "bilinear").value[0] == 0.0f);
    CHECK(probe.find("ran", "3x3 fallback").value[0] == 0.0f);
    // The renormalised lengths are 10 only up to rounding; n counts whole frames.
    CHECK(probe.find("weighted mean of the taps' n", "history").value[0] == Approx(10.0f));
    CHECK(probe.find("n_{i-1}", "history").value[0] == 10.0f);
    CHECK(temporal_pixel(noisy, cur, prev, SvgfParams{}, 3, 2).length == 11.0f);
  }
  SECTION("at the image's right edge the outside taps drop out") {
    // Pixel (7, 2): p' = (7.75, 3.0), taps (7, 2) and (7, 3) with weight 0.375 each, (8, 2) and (8, 3) outside:
    // renormalised, 0.5 and 0.5.
    Probe probe;
    const float got = probed_history(noisy, cur, prev, 7, 2, probe).x;
    CHECK(got == Approx(0.5 * ramp({7.5f, 2.5f}) + 0.5 * ramp({7.5f, 3.5f})).margin(1e-6));
    CHECK(probe.find("inside", "bilinear tap (1, 0)").value[0] == 0.0f);
  }
}

TEST_CASE("the 3x3 fallback finds thin geometry the bilinear taps miss") {
  const int w = 8, h = 6;
  // A one-pixel wire (mesh 7) over a wall (mesh 0). In the previous frame the wire was at (3, 2).
  SurfacePlanes prev_s = flat_surface(w, h);
  TemporalHistory prev = uniform_history(prev_s, glm::vec3(0.1f), 5.0f);
  prev.surface.mesh.at(3, 2) = 7;
  prev.color.at(3, 2) = glm::vec3(2.0f);
  prev.length.at(3, 2) = 6.0f;
  // Now it is at (4, 3) with motion (0.1, 0.1): p' = (4.6, 3.6), bilinear taps (4..5, 3..4), all wall;
  // the 3x3 around floor(p') = (4, 3) covers (3..5, 2..4), which holds (3, 2).
  SurfacePlanes cur = flat_surface(w, h);
  cur.mesh.at(4, 3) = 7;
  cur.motion.at(4, 3) = glm::vec2(0.1f, 0.1f);
  const RgbPlane noisy(w, h, glm::vec3(1.0f));

  SECTION("one neighbour matches: its history, whole") {
    Probe probe;
    CHECK(probed_history(noisy, cur, prev, 4, 3, probe) == glm::vec3(2.0f));
    CHECK(probe.find("sum of consistent weights", "bilinear").value[0] == 0.0f);
    CHECK(probe.find("ran", "3x3 fallback").value[0] == 1.0f);
    CHECK(probe.find("consistent taps", "3x3 fallback").value[0] == 1.0f);
    CHECK(probe.find("consistent", "3x3 tap (-1, -1)").value[0] == 1.0f);
    const TemporalPixel p = temporal_pixel(noisy, cur, prev, SvgfParams{}, 4, 3);
    CHECK(p.length == 7.0f);
    CHECK(p.color.x == Approx(0.2 * 1.0 + 0.8 * 2.0));
  }
  SECTION("two neighbours match: equal weights") {
    prev.surface.mesh.at(5, 2) = 7;
    prev.color.at(5, 2) = glm::vec3(4.0f);
    prev.length.at(5, 2) = 2.0f;
    Probe probe;
    CHECK(probed_history(noisy, cur, prev, 4, 3, probe) == glm::vec3(3.0f));
    CHECK(probe.find("n_{i-1}", "history").value[0] == 4.0f);  // (6 + 2) / 2
    // Lengths 6 and 1 average to 3.5: rounded to 4 whole frames.
    prev.length.at(5, 2) = 1.0f;
    Probe probe2;
    temporal_pixel(noisy, cur, prev, SvgfParams{}, 4, 3, &probe2);
    CHECK(probe2.find("weighted mean of the taps' n", "history").value[0] == 3.5f);
    CHECK(probe2.find("n_{i-1}", "history").value[0] == 4.0f);
  }
}

TEST_CASE("no surface: everything 0, sizes are checked, any thread count gives the same bits") {
  const int w = 7, h = 5;
  SurfacePlanes s = flat_surface(w, h);
  s.mesh.at(2, 2) = kInvalidId;
  std::mt19937 rng(5);
  std::uniform_real_distribution<float> u(0.0f, 1.0f);
  RgbPlane noisy(w, h);
  for (auto& c : noisy.data) c = {u(rng), u(rng), u(rng)};
  TemporalHistory prev = uniform_history(s, glm::vec3(0.3f), 2.0f);
  for (auto& m : s.motion.data) m = {u(rng) - 0.5f, u(rng) - 0.5f};
  const TemporalOutput a = temporal_pass(noisy, s, prev, SvgfParams{});
  CHECK(a.color.at(2, 2) == glm::vec3(0.0f));
  CHECK(a.moment1.at(2, 2) == 0.0f);
  CHECK(a.moment2.at(2, 2) == 0.0f);
  CHECK(a.length.at(2, 2) == 0.0f);

  set_thread_count(1);
  const TemporalOutput b = temporal_pass(noisy, s, prev, SvgfParams{});
  set_thread_count(0);
  CHECK(a.color.data == b.color.data);
  CHECK(a.moment2.data == b.moment2.data);

  prev.length = FloatPlane(w + 1, h);
  CHECK_THROWS_AS(temporal_pass(noisy, s, prev, SvgfParams{}), Error);
  CHECK_THROWS_AS(temporal_pass(RgbPlane(w, h + 1), s, TemporalHistory{}, SvgfParams{}), Error);
}
