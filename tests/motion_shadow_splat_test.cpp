// Tests of motion/shadow_splat.cpp: the splat of shadow motion vectors [TRMV21 Sec. 4.1], its window, its
// weights, its depth test and its fallback to the surface motion.
#include "motion/shadow_splat.h"

#include "core/error.h"

#include <catch2/catch.hpp>

#include <cstdlib>
#include <vector>

using namespace rtdr;

namespace {

constexpr int kW = 24, kH = 20;

struct Planes {
  std::vector<ShadowMotion> shadow = std::vector<ShadowMotion>(size_t(kW * kH));
  std::vector<glm::vec2> surface = std::vector<glm::vec2>(size_t(kW * kH), glm::vec2(0.25f, -0.5f));
  std::vector<float> depth = std::vector<float>(size_t(kW * kH), 5.0f);  // a flat wall, 5 m away
  void set(int x, int y, glm::vec2 m) { shadow[size_t(y * kW + x)] = {m, true}; }
  // The splatted motion of every pixel; `landed` counts the pixels a valid vector landed on.
  std::vector<glm::vec2> splat(int size = kShadowSplatSize, int* landed = nullptr) const {
    std::vector<glm::vec2> motion;
    for (const SplatMotion& m : splat_shadow_motion(shadow, surface, depth, kW, kH, size)) {
      motion.push_back(m.motion);
      if (landed) *landed += m.landed;
    }
    return motion;
  }
};

}  // namespace

TEST_CASE("one in-shadow pixel's vector lands on exactly the 9x9 window around it, elsewhere the surface motion") {
  Planes p;
  p.set(10, 8, {3.0f, -2.0f});
  int landed_flags = 0;
  const std::vector<glm::vec2> out = p.splat(kShadowSplatSize, &landed_flags);
  int landed = 0;
  for (int y = 0; y < kH; ++y)
    for (int x = 0; x < kW; ++x) {
      const bool inside = std::abs(x - 10) <= 4 && std::abs(y - 8) <= 4;
      const glm::vec2 expected = inside ? glm::vec2(3.0f, -2.0f) : glm::vec2(0.25f, -0.5f);
      CHECK(out[size_t(y * kW + x)] == expected);
      landed += inside;
    }
  CHECK(landed == 81);
  CHECK(landed_flags == 81);
}

TEST_CASE("overlapping splats average with equal weights, and a window clipped by the image still averages") {
  Planes p;
  p.set(0, 0, {1.0f, 0.0f});
  p.set(2, 0, {0.0f, 4.0f});
  p.set(3, 1, {2.0f, 2.0f});
  const std::vector<glm::vec2> out = p.splat();
  CHECK(out[0] == glm::vec2(1.0f, 2.0f));          // (0, 0) reaches all three: (1 + 0 + 2, 0 + 4 + 2) / 3
  CHECK(out[size_t(6)] == glm::vec2(1.0f, 3.0f));   // (6, 0) reaches (2, 0) and (3, 1), not (0, 0)
  CHECK(out[size_t(kW * 5 + 7)] == glm::vec2(2.0f, 2.0f));  // (7, 5): only (3, 1) is within 4 pixels
}

TEST_CASE("a splat lands only on the same surface (depths within 10 %), and never on the background") {
  Planes p;
  p.set(10, 8, {3.0f, -2.0f});
  p.depth[size_t(8 * kW + 12)] = 5.6f;   // 12 % further: another surface
  p.depth[size_t(8 * kW + 13)] = 5.45f;  // 8 % further: the same one
  p.depth[size_t(9 * kW + 10)] = 0.0f;   // no surface
  const std::vector<glm::vec2> out = p.splat();
  CHECK(out[size_t(8 * kW + 12)] == glm::vec2(0.25f, -0.5f));
  CHECK(out[size_t(8 * kW + 13)] == glm::vec2(3.0f, -2.0f));
  CHECK(out[size_t(9 * kW + 10)] == glm::vec2(0.0f));
}

TEST_CASE("a 1x1 window keeps each pixel's own vector, and an even or empty window, or planes of another size, throw") {
  Planes p;
  p.set(5, 5, {3.0f, -2.0f});
  const std::vector<glm::vec2> out = p.splat(1);
  CHECK(out[size_t(5 * kW + 5)] == glm::vec2(3.0f, -2.0f));
  CHECK(out[size_t(5 * kW + 6)] == glm::vec2(0.25f, -0.5f));
  CHECK_THROWS_AS(p.splat(8), Error);
  CHECK_THROWS_AS(p.splat(0), Error);
  CHECK_THROWS_AS(splat_shadow_motion(p.shadow, p.surface, std::vector<float>(3), kW, kH, 9), Error);
}

TEST_CASE("the frame loop equals the per-pixel gather at every pixel, windows without a valid vector included") {
  Planes p;
  // A scattered pattern: valid vectors on some pixels, another surface on others, background on a few.
  for (int y = 0; y < kH; ++y)
    for (int x = 0; x < kW; ++x) {
      const int h = (x * 7 + y * 13) % 29;
      if (h < 2) p.set(x, y, {float(h) - 0.5f, float(x % 3)});
      if (h == 5) p.depth[size_t(y * kW + x)] = 9.0f;
      if (h == 11) p.depth[size_t(y * kW + x)] = 0.0f;
      p.surface[size_t(y * kW + x)] = {float(x) * 0.25f, float(y) * -0.5f};
    }
  p.shadow[size_t(3 * kW + 3)] = {};  // and a corner far from the rest: some windows hold no valid vector
  const std::vector<SplatMotion> frame = splat_shadow_motion(p.shadow, p.surface, p.depth, kW, kH, 5);
  int empty_windows = 0;
  for (int y = 0; y < kH; ++y)
    for (int x = 0; x < kW; ++x) {
      const SplatMotion one = splat_shadow_motion_pixel(p.shadow, p.surface, p.depth, kW, kH, 5, x, y);
      const SplatMotion& got = frame[size_t(y * kW + x)];
      CHECK(got.motion == one.motion);
      CHECK(got.landed == one.landed);
      empty_windows += !one.landed;
    }
  CHECK(empty_windows > 0);
}
