// Tests of filters/trmv/atrous.cpp: TRMV's a-trous of diffuse light and cones [TRMV21 Sec. 5]: SVGF's 3x3 box levels
// with w_z w_n and no luminance weight, by hand, its 31x31 reach, and its geometric edges.
#include "filters/trmv/atrous.h"

#include "core/error.h"

#include "trmv_fixtures.h"

#include <catch2/catch.hpp>

#include <cstdlib>

using namespace rtdr;

namespace {

SurfacePlanes flat(int w, int h) {
  return {FloatPlane(w, h, 3.0f), Vec2Plane(w, h, glm::vec2(0.0f)), RgbPlane(w, h, glm::vec3(0.0f, 0.0f, 1.0f)),
          UIntPlane(w, h, 0u), Vec2Plane(w, h, glm::vec2(0.0f))};
}

}  // namespace

TEST_CASE("a-trous: one level spreads a spike over the 3x3 box, 1/9 each, and level 1 over taps 2 apart") {
  RgbPlane spike(9, 9, glm::vec3(0.0f));
  spike.at(4, 4) = glm::vec3(9.0f);
  const SvgfParams edges;
  const RgbPlane one = trmv_atrous_level(spike, flat(9, 9), 0, edges);
  const RgbPlane two = trmv_atrous_level(spike, flat(9, 9), 1, edges);
  for (int y = 0; y < 9; ++y)
    for (int x = 0; x < 9; ++x) {
      INFO("pixel " << x << ", " << y);
      const int dx = std::abs(x - 4), dy = std::abs(y - 4);
      CHECK(one.at(x, y).x == Approx(dx <= 1 && dy <= 1 ? 1.0f : 0.0f).margin(1e-6));
      // Level 1 reaches (x +- 2, y +- 2): the pixels 0 or 2 away on each axis see the spike.
      const bool reached = (dx == 0 || dx == 2) && (dy == 0 || dy == 2);
      CHECK(two.at(x, y).x == Approx(reached ? 1.0f : 0.0f).margin(1e-6));
    }
}

TEST_CASE("a-trous: four levels reach 15 pixels each way, 'essentially 32x32', and a constant stays constant") {
  const int n = 41;
  RgbPlane spike(n, n, glm::vec3(0.0f));
  spike.at(20, 20) = glm::vec3(1.0f);
  const RgbPlane out = trmv_atrous_pass(spike, flat(n, n), 4, SvgfParams{});
  for (int y = 0; y < n; ++y)
    for (int x = 0; x < n; ++x) {
      const int reach = std::max(std::abs(x - 20), std::abs(y - 20));
      if (reach > 15) CHECK(out.at(x, y).x == 0.0f);
    }
  CHECK(out.at(35, 20).x > 0.0f);  // 15 away: 1 + 2 + 4 + 8
  CHECK(out.at(5, 5).x > 0.0f);
  const RgbPlane constant = trmv_atrous_pass(RgbPlane(n, n, glm::vec3(0.5f, 1.0f, 2.0f)), flat(n, n), 4, SvgfParams{});
  for (const glm::vec3& v : constant.data) {
    CHECK(v.x == Approx(0.5f).epsilon(1e-6));
    CHECK(v.z == Approx(2.0f).epsilon(1e-6));
  }
}

TEST_CASE("a-trous: no luminance weight, so the filter is linear in the light: f(a + b) = f(a) + f(b)") {
  // A 1-spp input is 0 or one bright path; SVGF's w_l would keep the bright pixel from its neighbours (atrous.h).
  const SurfacePlanes s = flat(16, 12);
  const RgbPlane a = noise_rgb(16, 12, 1), b = noise_rgb(16, 12, 2);
  RgbPlane sum = a;
  for (size_t i = 0; i < sum.data.size(); ++i) sum.data[i] = a.data[i] + 20.0f * b.data[i];
  const RgbPlane fa = trmv_atrous_pass(a, s, 3, SvgfParams{}), fb = trmv_atrous_pass(b, s, 3, SvgfParams{});
  const RgbPlane fsum = trmv_atrous_pass(sum, s, 3, SvgfParams{});
  for (size_t i = 0; i < sum.data.size(); ++i)
    CHECK(glm::length(fsum.data[i] - (fa.data[i] + 20.0f * fb.data[i])) < 1e-4f);
}

TEST_CASE("a-trous: two faces at right angles do not mix (w_n = 0), a pixel without a surface passes through") {
  SurfacePlanes s = flat(12, 6);
  RgbPlane c(12, 6, glm::vec3(0.0f));
  for (int y = 0; y < 6; ++y)
    for (int x = 6; x < 12; ++x) s.normal.at(x, y) = glm::vec3(1.0f, 0.0f, 0.0f), c.at(x, y) = glm::vec3(1.0f);
  s.mesh.at(2, 2) = kInvalidId;
  c.at(2, 2) = glm::vec3(50.0f);
  const RgbPlane out = trmv_atrous_pass(c, s, 3, SvgfParams{});
  for (int y = 0; y < 6; ++y)
    for (int x = 0; x < 12; ++x) {
      INFO("pixel " << x << ", " << y);
      if (x == 2 && y == 2) CHECK(out.at(x, y) == glm::vec3(50.0f));
      else if (x < 6) CHECK(out.at(x, y).x == 0.0f);
      else CHECK(out.at(x, y).x == Approx(1.0f).epsilon(1e-6));
    }
  CHECK_THROWS_AS(trmv_atrous_pass(c, flat(11, 6), 3, SvgfParams{}), Error);
}
