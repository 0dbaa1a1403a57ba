// Tests of eval/metrics.cpp: RMSE (whole and over a region), relMSE, brightness, umbrae, temporal error and lag
// by hand; SSIM exact on identical and constant images and against scikit-image on stored pairs
// (tests/data/ssim/, eval/make_ssim_fixtures.py); FLIP on closed forms (uniform images, where only the colour
// pipeline acts) and properties.
#include "eval/metrics.h"

#include "core/error.h"

#include <catch2/catch.hpp>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <limits>
#include <string>

using Catch::Detail::Approx;
using namespace rtdr;

namespace {

RgbPlane image(int w, int h, const std::vector<glm::vec3>& pixels) {
  RgbPlane p(w, h);
  p.data = pixels;
  return p;
}

// A deterministic pseudo-random image in [0, 1] (a 32-bit LCG, Numerical Recipes' constants).
RgbPlane random_image(int w, int h, uint32_t seed) {
  RgbPlane p(w, h);
  auto next = [&] { return float((seed = seed * 1664525u + 1013904223u) >> 8) / float(1 << 24); };
  for (glm::vec3& c : p.data) c = {next(), next(), next()};
  return p;
}

// A raw little-endian float32 RGB image as eval/make_ssim_fixtures.py writes it.
RgbPlane read_raw_rgb(const std::string& path, int w, int h) {
  std::ifstream in(path, std::ios::binary);
  REQUIRE(in.good());
  std::vector<float> values(size_t(w) * size_t(h) * 3);
  in.read(reinterpret_cast<char*>(values.data()), std::streamsize(values.size() * sizeof(float)));
  REQUIRE(in.gcount() == std::streamsize(values.size() * sizeof(float)));
  RgbPlane p(w, h);
  for (size_t i = 0; i < p.data.size(); ++i) p.data[i] = {values[3 * i], values[3 * i + 1], values[3 * i + 2]};
  return p;  // x86 and ARM are little-endian, like the files
}

}  // namespace

TEST_CASE("RMSE by hand: sqrt of the mean squared difference over pixels and channels") {
  const RgbPlane test = image(2, 1, {{1, 2, 3}, {0, 0, 0}});
  const RgbPlane reference = image(2, 1, {{1, 1, 1}, {0, 0, 2}});
  // Differences (0, 1, 2) and (0, 0, -2): squares 0 + 1 + 4 + 0 + 0 + 4 = 9 over 6 values; sqrt(1.5).
  CHECK(rmse(test, reference) == Approx(std::sqrt(1.5)).epsilon(1e-12));
  CHECK(rmse(test, test) == 0.0);
  CHECK_THROWS_AS(rmse(test, RgbPlane(1, 2)), Error);
}

TEST_CASE("brightness by hand: the image's error is |bias| of its mean luminance, a region's bias keeps its sign") {
  // Luminances: test 1, 0.5, 2; reference 1, 1, 1 (grey pixels: luminance = the grey value).
  const RgbPlane test = image(3, 1, {glm::vec3(1.0f), glm::vec3(0.5f), glm::vec3(2.0f)});
  const RgbPlane reference = image(3, 1, {glm::vec3(1.0f), glm::vec3(1.0f), glm::vec3(1.0f)});
  CHECK(brightness_error(test, reference) == Approx(0.5 / 3.0).epsilon(1e-12));  // |3.5 - 3| / 3
  CHECK(brightness_bias(test, reference, {1, 1, 1}) == Approx(0.5 / 3.0).epsilon(1e-12));
  // Too dark in one region, too bright in the other; together they nearly cancel.
  CHECK(brightness_bias(test, reference, {0, 1, 0}) == Approx(-0.5).epsilon(1e-12));
  CHECK(brightness_bias(test, reference, {0, 0, 1}) == Approx(1.0).epsilon(1e-12));
  CHECK(brightness_bias(test, reference, {0, 0, 0}) == 0.0);  // an empty region: no light to compare
  CHECK_THROWS_AS(brightness_bias(test, reference, {1, 1}), Error);
}

