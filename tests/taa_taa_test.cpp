// Tests of filters/taa/taa.cpp: YCoCg by hand, the Halton(2,3) jitter, bilinear reprojection, the history
// clip and clamp by hand, the blend weight, jitter compensation, and fixed points (constant and static images).
#include "filters/taa/taa.h"

#include "core/error.h"

#include <catch2/catch.hpp>

#include <random>

using Catch::Detail::Approx;
using namespace rtdr;

namespace {

void check_close(const glm::vec3& a, const glm::vec3& b, double margin = 1e-6) {
  for (int i = 0; i < 3; ++i) CHECK(a[i] == Approx(b[i]).margin(margin));
}
void check_close(const std::vector<float>& a, const glm::vec3& b) {
  REQUIRE(a.size() == 3);
  check_close(glm::vec3(a[0], a[1], a[2]), b);
}

RgbPlane random_image(int w, int h, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> u(0.0f, 1.0f);
  RgbPlane p(w, h);
  for (glm::vec3& c : p.data) c = glm::vec3(u(rng), u(rng), u(rng));
  return p;
}

// A grey ramp v = 0.1 x + 0.01 y: bilinear interpolation of a linear function is exact.
RgbPlane grey_ramp(int w, int h) {
  RgbPlane p(w, h);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) p.at(x, y) = glm::vec3(0.1f * float(x) + 0.01f * float(y));
  return p;
}

// A 3x3 image whose YCoCg box is [0.4, 0.6] x [-0.1, 0.1] x [-0.1, 0.1] with mean (0.5, 0, 0): four pairs of
// colours symmetric about the centre (0.5, 0.5, 0.5). Each RGB value below is the YCoCg point in the comment.
RgbPlane known_box_image() {
  RgbPlane p(3, 3);
  p.at(0, 0) = {0.4f, 0.3f, 0.6f};    // (0.4, -0.1, -0.1)
  p.at(1, 0) = {0.6f, 0.7f, 0.4f};    // (0.6,  0.1,  0.1)
  p.at(2, 0) = {0.6f, 0.3f, 0.4f};    // (0.4,  0.1, -0.1)
  p.at(0, 1) = {0.4f, 0.7f, 0.6f};    // (0.6, -0.1,  0.1)
  p.at(1, 1) = {0.5f, 0.5f, 0.5f};    // (0.5,  0,    0)
  p.at(2, 1) = {0.5f, 0.45f, 0.4f};   // (0.45, 0.05, 0)
  p.at(0, 2) = {0.5f, 0.55f, 0.6f};   // (0.55,-0.05, 0)
  p.at(1, 2) = {0.45f, 0.55f, 0.45f}; // (0.5,  0,    0.05)
  p.at(2, 2) = {0.55f, 0.45f, 0.55f}; // (0.5,  0,   -0.05)
  return p;
}

}  // namespace

TEST_CASE("YCoCg of a few colours by hand, and the round trip") {
  check_close(rgb_to_ycocg({1.0f, 1.0f, 1.0f}), {1.0f, 0.0f, 0.0f});      // white: all luma, no chroma
  check_close(rgb_to_ycocg({1.0f, 0.0f, 0.0f}), {0.25f, 0.5f, -0.25f});   // red
  check_close(rgb_to_ycocg({0.0f, 1.0f, 0.0f}), {0.5f, 0.0f, 0.5f});      // green
  check_close(rgb_to_ycocg({0.0f, 0.0f, 1.0f}), {0.25f, -0.5f, -0.25f});  // blue
  check_close(rgb_to_ycocg({0.2f, 0.4f, 0.8f}), {0.45f, -0.3f, -0.05f});  // 0.05 + 0.2 + 0.2, 0.1 - 0.4, ...
  check_close(ycocg_to_rgb({0.25f, 0.5f, -0.25f}), {1.0f, 0.0f, 0.0f});
  const RgbPlane colours = random_image(64, 64, 3);
  for (const glm::vec3& c : colours.data) check_close(ycocg_to_rgb(rgb_to_ycocg(4.0f * c - 1.0f)), 4.0f * c - 1.0f);
}

