// Tests for core/color.h: the sRGB curve at points known from IEC 61966-2-1, luminance weights, bytes.
#include "core/color.h"

#include <catch2/catch.hpp>

#include <limits>

using Catch::Detail::Approx;

TEST_CASE("srgb_encode at known points of IEC 61966-2-1") {
  CHECK(rtdr::srgb_encode(0.0f) == 0.0f);
  CHECK(rtdr::srgb_encode(1.0f) == Approx(1.0f).margin(1e-6));
  // The junction of the two segments: linear 0.0031308 encodes to 0.04045 from both sides.
  CHECK(rtdr::srgb_encode(0.0031308f) == Approx(0.04045f).margin(1e-6));
  CHECK(rtdr::srgb_encode(0.0031309f) == Approx(0.04045f).margin(1e-5));
  // Mid grey: 1.055 * 0.5^(1/2.4) - 0.055 = 0.735357 (to six digits).
  CHECK(rtdr::srgb_encode(0.5f) == Approx(0.735357f).margin(1e-6));
  // 18% grey, a photographer's reference, encodes to about 0.4614.
  CHECK(rtdr::srgb_encode(0.18f) == Approx(0.461356f).margin(1e-5));
}

TEST_CASE("srgb_encode is increasing on [0, 1]") {
  float previous = rtdr::srgb_encode(0.0f);
  for (int i = 1; i <= 1000; ++i) {
    const float encoded = rtdr::srgb_encode(float(i) / 1000.0f);
    CHECK(encoded > previous);
    previous = encoded;
  }
}

TEST_CASE("luminance uses the Rec. 709 weights") {
  CHECK(rtdr::luminance(glm::vec3(1.0f)) == Approx(1.0f).margin(1e-6));
  CHECK(rtdr::luminance({1.0f, 0.0f, 0.0f}) == Approx(0.2126f));
  CHECK(rtdr::luminance({0.0f, 1.0f, 0.0f}) == Approx(0.7152f));
  CHECK(rtdr::luminance({0.0f, 0.0f, 1.0f}) == Approx(0.0722f));
}

TEST_CASE("to_byte rounds and clamps, NaN becomes 0") {
  CHECK(rtdr::to_byte(0.0f) == 0);
  CHECK(rtdr::to_byte(1.0f) == 255);
  CHECK(rtdr::to_byte(0.5f) == 128);               // 127.5 rounds up
  CHECK(rtdr::to_byte(1.0f / 255.0f) == 1);
  CHECK(rtdr::to_byte(0.49f / 255.0f) == 0);
  CHECK(rtdr::to_byte(-3.0f) == 0);
  CHECK(rtdr::to_byte(7.0f) == 255);
  CHECK(rtdr::to_byte(std::numeric_limits<float>::infinity()) == 255);
  CHECK(rtdr::to_byte(std::numeric_limits<float>::quiet_NaN()) == 0);
}