TEST_CASE("RMSE over a region by hand: only its pixels count, NaN for an empty region") {
  const RgbPlane test = image(2, 1, {{1, 2, 3}, {0, 0, 0}});
  const RgbPlane reference = image(2, 1, {{1, 1, 1}, {0, 0, 2}});
  CHECK(rmse(test, reference, {1, 0}) == Approx(std::sqrt(5.0 / 3.0)).epsilon(1e-12));  // (0 + 1 + 4) / 3
  CHECK(rmse(test, reference, {0, 1}) == Approx(std::sqrt(4.0 / 3.0)).epsilon(1e-12));
  CHECK(rmse(test, reference, {1, 1}) == Approx(rmse(test, reference)).epsilon(1e-12));
  CHECK(std::isnan(rmse(test, reference, {0, 0})));
  CHECK_THROWS_AS(rmse(test, reference, {1}), Error);
}

TEST_CASE("umbrae by hand: below a tenth of the pixel's most direct light, on surface points that stay put") {
  // Four pixels over three frames. Pixel 0: lit, then in shadow, then lit. Pixel 1: in a penumbra, never below a
  // tenth. Pixel 2: in shadow at frame 1, but it sees another point then (x moves by 0.1 at depth 2: 5 % of
  // it). Pixel 3: never lit.
  auto plane = [](std::vector<float> v) {
    FloatPlane p(4, 1);
    p.data = std::move(v);
    return p;
  };
  auto points = [](float x2) {
    RgbPlane p(4, 1);
    p.data = {{0, 0, 0}, {1, 0, 0}, {x2, 0, 0}, {3, 0, 0}};
    return p;
  };
  const std::vector<FloatPlane> direct = {plane({1.0f, 1.0f, 1.0f, 0.0f}), plane({0.05f, 0.5f, 0.0f, 0.0f}),
                                          plane({0.8f, 0.2f, 1.0f, 0.0f})};
  const FloatPlane depth = plane({2.0f, 2.0f, 2.0f, 2.0f});
  const std::vector<RgbPlane> position = {points(2.0f), points(2.1f), points(2.0f)};
  const std::vector<Region> umbrae = umbra_regions(direct, position, {depth, depth, depth});
  REQUIRE(umbrae.size() == 3);
  CHECK(umbrae[0] == Region{0, 0, 0, 0});
  CHECK(umbrae[1] == Region{1, 0, 0, 0});  // 0.05 < 0.1 x 1
  CHECK(umbrae[2] == Region{0, 0, 0, 0});
  // Within 1 % of the depth the point counts as the same (jitter): pixel 2 is in its umbra at frame 1.
  const std::vector<RgbPlane> jittered = {points(2.0f), points(2.015f), points(2.0f)};
  CHECK(umbra_regions(direct, jittered, {depth, depth, depth})[1] == Region{1, 0, 1, 0});
  // A pixel that sees no surface in some frame (depth 0) never counts: pixel 0 drops out.
  CHECK(umbra_regions(direct, jittered, {depth, plane({0.0f, 2.0f, 2.0f, 2.0f}), depth})[1] == Region{0, 0, 1, 0});
  CHECK_THROWS_AS(umbra_regions(direct, position, {depth}), Error);
}

TEST_CASE("relMSE by hand: mean of (x - y)^2 / (y^2 + eps), eps = 0.01") {
  const RgbPlane test = image(1, 1, {{2, 0, 1}});
  const RgbPlane reference = image(1, 1, {{1, 0, 0}});
  // R: 1 / (1 + 0.01); G: 0; B: 1 / (0 + 0.01) = 100. Mean of three: 33.66336...
  CHECK(kRelMseEpsilon == 0.01);
  CHECK(relmse(test, reference) == Approx((1.0 / 1.01 + 100.0) / 3.0).epsilon(1e-12));
  // With eps = 1: (1/2 + 0 + 1) / 3 = 0.5. The reference is the denominator: swapping changes the value.
  CHECK(relmse(test, reference, 1.0) == Approx(0.5).epsilon(1e-12));
  CHECK(relmse(reference, test, 1.0) == Approx((1.0 / 5.0 + 0.0 + 1.0 / 2.0) / 3.0).epsilon(1e-12));
  CHECK_THROWS_AS(relmse(test, reference, 0.0), Error);
}

