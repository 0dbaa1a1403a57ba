// Tests of filters/baselines/eaw.cpp: the edge-avoiding a-trous filter of Dammertz et al. 2010 [EAW10].
#include "filters/baselines/eaw.h"

#include "core/error.h"

#include <catch2/catch.hpp>

#include <cmath>
#include <string>

using namespace rtdr;

namespace {

// A plane facing the camera, normal +z, positions 1 mm apart per pixel (so w_x ~ 1 even 32 pixels away:
// exp(-(0.032 / 0.25)^2) = 0.984), one mesh.
struct Scene {
  SurfacePlanes s;
  RgbPlane position;
};

Scene flat_scene(int w, int h) {
  Scene sc;
  sc.s.depth = FloatPlane(w, h, 1.0f);
  sc.s.depth_grad = Vec2Plane(w, h, glm::vec2(0.0f));
  sc.s.normal = RgbPlane(w, h, glm::vec3(0.0f, 0.0f, 1.0f));
  sc.s.mesh = UIntPlane(w, h, 0u);
  sc.s.motion = Vec2Plane(w, h, glm::vec2(0.0f));
  sc.position = RgbPlane(w, h);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) sc.position.at(x, y) = {0.001f * float(x), -0.001f * float(y), -1.0f};
  return sc;
}

std::string tap(int dx, int dy) { return "tap (" + std::to_string(dx) + ", " + std::to_string(dy) + ")"; }

}  // namespace

TEST_CASE("EAW parameters: one table, documented defaults, range checks", "[eaw]") {
  const EawParams p;
  CHECK(p.sigma_rt == 1.0f);
  CHECK(p.sigma_n == 0.3f);
  CHECK(p.sigma_x == 0.25f);
  CHECK(p.levels == 5);
  CHECK(eaw_param_table().size() == 4);
  CHECK_NOTHROW(validate(p));
  EawParams bad;
  bad.sigma_rt = 0.0f;
  CHECK_THROWS_AS(validate(bad), Error);
}

TEST_CASE("EAW passes a constant image unchanged through all levels", "[eaw]") {
  // Normalised by sum h w, so any weights give c back; bend normals and positions so the weights differ.
  const int w = 48, h = 40;
  Scene sc = flat_scene(w, h);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      sc.s.normal.at(x, y) = glm::normalize(glm::vec3(0.03f * float(x - 20), 0.0f, 1.0f));
      sc.position.at(x, y).z = -1.0f - 0.2f * float((x + y) % 3);
      if ((x * 7 + y * 3) % 19 == 0) sc.s.mesh.at(x, y) = kInvalidId;
    }
  const glm::vec3 c(3.0f, 0.4f, 1.25f);
  const RgbPlane out = eaw_filter(RgbPlane(w, h, c), sc.position, sc.s, EawParams{});
  for (const glm::vec3& v : out.data) {
    CHECK(v.r == Approx(c.r).epsilon(1e-6));
    CHECK(v.g == Approx(c.g).epsilon(1e-6));
    CHECK(v.b == Approx(c.b).epsilon(1e-6));
  }
}

TEST_CASE("EAW halves sigma_rt every level", "[eaw]") {
  // The centre pixel is black, every other pixel (0.05, 0, 0): ||I_p - I_q||^2 = 0.0025 at every tap. With
  // sigma_rt 2^-i the colour weight is exp(-0.0025 4^i / sigma_rt^2): level 0 exp(-0.0025) = 0.9975, level 4
  // exp(-0.64) = 0.527. w_n = 1 and w_x = exp(-(0.001 * 2^i)^2 / 0.0625) (1 mm per pixel along x).
  const int n = 41, c = 20;
  const Scene sc = flat_scene(n, n);
  RgbPlane color(n, n, glm::vec3(0.05f, 0.0f, 0.0f));
  color.at(c, c) = glm::vec3(0.0f);
  const EawParams p;
  for (int level = 0; level < 5; ++level) {
    const int step = 1 << level;
    Probe probe;
    eaw_pixel(color, sc.position, sc.s, level, p, c, c, &probe);
    const double sigma_i = 1.0 / double(step);  // sigma_rt = 1, halved `level` times
    INFO("level " << level);
    CHECK(probe.find("sigma_rt 2^-i").value[0] == float(sigma_i));
    CHECK(eaw_sigma_rt(p, level) == float(sigma_i));
    CHECK(probe.find("w_rt", tap(step, 0)).value[0] ==
          Approx(std::exp(-0.0025 / (sigma_i * sigma_i))).epsilon(1e-5));
    const double dx_m = 0.001 * step;  // the tap's distance in metres
    CHECK(probe.find("w_x", tap(step, 0)).value[0] == Approx(std::exp(-dx_m * dx_m / 0.0625)).epsilon(1e-5));
    CHECK(probe.find("w_n", tap(step, 0)).value[0] == 1.0f);
    CHECK(probe.find("w", tap(0, 0)).value[0] == 1.0f);  // the centre: all three differences are 0
  }
  CHECK(std::exp(-0.0025 * 256.0) == Approx(0.527292).epsilon(1e-5));  // the level-4 number in the comment
}