TEST_CASE("Halton radical inverse and the jitter sequence by hand") {
  CHECK(halton(1, 2) == 0.5f);
  CHECK(halton(2, 2) == 0.25f);
  CHECK(halton(3, 2) == 0.75f);
  CHECK(halton(6, 2) == 0.375f);  // 110 -> 0.011
  CHECK(halton(1, 3) == Approx(1.0 / 3.0).margin(1e-7));
  CHECK(halton(2, 3) == Approx(2.0 / 3.0).margin(1e-7));
  CHECK(halton(3, 3) == Approx(1.0 / 9.0).margin(1e-7));   // 10 -> 0.01
  CHECK(halton(5, 3) == Approx(7.0 / 9.0).margin(1e-7));   // 12 -> 0.21
  // taa_jitter(f) = (halton(f + 1, 2), halton(f + 1, 3)) - 0.5.
  const glm::vec2 expected[8] = {{0.0f, -1.0f / 6.0f},     {-0.25f, 1.0f / 6.0f},       {0.25f, -7.0f / 18.0f},
                                 {-0.375f, -1.0f / 18.0f}, {0.125f, 5.0f / 18.0f},      {-0.125f, -5.0f / 18.0f},
                                 {0.375f, 1.0f / 18.0f},   {-7.0f / 16.0f, 7.0f / 18.0f}};
  for (int f = 0; f < 8; ++f) {
    CHECK(taa_jitter(f).x == Approx(expected[f].x).margin(1e-6));
    CHECK(taa_jitter(f).y == Approx(expected[f].y).margin(1e-6));
  }
}

TEST_CASE("the jitter repeats with its period, stays in [-0.5, 0.5)^2 and averages to about 0") {
  for (int f = -20; f < 40; ++f) CHECK(taa_jitter(f) == taa_jitter(f + 8));
  CHECK(taa_jitter(-1) == taa_jitter(7));
  CHECK(taa_jitter(5, 4) == taa_jitter(1, 4));
  CHECK(taa_jitter(100, 1) == taa_jitter(0, 1));
  for (int period : {1, 2, 8, 16, 37, 64}) {
    glm::dvec2 sum(0.0);
    for (int f = 0; f < period; ++f) {
      const glm::vec2 j = taa_jitter(f, period);
      CHECK(j.x >= -0.5f);
      CHECK(j.x < 0.5f);
      CHECK(j.y >= -0.5f);
      CHECK(j.y < 0.5f);
      sum += glm::dvec2(j);
    }
    if (period >= 8) {
      CHECK(std::abs(sum.x / period) < 1.0 / period);
      CHECK(std::abs(sum.y / period) < 1.0 / period);
    }
  }
  // Period 8 by hand: x takes 1/2, 1/4, 3/4, 1/8, 5/8, 3/8, 7/8, 1/16 (sum 57/16), y the ninths 1..8 but 6.
  glm::dvec2 sum(0.0);
  for (int f = 0; f < 8; ++f) sum += glm::dvec2(taa_jitter(f));
  CHECK(sum.x / 8.0 == Approx(57.0 / 128.0 - 0.5).margin(1e-6));  // -7/128
  CHECK(sum.y / 8.0 == Approx(0.0).margin(1e-6));
}

TEST_CASE("history position: pixel centre + motion - (previous jitter - current jitter)") {
  const TaaJitter jitter{{0.25f, -0.125f}, {-0.125f, 0.375f}};
  // m0 = (1, -2) - (-0.375, 0.5) = (1.375, -2.5); centre (3.5, 2.5).
  const glm::vec2 q = taa_history_position(3, 2, {1.0f, -2.0f}, jitter);
  CHECK(q.x == 4.875f);
  CHECK(q.y == 0.0f);
  CHECK(taa_history_position(3, 2, {1.0f, -2.0f}, TaaJitter{}) == glm::vec2(4.5f, 0.5f));
}

TEST_CASE("bilinear history fetch by hand, edges clamped") {
  RgbPlane h(2, 2);
  h.at(0, 0) = glm::vec3(0.0f);
  h.at(1, 0) = glm::vec3(1.0f);
  h.at(0, 1) = glm::vec3(2.0f);
  h.at(1, 1) = glm::vec3(4.0f);
  check_close(sample_bilinear(h, {0.5f, 0.5f}), glm::vec3(0.0f));  // a pixel centre reads that pixel
  check_close(sample_bilinear(h, {1.5f, 1.5f}), glm::vec3(4.0f));
  // (1.25, 0.75): fractions (0.75, 0.25): 0.75*0.75*1 + 0.25*0.25*2 + 0.75*0.25*4 = 1.4375.
  check_close(sample_bilinear(h, {1.25f, 0.75f}), glm::vec3(1.4375f));
  check_close(sample_bilinear(h, {0.2f, 0.5f}), glm::vec3(0.0f));  // left of the first centre: edge repeats
  check_close(sample_bilinear(h, {1.9f, 0.5f}), glm::vec3(1.0f));
}