TEST_CASE("SSIM of an image with itself is exactly 1") {
  const RgbPlane a = random_image(23, 17, 7);
  CHECK(ssim(a, a) == 1.0);
}

TEST_CASE("SSIM of constant images by hand: (2 c1 c2 + C1) / (c1^2 + c2^2 + C1) per channel, averaged") {
  // Zero variance everywhere, so the contrast-structure factor is C2 / C2 = 1 [Wang04 Eq. 13]. C1 = 0.01^2.
  const RgbPlane a(13, 12, glm::vec3(0.2f, 0.5f, 0.9f)), b(13, 12, glm::vec3(0.6f, 0.5f, 0.3f));
  const double C1 = 1e-4;
  auto s = [&](double c1, double c2) { return (2.0 * c1 * c2 + C1) / (c1 * c1 + c2 * c2 + C1); };
  // R: 0.2401 / 0.4001 = 0.60010; G: 1; B: 0.5401 / 0.9001 = 0.60004.
  const double expected = (s(0.2f, 0.6f) + s(0.5f, 0.5f) + s(0.9f, 0.3f)) / 3.0;
  CHECK(ssim(a, b) == Approx(expected).epsilon(1e-9));
  CHECK(expected == Approx((0.2401 / 0.4001 + 1.0 + 0.5401 / 0.9001) / 3.0).epsilon(1e-6));
  CHECK_THROWS_AS(ssim(RgbPlane(10, 20), RgbPlane(10, 20)), Error);  // narrower than the 11x11 window
}

TEST_CASE("SSIM matches scikit-image's structural_similarity on the stored pairs (within 1e-9)") {
  // Both sides compute in double from the same float32 pixels; they agree to ~1e-15.
  const std::string dir = std::string(RTDR_TEST_DATA_DIR) + "/ssim/";
  std::ifstream in(dir + "ssim.json");
  REQUIRE(in.good());
  const nlohmann::json fixture = nlohmann::json::parse(in);
  const int w = fixture.at("width"), h = fixture.at("height");
  REQUIRE(fixture.at("pairs").size() == 3);
  for (const nlohmann::json& pair : fixture.at("pairs")) {
    INFO(pair.at("test").get<std::string>() << " against " << pair.at("reference").get<std::string>());
    const RgbPlane test = read_raw_rgb(dir + pair.at("test").get<std::string>(), w, h);
    const RgbPlane reference = read_raw_rgb(dir + pair.at("reference").get<std::string>(), w, h);
    CHECK(ssim(test, reference) == Approx(pair.at("ssim").get<double>()).margin(1e-9));
  }
}

TEST_CASE("FLIP of identical images is exactly 0") {
  const RgbPlane a = random_image(24, 20, 3);
  const FlipResult r = flip(a, a);
  CHECK(r.mean == 0.0);
  for (float v : r.map.data) CHECK(v == 0.0f);
}

