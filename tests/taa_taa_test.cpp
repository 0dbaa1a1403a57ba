// Tests of filters/taa/taa.cpp: YCoCg by hand, the Halton(2,3) jitter, bilinear reprojection, the history
// clip (onto the padded box) and clamp by hand, the clip's continuity where the box is flat and its Lipschitz
// bound, the blend weight, jitter compensation, and fixed points (constant and static images).
#include "filters/taa/taa.h"

#include "core/error.h"
#include "filters/taa/taa_shared.h"

#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
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

// The clip's bounds below are derived for the padding e = 1/1024 of taa_shared.h. Beyond a face F of channel i,
// t = (F - mean_i) / d_i with d_i = h_i - mean_i >= F - mean_i >= e, so |dt/dh_i| = t / d_i <= 1 / e, and the
// output mean + t (h - mean) moves by at most |dh| (1 + |h - mean| / e) when the history moves by dh. The tests
// write e as this design value, not as kTaaClipPadding, so that an unpadded clip (e = 0, Karis14's bare box) fails
// them instead of making their bounds infinite.
constexpr float kPadding = 1.0f / 1024.0f;
// Each evaluation of the clip rounds face - mean, d, their quotient, h - mean, the product and the sum: within
// 5e-7 of the exact clip for |h - mean| <= 1.5, so two evaluations may differ by 1e-6 more than the exact ones.
constexpr double kClipRounding = 1e-6;

double max_abs_diff(const glm::vec3& a, const glm::vec3& b) {
  double d = 0.0;
  for (int i = 0; i < 3; ++i) d = std::max(d, std::abs(double(a[i]) - double(b[i])));
  return d;
}