TEST_CASE("a ramp reprojected with fractional motion reads the bilinear value") {
  const RgbPlane ramp = grey_ramp(8, 6);
  Vec2Plane motion(8, 6, glm::vec2(0.3f, -0.6f));
  // Pixel (3, 2): history at (3.8, 1.9), i.e. index position (3.3, 1.4): 0.1 * 3.3 + 0.01 * 1.4 = 0.344.
  check_close(sample_bilinear(ramp, taa_history_position(3, 2, motion.at(3, 2), {})), glm::vec3(0.344f));
  // 0.344 lies in the 3x3 box [0.21, 0.43], so the output is 0.1 * 0.32 + 0.9 * 0.344 = 0.3416.
  Probe probe;
  const glm::vec3 out = taa_pixel(ramp, ramp, motion, 3, 2, TaaParams{}, {}, &probe);
  CHECK(probe.find("bilinear top-left tap (x0, y0)").value == std::vector<float>{3.0f, 1.0f});
  CHECK(probe.find("bilinear fractions (fx, fy)").value[0] == Approx(0.3f).margin(1e-6));
  CHECK(probe.find("bilinear fractions (fx, fy)").value[1] == Approx(0.4f).margin(1e-6));
  check_close(probe.find("history RGB (bilinear)").value, glm::vec3(0.344f));
  check_close(out, glm::vec3(0.3416f));
}

TEST_CASE("a constant image stays constant, whatever the motion and jitter") {
  const glm::vec3 grey(0.3f, 0.6f, 0.2f);
  const RgbPlane image(16, 12, grey);
  std::mt19937 rng(11);
  std::uniform_real_distribution<float> u(-2.5f, 2.5f);
  Vec2Plane motion(16, 12);
  for (glm::vec2& m : motion.data) m = glm::vec2(u(rng), u(rng));
  for (const int clip : {0, 1}) {
    TaaParams params;
    params.clip_history = clip;
    const RgbPlane out = taa_pass(image, image, motion, params, {taa_jitter(3), taa_jitter(2)});
    for (const glm::vec3& c : out.data) check_close(c, grey);
  }
}

TEST_CASE("a static scene with history = current gives the input back") {
  const RgbPlane image = random_image(16, 12, 5);
  const RgbPlane out = taa_pass(image, image, Vec2Plane(16, 12), TaaParams{});
  for (size_t i = 0; i < image.data.size(); ++i) check_close(out.data[i], image.data[i]);
}

TEST_CASE("jitter compensation: a static scene rendered with jitter reads the history at the pixel centre") {
  // For a static scene and camera the renderer's motion is j_prev - j_cur (raster/backproject.h).
  const TaaJitter jitter{taa_jitter(5), taa_jitter(4)};
  const RgbPlane image = grey_ramp(8, 6);
  const Vec2Plane motion(8, 6, jitter.previous - jitter.current);
  const RgbPlane out = taa_pass(image, image, motion, TaaParams{}, jitter);
  for (size_t i = 0; i < image.data.size(); ++i) check_close(out.data[i], image.data[i]);
  // Without the jitters the history is resampled at a sub-pixel offset: the ramp shifts.
  // j_prev - j_cur = (0.125, 5/18) - (-0.125, -5/18) = (0.25, 5/9); pixel (3, 2) reads 0.1 * 3.25 + 0.01 * 2.5556.
  const glm::vec3 shifted = taa_pixel(image, image, motion, 3, 2, TaaParams{});
  check_close(shifted, glm::vec3(0.1f * 0.32f + 0.9f * (0.325f + 0.01f * (2.0f + 5.0f / 9.0f))));
}

TEST_CASE("a history far outside the box is clipped towards the mean onto the box (by hand)") {
  const RgbPlane current = known_box_image();
  const RgbPlane red(3, 3, glm::vec3(1.0f, 0.0f, 0.0f));
  Probe probe;
  const glm::vec3 out = taa_pixel(current, red, Vec2Plane(3, 3), 1, 1, TaaParams{}, {}, &probe);
  check_close(probe.find("box min (YCoCg)").value, {0.4f, -0.1f, -0.1f});
  check_close(probe.find("box max (YCoCg)").value, {0.6f, 0.1f, 0.1f});
  check_close(probe.find("box mean (YCoCg)").value, {0.5f, 0.0f, 0.0f});
  check_close(probe.find("history (YCoCg)").value, {0.25f, 0.5f, -0.25f});
  // From the mean, history - mean = (-0.25, 0.5, -0.25). The faces it crosses: Y = 0.4 at t = 0.4, Co = 0.1 at
  // t = 0.2, Cg = -0.1 at t = 0.4. The first is Co at t = 0.2: (0.5, 0, 0) + 0.2 (-0.25, 0.5, -0.25).
  CHECK(probe.find("clip t (1: inside the box)").value[0] == Approx(0.2f).margin(1e-6));
  check_close(probe.find("history clipped (YCoCg)").value, {0.45f, 0.1f, -0.05f});
  // Blend 0.1 (0.5, 0, 0) + 0.9 (0.45, 0.1, -0.05) = (0.455, 0.09, -0.045) -> RGB (0.59, 0.41, 0.41).
  check_close(probe.find("blend alpha c + (1 - alpha) h (YCoCg)").value, {0.455f, 0.09f, -0.045f});
  check_close(out, {0.59f, 0.41f, 0.41f});
  // The same by the helper directly.
  check_close(clip_towards_mean({0.25f, 0.5f, -0.25f}, {0.5f, 0.0f, 0.0f}, {0.4f, -0.1f, -0.1f}, {0.6f, 0.1f, 0.1f}),
              {0.45f, 0.1f, -0.05f});
}