TEST_CASE("FLIP of uniform images is the colour term alone, by hand") {
  // On flat images the edge and point filters give 0 (their taps sum to 0), so FLIP = Delta E_c everywhere:
  // HyAB of the Hunt-adjusted L*a*b* colours, ^0.7, mapped with c_max = HyAB(green, blue)^0.7 = 203.3119^0.7
  // = 41.2776 (green: L* 87.737, Hunt a* -75.619, b* 72.985; blue: L* 32.303, a* 25.582, b* -34.840).
  // Black vs white: HyAB = 100 (L* 0 vs 100), 100^0.7 = 25.119 > 0.4 c_max = 16.511, so
  // 0.95 + (25.119 - 16.511) / (0.6 c_max) * 0.05 = 0.967378.
  const FlipResult bw = flip(RgbPlane(16, 16, glm::vec3(0.0f)), RgbPlane(16, 16, glm::vec3(1.0f)));
  CHECK(bw.mean == Approx(0.967378).margin(1e-4));
  CHECK(bw.map.at(0, 0) == Approx(0.967378).margin(1e-4));
  CHECK(bw.map.at(7, 9) == Approx(0.967378).margin(1e-4));
  // Greys 0.5 vs 0.6: HyAB = |dL*| = 5.76893, 5.76893^0.7 < 0.4 c_max, so 0.95 / (0.4 c_max) * 5.76893^0.7 = 0.196208.
  const RgbPlane grey5(16, 16, glm::vec3(0.5f)), grey6(16, 16, glm::vec3(0.6f));
  CHECK(flip(grey5, grey6).mean == Approx(0.196208).margin(1e-4));
  // A chromatic pair, (0.2, 0.4, 0.1) vs (0.25, 0.35, 0.1): HyAB = 9.34318, FLIP 0.274977.
  const RgbPlane olive(16, 16, {0.2f, 0.4f, 0.1f}), khaki(16, 16, {0.25f, 0.35f, 0.1f});
  CHECK(flip(olive, khaki).mean == Approx(0.274977).margin(1e-4));
  // Red vs green: HyAB = 158.479 is beyond 0.4 c_max, near the top of the range: 0.986664.
  CHECK(flip(RgbPlane(16, 16, {1, 0, 0}), RgbPlane(16, 16, {0, 1, 0})).mean == Approx(0.986664).margin(1e-4));
}

TEST_CASE("FLIP lies in [0, 1], is symmetric, and clamps its inputs to [0, 1]") {
  const RgbPlane a = random_image(24, 20, 11), b = random_image(24, 20, 12);
  const FlipResult ab = flip(a, b), ba = flip(b, a);
  CHECK(ab.mean > 0.0);
  CHECK(ab.mean <= 1.0);
  for (float v : ab.map.data) {
    CHECK(v >= 0.0f);
    CHECK(v <= 1.0f);
  }
  CHECK(ab.mean == Approx(ba.mean).epsilon(1e-6));
  // HDR values above 1 are clipped like a display would: 5.0 looks the same as 1.0.
  CHECK(flip(RgbPlane(16, 16, glm::vec3(5.0f)), RgbPlane(16, 16, glm::vec3(1.0f))).mean == 0.0);
  CHECK_THROWS_AS(flip(a, RgbPlane(20, 24)), Error);
  CHECK_THROWS_AS(flip(a, b, 0.0), Error);
}

TEST_CASE("FLIP: one bright pixel gives a positive local error that decays with distance") {
  const int n = 41, c = 20;
  const RgbPlane reference(n, n, glm::vec3(0.2f));
  RgbPlane test = reference;
  test.at(c, c) = glm::vec3(1.0f);
  const FlipResult r = flip(test, reference);
  // Largest at the pixel, falling off along a row and along the diagonal.
  float largest = 0.0f;
  for (float v : r.map.data) largest = std::max(largest, v);
  CHECK(r.map.at(c, c) == largest);
  CHECK(r.map.at(c, c) > 0.3f);  // 0.392 here
  for (int d = 1; d <= 4; ++d) {
    CHECK(r.map.at(c + d, c) < r.map.at(c + d - 1, c));
    CHECK(r.map.at(c - d, c) == Approx(r.map.at(c + d, c)).margin(1e-6));  // symmetric about the pixel
  }
  CHECK(r.map.at(c + 2, c + 2) < r.map.at(c + 1, c + 1));
  // Beyond both filters' reach (CSF radius 10, feature radius 9 at 67 PPD) nothing differs: exactly 0.
  CHECK(r.map.at(c + 11, c) == 0.0f);
  CHECK(r.map.at(0, 0) == 0.0f);
  CHECK(r.mean > 0.0);
  CHECK(r.mean < 0.05);  // a local error in a large image
}

