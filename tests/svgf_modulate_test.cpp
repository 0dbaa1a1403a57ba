// Tests of filters/svgf/modulate.cpp: remodulation inverts the path tracer's demodulation [SVGF17 Sec. 3],
// black albedo channels included, and emission adds unchanged.
#include "filters/svgf/modulate.h"

#include "core/color.h"
#include "core/error.h"

#include <catch2/catch.hpp>

#include <random>

using Catch::Detail::Approx;
using namespace rtdr;

namespace {

// What trace/render_frame does: divide radiance by the demodulation factor (core/color.h).
glm::vec3 demodulate(const glm::vec3& radiance, const glm::vec3& albedo) {
  return radiance / demodulation_factor(albedo);
}

// A float division followed by a multiplication by the same number is exact up to two roundings; the sum
// direct + indirect adds one more: a relative error of a few 1e-7 at most.
void check_close(const glm::vec3& a, const glm::vec3& b) {
  for (int i = 0; i < 3; ++i) CHECK(a[i] == Approx(b[i]).epsilon(1e-6).margin(1e-12));
}

}  // namespace

TEST_CASE("remodulating the demodulated radiance gives the radiance back, for any albedo") {
  std::mt19937 rng(7);
  std::uniform_real_distribution<float> radiance(0.0f, 20.0f), albedo_value(0.0f, 1.0f);
  for (int i = 0; i < 1000; ++i) {
    const glm::vec3 L_direct(radiance(rng), radiance(rng), radiance(rng));
    const glm::vec3 L_indirect(radiance(rng), radiance(rng), radiance(rng));
    glm::vec3 albedo(albedo_value(rng), albedo_value(rng), albedo_value(rng));
    if (i % 3 == 0) albedo[i % 9 / 3] = 0.0f;  // a black channel: the factor is the floor 0.001
    if (i % 7 == 0) albedo = glm::vec3(0.0f);
    const glm::vec3 colour = remodulate_pixel(demodulate(L_direct, albedo), demodulate(L_indirect, albedo), albedo,
                                              glm::vec3(0.0f));
    check_close(colour, L_direct + L_indirect);
  }
}

TEST_CASE("black albedo channels: illumination was divided by 0.001 and is multiplied by 0.001") {
  const glm::vec3 albedo(0.0f, 0.5f, 0.0005f);  // two channels below the 0.001 floor
  const glm::vec3 direct_radiance(0.002f, 0.3f, 0.004f), indirect_radiance(0.001f, 0.1f, 0.0f);
  const glm::vec3 direct = demodulate(direct_radiance, albedo), indirect = demodulate(indirect_radiance, albedo);
  CHECK(direct.r == Approx(2.0f).epsilon(1e-6));  // 0.002 / 0.001
  CHECK(direct.b == Approx(4.0f).epsilon(1e-6));  // 0.004 / 0.001, not / 0.0005
  check_close(remodulate_pixel(direct, indirect, albedo, glm::vec3(0.0f)), {0.003f, 0.4f, 0.004f});
}

TEST_CASE("with power-of-two albedos demodulation and remodulation are bit-exact") {
  const glm::vec3 albedo(0.5f, 0.25f, 1.0f);
  const glm::vec3 direct(1.5f, 2.0f, 0.75f), indirect(0.25f, 4.0f, 0.125f);  // demodulated values
  // 0.5 * (1.5 + 0.25) = 0.875, 0.25 * (2 + 4) = 1.5, 1 * (0.75 + 0.125) = 0.875: all exact in float.
  CHECK(remodulate_pixel(direct, indirect, albedo, glm::vec3(0.0f)) == glm::vec3(0.875f, 1.5f, 0.875f));
}

TEST_CASE("emission is added unchanged, never multiplied by the albedo") {
  const glm::vec3 albedo(0.2f, 0.0f, 0.9f), direct(1.0f, 2.0f, 3.0f), indirect(0.5f, 0.5f, 0.5f);
  const glm::vec3 emission(4.0f, 5.0f, 6.0f);
  const glm::vec3 without = remodulate_pixel(direct, indirect, albedo, glm::vec3(0.0f));
  const glm::vec3 with = remodulate_pixel(direct, indirect, albedo, emission);
  check_close(with, without + emission);
  // By hand: (0.2, 0.001, 0.9) * (1.5, 2.5, 3.5) = (0.3, 0.0025, 3.15), plus the emission.
  check_close(with, {4.3f, 5.0025f, 9.15f});
  // An emitter with no reflected light shows its emission exactly.
  CHECK(remodulate_pixel(glm::vec3(0.0f), glm::vec3(0.0f), albedo, emission) == emission);
}

TEST_CASE("the probe records the factor, the illumination, the reflected light and the colour") {
  Probe probe;
  const glm::vec3 colour =
      remodulate_pixel({1.0f, 1.0f, 1.0f}, {1.0f, 0.0f, 3.0f}, {0.5f, 0.0f, 0.25f}, {0.0f, 0.0f, 1.0f}, &probe);
  CHECK(probe.find("demodulation factor max(albedo, 0.001)").value == std::vector<float>{0.5f, 0.001f, 0.25f});
  CHECK(probe.find("illumination direct + indirect").value == std::vector<float>{2.0f, 1.0f, 4.0f});
  CHECK(probe.find("reflected factor * illumination").value == std::vector<float>{1.0f, 0.001f, 1.0f});
  CHECK(probe.find("colour emission + reflected").value == std::vector<float>{colour.r, colour.g, colour.b});
  CHECK(colour == glm::vec3(1.0f, 0.001f, 2.0f));
}

TEST_CASE("remodulate applies the per-pixel function to every pixel and checks sizes") {
  RgbPlane direct(4, 3), indirect(4, 3), albedo(4, 3), emission(4, 3);
  for (int y = 0; y < 3; ++y)
    for (int x = 0; x < 4; ++x) {
      direct.at(x, y) = glm::vec3(float(x), float(y), 1.0f);
      indirect.at(x, y) = glm::vec3(0.5f * float(y), 0.25f, float(x + y));
      albedo.at(x, y) = glm::vec3(0.25f * float(x), 0.5f, 0.0f);
      emission.at(x, y) = glm::vec3(0.0f, float(x == 2), 0.0f);
    }
  const RgbPlane colour = remodulate(direct, indirect, albedo, emission);
  REQUIRE(colour.width == 4);
  REQUIRE(colour.height == 3);
  for (int y = 0; y < 3; ++y)
    for (int x = 0; x < 4; ++x)
      CHECK(colour.at(x, y) ==
            remodulate_pixel(direct.at(x, y), indirect.at(x, y), albedo.at(x, y), emission.at(x, y)));
  CHECK_THROWS_AS(remodulate(direct, indirect, RgbPlane(3, 4), emission), Error);
}