TEST_CASE("with clipping off the history is clamped per component (by hand)") {
  TaaParams params;
  params.clip_history = 0;
  Probe probe;
  const RgbPlane red(3, 3, glm::vec3(1.0f, 0.0f, 0.0f));
  const glm::vec3 out = taa_pixel(known_box_image(), red, Vec2Plane(3, 3), 1, 1, params, {}, &probe);
  // clamp((0.25, 0.5, -0.25)) = (0.4, 0.1, -0.1); blend (0.41, 0.09, -0.09) -> RGB (0.59, 0.32, 0.41).
  check_close(probe.find("history clamped (YCoCg)").value, {0.4f, 0.1f, -0.1f});
  check_close(out, {0.59f, 0.32f, 0.41f});
}

TEST_CASE("with the history inside the box the output is alpha * current + (1 - alpha) * history") {
  const RgbPlane current = known_box_image();
  const glm::vec3 c = current.at(1, 1), h(0.52f, 0.5f, 0.48f);  // h in YCoCg: (0.5, 0.02, 0), inside
  for (const float alpha : {0.0f, 0.1f, 0.25f, 0.5f, 1.0f}) {
    TaaParams params;
    params.alpha = alpha;
    const glm::vec3 out = taa_pixel(current, RgbPlane(3, 3, h), Vec2Plane(3, 3), 1, 1, params);
    check_close(out, alpha * c + (1.0f - alpha) * h);
  }
  check_close(taa_pixel(current, RgbPlane(3, 3, h), Vec2Plane(3, 3), 1, 1, TaaParams{}), {0.518f, 0.5f, 0.482f});
}

TEST_CASE("missing or off-screen history: the output is the current colour") {
  const RgbPlane image = random_image(6, 5, 9);
  const RgbPlane history(6, 5, glm::vec3(0.5f));
  Probe probe;
  CHECK(taa_pixel(image, history, Vec2Plane(6, 5, glm::vec2(-0.6f, 0.0f)), 0, 2, TaaParams{}, {}, &probe) ==
        image.at(0, 2));  // history at x = -0.1: off screen
  CHECK(probe.find("history on screen").value[0] == 0.0f);
  // kMotionBehindCamera (raster/backproject.h) puts the history 1e6 pixels away.
  CHECK(taa_pixel(image, history, Vec2Plane(6, 5, glm::vec2(1e6f)), 3, 3, TaaParams{}) == image.at(3, 3));
  const RgbPlane first_frame = taa_pass(image, RgbPlane{}, Vec2Plane(6, 5), TaaParams{});
  CHECK(first_frame.data == image.data);
}

TEST_CASE("taa_pass is taa_pixel at every pixel; sizes and parameters are checked") {
  const RgbPlane current = random_image(9, 7, 21), history = random_image(9, 7, 22);
  Vec2Plane motion(9, 7);
  std::mt19937 rng(23);
  std::uniform_real_distribution<float> u(-1.5f, 1.5f);
  for (glm::vec2& m : motion.data) m = glm::vec2(u(rng), u(rng));
  const TaaJitter jitter{taa_jitter(1), taa_jitter(0)};
  const RgbPlane out = taa_pass(current, history, motion, TaaParams{}, jitter);
  for (int y = 0; y < 7; ++y)
    for (int x = 0; x < 9; ++x) CHECK(out.at(x, y) == taa_pixel(current, history, motion, x, y, TaaParams{}, jitter));
  CHECK_THROWS_AS(taa_pass(current, RgbPlane(7, 9), motion, TaaParams{}), Error);
  CHECK_THROWS_AS(taa_pass(current, history, Vec2Plane(9, 6), TaaParams{}), Error);
  TaaParams bad;
  bad.alpha = 1.5f;
  CHECK_THROWS_AS(taa_pass(current, history, motion, bad), Error);
  CHECK(taa_param_table().size() == 3);
}
