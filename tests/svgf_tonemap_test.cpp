// Tests of filters/svgf/tonemap.cpp: Reinhard02 Eq. 3 on luminance with a fixed exposure: 0 -> 0, values by
// hand, monotonic, bounded by 1, chromaticity kept below the clamp.
#include "filters/svgf/tonemap.h"

#include "core/color.h"
#include "core/error.h"

#include <catch2/catch.hpp>

using Catch::Detail::Approx;
using namespace rtdr;

TEST_CASE("black maps to black") {
  CHECK(tonemap_pixel(glm::vec3(0.0f), TonemapParams{}) == glm::vec3(0.0f));
  // Negative luminance (only from negative inputs) also maps to black.
  CHECK(tonemap_pixel(glm::vec3(-1.0f, 0.0f, 0.0f), TonemapParams{}) == glm::vec3(0.0f));
}

TEST_CASE("grey values by hand: L_d = L / (1 + L) with L = exposure * L_w") {
  const TonemapParams unit;  // exposure 1
  CHECK(tonemap_pixel(glm::vec3(1.0f), unit).g == Approx(0.5f).margin(1e-6));    // 1 / 2
  CHECK(tonemap_pixel(glm::vec3(3.0f), unit).g == Approx(0.75f).margin(1e-6));   // 3 / 4
  CHECK(tonemap_pixel(glm::vec3(0.25f), unit).g == Approx(0.2f).margin(1e-6));   // 0.25 / 1.25
  CHECK(tonemap_pixel(glm::vec3(99.0f), unit).g == Approx(0.99f).margin(1e-6));  // 99 / 100
  TonemapParams bright;
  bright.exposure = 2.0f;
  CHECK(tonemap_pixel(glm::vec3(0.5f), bright).r == Approx(0.5f).margin(1e-6));  // L = 1
  TonemapParams dark;
  dark.exposure = 0.5f;
  CHECK(tonemap_pixel(glm::vec3(1.0f), dark).b == Approx(1.0f / 3.0f).margin(1e-6));  // L = 0.5: 0.5 / 1.5
}

TEST_CASE("a colour by hand: scaled by L_d / L_w, so its chromaticity is kept") {
  // L_w = 0.2126 * 0.2 + 0.7152 * 0.4 + 0.0722 * 0.1 = 0.33582; L_d / L_w = 1 / (1 + L_w) = 0.7486038...
  const glm::vec3 colour(0.2f, 0.4f, 0.1f);
  Probe probe;
  const glm::vec3 display = tonemap_pixel(colour, TonemapParams{}, &probe);
  CHECK(probe.find("L_w").value[0] == Approx(0.33582f).margin(1e-6));
  CHECK(probe.find("L_d").value[0] == Approx(0.33582f / 1.33582f).margin(1e-6));
  CHECK(display.r == Approx(0.14972077f).margin(1e-6));
  CHECK(display.g == Approx(0.29944154f).margin(1e-6));
  CHECK(display.b == Approx(0.07486039f).margin(1e-6));
  CHECK(luminance(display) == Approx(0.33582f / 1.33582f).margin(1e-6));  // the display luminance is L_d
}

TEST_CASE("monotonic: brighter input, brighter output, channel by channel") {
  for (const glm::vec3 hue : {glm::vec3(1.0f), glm::vec3(0.2f, 0.4f, 0.1f), glm::vec3(0.9f, 0.05f, 0.3f)}) {
    glm::vec3 previous = tonemap_pixel(glm::vec3(0.0f), TonemapParams{});
    for (int i = 1; i <= 2000; ++i) {
      const float k = 0.01f * float(i) * float(i) / 100.0f;  // 1e-4 .. 400, denser near black
      const glm::vec3 display = tonemap_pixel(k * hue, TonemapParams{});
      for (int c = 0; c < 3; ++c) CHECK(display[c] >= previous[c]);
      CHECK(luminance(display) >= luminance(previous));
      previous = display;
    }
  }
}

TEST_CASE("bounded by 1, also for very bright saturated colours") {
  for (const glm::vec3 colour : {glm::vec3(1e6f), glm::vec3(1e30f, 0.0f, 0.0f), glm::vec3(0.0f, 0.0f, 10.0f),
                                 glm::vec3(50.0f, 1.0f, 200.0f)}) {
    const glm::vec3 display = tonemap_pixel(colour, TonemapParams{});
    for (int c = 0; c < 3; ++c) {
      CHECK(display[c] >= 0.0f);
      CHECK(display[c] <= 1.0f);
    }
  }
  // Pure blue (0, 0, 10): L_w = 0.722, L_d = 0.722 / 1.722, scaled blue = 10 / 1.722 = 5.81 -> clamped to 1.
  Probe probe;
  CHECK(tonemap_pixel(glm::vec3(0.0f, 0.0f, 10.0f), TonemapParams{}, &probe) == glm::vec3(0.0f, 0.0f, 1.0f));
  CHECK(probe.find("scaled colour").value[2] == Approx(10.0f / 1.722f).epsilon(1e-6));
}

TEST_CASE("tonemap applies the per-pixel function to every pixel, parameters are range-checked") {
  RgbPlane colour(3, 2);
  for (int y = 0; y < 2; ++y)
    for (int x = 0; x < 3; ++x) colour.at(x, y) = glm::vec3(float(x), 0.5f * float(y), float(x * y) + 0.1f);
  TonemapParams params;
  params.exposure = 1.5f;
  const RgbPlane display = tonemap(colour, params);
  for (int y = 0; y < 2; ++y)
    for (int x = 0; x < 3; ++x) CHECK(display.at(x, y) == tonemap_pixel(colour.at(x, y), params));
  params.exposure = -1.0f;
  CHECK_THROWS_AS(tonemap(colour, params), Error);
  REQUIRE(tonemap_param_table().size() == 1);
  CHECK(tonemap_param_table()[0].name == "exposure");
  CHECK(tonemap_param_table()[0].default_value == 1.0);
}