TEST_CASE("FLIP: a one-pixel checkerboard against its mean grey is less visible from further away") {
  // The CSFs are low-pass in degrees: more pixels per degree, the finer the pattern, the smaller its error.
  // Measured at the centre of a 64 x 64 image, further from the border than the largest kernel radius used
  // (17 pixels at 120 PPD), so the clamped borders play no part.
  const int n = 64, c = 32;
  RgbPlane checker(n, n), grey(n, n, glm::vec3(0.5f));
  for (int y = 0; y < n; ++y)
    for (int x = 0; x < n; ++x) checker.at(x, y) = glm::vec3((x + y) % 2 ? 0.3f : 0.7f);
  const float near = flip(checker, grey, 20.0).map.at(c, c);  // 0.345
  const float standard = flip(checker, grey).map.at(c, c);    // 0.00055
  const float far = flip(checker, grey, 120.0).map.at(c, c);  // 0.00003
  CHECK(near > 10.0f * standard);
  CHECK(standard > far);
  CHECK(far >= 0.0f);
}

TEST_CASE("temporal error by hand: mean luminance of |a - b|, not |luminance(a) - luminance(b)|") {
  const RgbPlane a = image(2, 1, {{1, 0, 0}, {0.5f, 0.5f, 0.5f}});
  const RgbPlane b = image(2, 1, {{0, 1, 0}, {0.5f, 0.5f, 0.5f}});
  // Pixel 0: |a - b| = (1, 1, 0), luminance 0.2126 + 0.7152 = 0.9278 (|L(a) - L(b)| would be only 0.5026);
  // pixel 1: unchanged. Mean 0.4639.
  CHECK(temporal_error(a, b) == Approx(0.4639).epsilon(1e-6));
  CHECK(temporal_error(b, a) == Approx(0.4639).epsilon(1e-6));
  CHECK(temporal_error(a, a) == 0.0);
  // A uniform brightening by 0.1 in every channel: luminance 0.1 (the weights sum to 1).
  CHECK(temporal_error(RgbPlane(3, 3, glm::vec3(0.3f)), RgbPlane(3, 3, glm::vec3(0.4f))) == Approx(0.1).epsilon(1e-5));
}

TEST_CASE("lag by hand: frames after the change until the error is back at or below the threshold") {
  //                                 0  1  2  3  4  5  6     7
  const std::vector<double> error = {1, 1, 1, 5, 4, 3, 1.05, 1};
  CHECK(lag_frames(error, 3, 1.1) == 3);            // frame 6 is the first at or below 1.1
  CHECK(lag_frames_relative(error, 3, 0.1) == 3);   // pre-change mean 1, threshold 1.1
  CHECK(lag_frames_relative(error, 3, 0.0) == 4);   // threshold 1: frame 7
  CHECK(lag_frames(error, 3, 5.0) == 0);            // the change frame is already at the threshold: no lag
  CHECK(lag_frames(error, 3, 0.5) == -1);           // never recovers within the series
  CHECK(lag_frames_relative({1, 1, 5, 5}, 2, 0.5) == -1);
  // NaN (the temporal error of a first frame) is skipped in the pre-change mean and never counts as recovered.
  const double nan = std::numeric_limits<double>::quiet_NaN();
  CHECK(lag_frames_relative({nan, 2, 2, 9, nan, 2}, 3, 0.0) == 2);
  CHECK_THROWS_AS(lag_frames_relative(error, 0, 0.1), Error);  // nothing before the change
  CHECK_THROWS_AS(lag_frames(error, 8, 1.0), Error);           // outside the series
}