// The Lipschitz bound of the padded clip between histories h1 and h2 (same mean and box): |h2 - h1| (1 + r / e),
// r the largest |h - mean| of either; 1e-3 relative more because the face box + e rounds (e is off by < 1e-4 of
// itself, an ulp of the box).
double clip_bound(const glm::vec3& h1, const glm::vec3& h2, const glm::vec3& mean) {
  double r = 0.0;
  for (int i = 0; i < 3; ++i)
    r = std::max({r, std::abs(double(h1[i]) - double(mean[i])), std::abs(double(h2[i]) - double(mean[i]))});
  return max_abs_diff(h1, h2) * (1.0 + r / kPadding) * (1.0 + 1e-3) + kClipRounding;
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

TEST_CASE("the jitter repeats with its period, stays in -0.5 <= x, y < 0.5 and averages to about 0") {
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
  // For a static scene and camera the renderer's motion is j_prev - j_cur (motion/backproject.h).
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

TEST_CASE("a history far outside the box is clipped towards the mean onto the padded box (by hand)") {
  const RgbPlane current = known_box_image();
  const RgbPlane red(3, 3, glm::vec3(1.0f, 0.0f, 0.0f));
  Probe probe;
  const glm::vec3 out = taa_pixel(current, red, Vec2Plane(3, 3), 1, 1, TaaParams{}, {}, &probe);
  check_close(probe.find("box min (YCoCg)").value, {0.4f, -0.1f, -0.1f});
  check_close(probe.find("box max (YCoCg)").value, {0.6f, 0.1f, 0.1f});
  check_close(probe.find("box mean (YCoCg)").value, {0.5f, 0.0f, 0.0f});
  check_close(probe.find("history (YCoCg)").value, {0.25f, 0.5f, -0.25f});
  // The clip box is padded by e = 1/1024 (taa_shared.h): [0.4 - e, 0.6 + e] x [-0.1 - e, 0.1 + e]^2. From the
  // mean, history - mean = (-0.25, 0.5, -0.25). The faces it crosses: Y = 0.4 - e at t = (0.1 + e) / 0.25 =
  // 0.4 + 4e, Co = 0.1 + e at t = 0.2 + 2e, Cg = -0.1 - e at t = 0.4 + 4e. The first is Co at t = 0.2 + 2e =
  // 0.201953125: (0.5, 0, 0) + t (-0.25, 0.5, -0.25) = (0.45 - e/2, 0.1 + e, -0.05 - e/2).
  const float e = kTaaClipPadding;
  CHECK(e == 1.0f / 1024.0f);
  CHECK(probe.find("clip t (1: inside the padded box)").value[0] == Approx(0.201953125).margin(1e-6));
  check_close(probe.find("history clipped (YCoCg)").value, {0.44951171875f, 0.1009765625f, -0.05048828125f});
  check_close(probe.find("history clipped (YCoCg)").value, {0.45f - e / 2.0f, 0.1f + e, -0.05f - e / 2.0f});
  // Blend 0.1 (0.5, 0, 0) + 0.9 clipped = (0.455 - 0.45e, 0.09 + 0.9e, -0.045 - 0.45e); to RGB with
  // R = Y + Co - Cg, G = Y + Cg, B = Y - Co - Cg: (0.59 + 0.9e, 0.41 - 0.9e, 0.41 - 0.9e).
  check_close(probe.find("blend alpha c + (1 - alpha) h (YCoCg)").value,
              {0.455f - 0.45f * e, 0.09f + 0.9f * e, -0.045f - 0.45f * e});
  check_close(out, {0.59087890625f, 0.40912109375f, 0.40912109375f});
  // The same by the helper directly.
  check_close(clip_towards_mean({0.25f, 0.5f, -0.25f}, {0.5f, 0.0f, 0.0f}, {0.4f, -0.1f, -0.1f}, {0.6f, 0.1f, 0.1f}),
              {0.45f - e / 2.0f, 0.1f + e, -0.05f - e / 2.0f});
  // A history inside the padding (a quarter of e beyond the bare face) is kept as it is.
  const glm::vec3 in_padding(0.5f, 0.1f + e / 4.0f, 0.0f);
  CHECK(clip_towards_mean(in_padding, {0.5f, 0.0f, 0.0f}, {0.4f, -0.1f, -0.1f}, {0.6f, 0.1f, 0.1f}) == in_padding);
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

TEST_CASE("where the box is flat the clip is continuous: a history on the padded face and an ulp beyond it") {
  CHECK(kTaaClipPadding == kPadding);
  // A grey neighbourhood: luma from 0.2 to 0.8 around the mean 0.5, no chroma, so the box is flat in Co and Cg.
  const glm::vec3 mean(0.5f, 0.0f, 0.0f), box_min(0.2f, 0.0f, 0.0f), box_max(0.8f, 0.0f, 0.0f);
  for (int i = 1; i < 3; ++i) {                 // Co, Cg
    for (const float side : {1.0f, -1.0f}) {    // the upper face, the lower face
      // The face as clip_towards_mean computes it, and the next float beyond it.
      const float face = side > 0.0f ? box_max[i] + kTaaClipPadding : box_min[i] - kTaaClipPadding;
      glm::vec3 on(0.7f, 0.0f, 0.0f), beyond = on;
      on[i] = face;
      beyond[i] = std::nextafter(face, side * INFINITY);
      INFO("YCoCg channel " << i << ", face at " << face);
      // On the face the history is inside and kept (t = 1); an ulp beyond it t = (face - mean) / d is just
      // below 1. Karis14's bare box (e = 0) sent the second to the mean, 0.2 away in luma: the jump padding removes.
      const glm::vec3 kept = clip_towards_mean(on, mean, box_min, box_max);
      CHECK(kept == on);
      const glm::vec3 clipped = clip_towards_mean(beyond, mean, box_min, box_max);
      CHECK(max_abs_diff(kept, clipped) <= clip_bound(on, beyond, mean));
    }
  }
}

TEST_CASE("over a grey neighbourhood a grey history an ulp off grey is blended, not replaced by the mean") {
  // Luma 0.2 to 0.8, mean 0.5; the YCoCg of a grey is exactly (g, 0, 0), so the box is flat at Co = Cg = 0.
  RgbPlane current(3, 3);
  for (int i = 0; i < 9; ++i) current.data[i] = glm::vec3(0.2f + 0.075f * float(i));
  const glm::vec3 grey(0.7f);
  const glm::vec3 reference = taa_pixel(current, RgbPlane(3, 3, grey), Vec2Plane(3, 3), 1, 1, TaaParams{});
  check_close(reference, glm::vec3(0.1f * 0.5f + 0.9f * 0.7f));  // inside the box: the plain blend
  // A history an ulp of 0.7 (2^-24) off in one channel, as a GPU's tone map leaves it: its YCoCg moves by about
  // an ulp (the change and the conversion's roundings), the clip multiplies that by at most 1 + |h - mean| / e
  // (|h - mean| <= 0.2 here), the blend by 0.9, and the RGB output sums three components: within 4 ulps
  // (1 + 1/e). The bare box (e = 0) put this history at the mean: the output fell by 0.9 * 0.2 = 0.18.
  const double bound = 4.0 * std::ldexp(1.0, -24) * (1.0 + 1.0 / kPadding);
  for (int c = 0; c < 3; ++c) {
    for (const float side : {1.0f, -1.0f}) {
      glm::vec3 h = grey;
      h[c] = std::nextafter(h[c], side * INFINITY);
      INFO("RGB channel " << c << " moved by " << side << " ulp");
      const glm::vec3 out = taa_pixel(current, RgbPlane(3, 3, h), Vec2Plane(3, 3), 1, 1, TaaParams{});
      CHECK(max_abs_diff(out, reference) <= bound);
    }
  }
}

TEST_CASE("the clip is Lipschitz in the history: |out(h + delta) - out(h)| <= |delta| (1 + max|h - mean| / e)") {
  // Random boxes, a third of their channels flat, and histories half of whose channels lie within s of a padded
  // face, moved by up to s per channel, s from 1e-7 to 1e-4: many cross a face, where Karis14's bare box jumps.
  std::mt19937 rng(31);
  std::uniform_real_distribution<float> unit(0.0f, 1.0f), sym(-1.0f, 1.0f);
  int crossings = 0, violations = 0;
  double worst = 0.0;  // the largest |out(h + delta) - out(h)| / bound
  for (int trial = 0; trial < 200000; ++trial) {
    glm::vec3 mean, box_min, box_max, h, moved;
    const float scale = std::pow(10.0f, -7.0f + 3.0f * unit(rng));
    for (int i = 0; i < 3; ++i) {
      mean[i] = i == 0 ? unit(rng) : 0.5f * sym(rng);  // Y in [0, 1], Co and Cg in [-0.5, 0.5]
      const bool flat = unit(rng) < 1.0f / 3.0f;
      box_min[i] = flat ? mean[i] : mean[i] - 0.3f * unit(rng);
      box_max[i] = flat ? mean[i] : mean[i] + 0.3f * unit(rng);
      const float face = unit(rng) < 0.5f ? box_max[i] + kTaaClipPadding : box_min[i] - kTaaClipPadding;
      h[i] = unit(rng) < 0.5f ? face + scale * sym(rng) : mean[i] + 0.6f * sym(rng);
      moved[i] = h[i] + scale * sym(rng);
      if ((h[i] > face) != (moved[i] > face)) ++crossings;
    }
    const double diff = max_abs_diff(clip_towards_mean(h, mean, box_min, box_max),
                                     clip_towards_mean(moved, mean, box_min, box_max));
    const double bound = clip_bound(h, moved, mean);
    if (!(diff <= bound)) ++violations;
    worst = std::max(worst, diff / bound);
  }
  INFO(crossings << " face crossings; the largest difference is " << worst << " of its bound");
  CHECK(crossings > 50000);  // the test does exercise the faces
  CHECK(violations == 0);
  WARN("clip Lipschitz test: " << crossings << " face crossings, largest difference " << worst << " of its bound");
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
  // kMotionBehindCamera (motion/backproject.h) puts the history 1e6 pixels away.
  CHECK(taa_pixel(image, history, Vec2Plane(6, 5, glm::vec2(1e6f)), 3, 3, TaaParams{}) == image.at(3, 3));
  const RgbPlane first_frame = taa_pass(image, RgbPlane{}, Vec2Plane(6, 5), TaaParams{});
  CHECK(first_frame.data == image.data);
}

TEST_CASE("taa_pass is taa_pixel at every pixel, and checks sizes and parameters") {
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
