// Tests of filters/trmv/penumbra.cpp: the penumbra-sized shadow filter [LLK*19, TRMV21 Sec. 4.1]: the light's
// diameter from its samples' second moment, the penumbra's width by similar triangles, the metres per pixel of the
// receiver and the std per axis, by hand.
#include "filters/trmv/penumbra.h"

#include "core/error.h"

#include <catch2/catch.hpp>

#include <cmath>

using namespace rtdr;

TEST_CASE("the light's diameter: a disk of radius R gives 2R, a 0.4 x 1 m quad 2 sqrt((0.4^2 + 1) / 6) = 0.8794 m") {
  // Samples on a regular polar grid of a disk of radius 0.5 (area-uniform: r = R sqrt(u)), light instance 7, and
  // on a 40 x 100 midpoint grid of a 0.4 x 1 quad, instance 9; a pixel without a light sample is skipped.
  const int n = 4000 + 4000 + 1;
  RgbPlane light(n, 1);
  UIntPlane id(n, 1, 7u);
  for (int i = 0; i < 4000; ++i) {
    const double u = (double(i / 40) + 0.5) / 100.0, phi = 2.0 * 3.14159265358979 * (double(i % 40) + 0.5) / 40.0;
    const double r = 0.5 * std::sqrt(u);
    light.at(i, 0) = glm::vec3(float(r * std::cos(phi)) + 2.0f, 3.0f, float(r * std::sin(phi)));
  }
  for (int i = 0; i < 4000; ++i) {
    light.at(4000 + i, 0) = glm::vec3(0.4f * (float(i % 40) + 0.5f) / 40.0f, 3.5f, (float(i / 40) + 0.5f) / 100.0f);
    id.at(4000 + i, 0) = 9u;
  }
  id.at(n - 1, 0) = kInvalidId;
  const std::map<uint32_t, float> d = trmv_light_diameters(light, id);
  REQUIRE(d.size() == 2);
  CHECK(d.at(7) == Approx(1.0).epsilon(2e-3));
  CHECK(d.at(9) == Approx(2.0 * std::sqrt((0.16 + 1.0) / 6.0)).epsilon(2e-3));
}

TEST_CASE("the penumbra's width W = D (d_r - d_b) / d_b, and the std W / (6 m) per axis, clamped") {
  // The light 4 m above the receiver, the blocker halfway: the penumbra is as wide as the light.
  CHECK(trmv_penumbra_width(0.8f, {0, 4, 0}, {0, 2, 0}, {0, 0, 0}) == Approx(0.8f));
  // The blocker 3 m up, 1 m from the receiver: a third as wide.
  CHECK(trmv_penumbra_width(0.9f, {0, 4, 0}, {0.1f, 3, 0}, {0.4f, 0, 0}) ==
        Approx(0.9 * (std::sqrt(16.16) - std::sqrt(1.01)) / std::sqrt(1.01)).epsilon(1e-5));
  CHECK(trmv_penumbra_width(0.8f, {0, 4, 0}, {0, 4, 0}, {0, 0, 0}) == 0.0f);  // d_b = 0
  CHECK(trmv_penumbra_width(0.8f, {0, 4, 0}, {0, 1, 0}, {0, 2, 0}) == 0.0f);  // the receiver before the blocker
  // W = 1.2 m over pixels of 0.1 m: 12 pixels, std 2; capped and floored.
  CHECK(trmv_penumbra_sigma(1.2f, 0.1f, 0.5f, 5.0f) == Approx(2.0f));
  CHECK(trmv_penumbra_sigma(1.2f, 0.01f, 0.5f, 5.0f) == 5.0f);
  CHECK(trmv_penumbra_sigma(0.0f, 0.1f, 0.5f, 5.0f) == 0.5f);
  CHECK(trmv_penumbra_sigma(1.2f, 0.0f, 0.5f, 5.0f) == 0.5f);  // no metric: the least
}

TEST_CASE("metres per pixel: central differences on the receiver, one-sided at its edge, none across instances") {
  // A floor of instance 1 whose pixels step 0.1 m across and 0.25 m down (a grazing view), and at x = 4 a wall of
  // instance 2.
  const int w = 5, h = 3;
  TrmvPenumbraInputs in{RgbPlane(w, h), UIntPlane(w, h, kInvalidId), RgbPlane(w, h), UIntPlane(w, h, kInvalidId),
                        RgbPlane(w, h), UIntPlane(w, h, 1u),         RgbPlane(w, h, glm::vec3(0, 1, 0))};
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) in.position.at(x, y) = glm::vec3(0.1f * float(x), 0.0f, 0.25f * float(y));
  for (int y = 0; y < h; ++y) in.instance.at(4, y) = 2u, in.normal.at(4, y) = glm::vec3(1, 0, 0);
  CHECK(trmv_metres_per_pixel(in, {1, 0}, 1, 1) == Approx(0.1f));
  CHECK(trmv_metres_per_pixel(in, {0, 1}, 1, 1) == Approx(0.25f));
  CHECK(trmv_metres_per_pixel(in, {0, 1}, 1, 0) == Approx(0.25f));  // one-sided at the image's edge
  CHECK(trmv_metres_per_pixel(in, {1, 0}, 3, 1) == Approx(0.1f));   // one-sided: (4, 1) is the wall
  in.instance.at(2, 1) = in.instance.at(0, 1) = 5u;
  CHECK(trmv_metres_per_pixel(in, {1, 0}, 1, 1) == 0.0f);  // alone on its instance along x: unknown
  // The pass: W only where the shadow ray was blocked; no surface, no metric.
  in.light_id = UIntPlane(w, h, 3u);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) in.light.at(x, y) = glm::vec3(0.2f * float(x), 4.0f, 0.2f * float(y));
  in.blocker = RgbPlane(w, h, glm::vec3(0.0f, 2.0f, 0.0f));
  in.blocker_id.at(0, 0) = 8u;
  in.instance.at(3, 2) = kInvalidId;
  const TrmvPenumbraOutput out = trmv_penumbra_pass(in);
  // At (0, 0): the light sample straight above at 4 m, the blocker at 2 m: W = D, the samples' diameter.
  const float diameter = trmv_light_diameters(in.light, in.light_id).at(3u);
  CHECK(diameter > 0.5f);
  CHECK(out.width.at(0, 0) == Approx(diameter));
  CHECK(out.width.at(1, 0) == 0.0f);  // lit
  CHECK(out.metres.at(3, 2) == glm::vec2(0.0f));
  CHECK_THROWS_AS(trmv_penumbra_pass({RgbPlane(w, h + 1), in.light_id, in.blocker, in.blocker_id, in.position,
                                      in.instance, in.normal}),
                  Error);
}