TEST_CASE("EAW keeps a colour edge that plain a-trous smoothing blurs", "[eaw]") {
  // Left half 0, right half (3, 3, 3): across the edge ||dI||^2 = 27, w_rt = exp(-27) = 1.9e-12 at level 0 and
  // smaller later, so the edge stays sharp to 1e-6 through five levels. The control: sigma_rt = 1e6 turns the
  // colour weight off and the same filter smears the edge (the pixel beside it ends up far from 0).
  const int w = 64, h = 24;
  const Scene sc = flat_scene(w, h);
  RgbPlane color(w, h, glm::vec3(0.0f));
  for (int y = 0; y < h; ++y)
    for (int x = 32; x < w; ++x) color.at(x, y) = glm::vec3(3.0f);
  const RgbPlane kept = eaw_filter(color, sc.position, sc.s, EawParams{});
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) CHECK(kept.at(x, y).g == Approx(color.at(x, y).g).margin(1e-6));
  EawParams blind;
  blind.sigma_rt = 1e6f;
  const RgbPlane blurred = eaw_filter(color, sc.position, sc.s, blind);
  CHECK(blurred.at(31, 12).g > 0.5f);
  CHECK(blurred.at(32, 12).g < 2.5f);
}

TEST_CASE("EAW stops at a position step and skips pixels without a surface", "[eaw]") {
  // The right half is 1 m behind the left: w_x = exp(-1 / 0.0625) = exp(-16) = 1.1e-7 per tap. A spike left of
  // the edge leaks at most ~1e-7 of itself across, where without the step it spreads freely.
  const int w = 32, h = 16;
  Scene sc = flat_scene(w, h);
  RgbPlane spike(w, h, glm::vec3(0.0f));
  spike.at(13, 8) = glm::vec3(1.0f);
  EawParams p;
  p.sigma_rt = 1e6f;  // colour weight off: only geometry may stop the filter
  const RgbPlane free_run = eaw_level(spike, sc.position, sc.s, 1, p);
  CHECK(free_run.at(17, 8).r > 0.01f);
  for (int y = 0; y < h; ++y)
    for (int x = 16; x < w; ++x) sc.position.at(x, y).z = -2.0f;
  for (int level = 0; level < 4; ++level) {
    const RgbPlane out = eaw_level(spike, sc.position, sc.s, level, p);
    for (int y = 0; y < h; ++y)
      for (int x = 16; x < w; ++x) CHECK(out.at(x, y).r < 2e-7f);
  }
  // No surface on the right: its colour (5) never reaches the left, and it passes through unchanged.
  Scene hole = flat_scene(w, h);
  RgbPlane color = spike;
  for (int y = 0; y < h; ++y)
    for (int x = 16; x < w; ++x) {
      hole.s.mesh.at(x, y) = kInvalidId;
      color.at(x, y) = glm::vec3(5.0f);
    }
  const RgbPlane out = eaw_level(color, hole.position, hole.s, 1, p);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) CHECK(out.at(x, y).r <= (x < 16 ? 1.0f : 5.0f));
  CHECK(out.at(20, 8) == glm::vec3(5.0f));
}
