// Tests of filters/trmv/splat.cpp: the splat of shadow motion vectors [TRMV21 Sec. 4.1], its window, its weights,
// its receiving-surface test (the same instance, normals within 25.8 degrees), the property it carries and its
// fallback to the surface motion.
#include "filters/trmv/splat.h"

#include "core/error.h"

#include <catch2/catch.hpp>

#include <cstdlib>

using namespace rtdr;

namespace {

constexpr int kW = 24, kH = 20;

struct Planes {
  TrmvSplatPlanes in{Vec2Plane(kW, kH), UIntPlane(kW, kH, 0u), Vec2Plane(kW, kH, glm::vec2(0.25f, -0.5f)),
                     UIntPlane(kW, kH, 3u), RgbPlane(kW, kH, glm::vec3(0.0f, 1.0f, 0.0f)), FloatPlane()};
  void set(int x, int y, glm::vec2 m) { in.shadow.at(x, y) = m, in.valid.at(x, y) = 1u; }
  // The splatted motion of every pixel; `landed` counts the pixels a valid vector landed on.
  std::vector<glm::vec2> splat(int size = 9, int* landed = nullptr) const {
    const TrmvSplatOutput out = trmv_splat_pass(in, size);
    if (landed)
      for (uint32_t l : out.landed.data) *landed += int(l);
    return out.motion.data;
  }
};

}  // namespace

TEST_CASE("one in-shadow pixel's vector lands on exactly the 9x9 window around it, elsewhere the surface motion") {
  Planes p;
  p.set(10, 8, {3.0f, -2.0f});
  int landed_flags = 0;
  const std::vector<glm::vec2> out = p.splat(9, &landed_flags);
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
  // An 11x11 window (the shadow filter's at 640x360, filters/trmv/footprint.h) reaches one pixel further each way.
  int wider = 0;
  p.splat(11, &wider);
  CHECK(wider == 121);
}

TEST_CASE("overlapping splats average with equal weights, the carried property too, and a clipped window averages") {
  Planes p;
  p.set(0, 0, {1.0f, 0.0f});
  p.set(2, 0, {0.0f, 4.0f});
  p.set(3, 1, {2.0f, 2.0f});
  p.in.carried = FloatPlane(kW, kH, 0.0f);
  p.in.carried.at(0, 0) = 0.3f, p.in.carried.at(2, 0) = 0.6f, p.in.carried.at(3, 1) = 1.2f;
  const TrmvSplatOutput out = trmv_splat_pass(p.in, 9);
  CHECK(out.motion.at(0, 0) == glm::vec2(1.0f, 2.0f));  // (0, 0) reaches all three: (1 + 0 + 2, 0 + 4 + 2) / 3
  CHECK(out.carried.at(0, 0) == Approx(0.7f));          // (0.3 + 0.6 + 1.2) / 3, "other associated properties"
  CHECK(out.motion.at(6, 0) == glm::vec2(1.0f, 3.0f));  // (6, 0) reaches (2, 0) and (3, 1), not (0, 0)
  CHECK(out.carried.at(6, 0) == Approx(0.9f));
  CHECK(out.motion.at(7, 5) == glm::vec2(2.0f, 2.0f));  // (7, 5): only (3, 1) is within 4 pixels
  CHECK(out.carried.at(20, 15) == 0.0f);                // none landed: 0
}

TEST_CASE("a splat lands only on its receiving surface: the same instance, normals within 25.8 degrees, never the "
          "background") {
  Planes p;
  p.set(10, 8, {3.0f, -2.0f});
  p.in.instance.at(12, 8) = 4u;                                 // another instance (the next slat of one mesh)
  p.in.normal.at(13, 8) = glm::normalize(glm::vec3(0.5f, 1.0f, 0.0f));  // 26.6 degrees off: round a fold
  p.in.normal.at(14, 8) = glm::normalize(glm::vec3(0.4f, 1.0f, 0.0f));  // 21.8 degrees off: the same face, bent
  p.in.instance.at(10, 9) = kInvalidId;                         // no surface
  const std::vector<glm::vec2> out = p.splat();
  CHECK(out[size_t(8 * kW + 12)] == glm::vec2(0.25f, -0.5f));
  CHECK(out[size_t(8 * kW + 13)] == glm::vec2(0.25f, -0.5f));
  CHECK(out[size_t(8 * kW + 14)] == glm::vec2(3.0f, -2.0f));
  CHECK(out[size_t(9 * kW + 10)] == glm::vec2(0.0f));
  CHECK(out[size_t(8 * kW + 11)] == glm::vec2(3.0f, -2.0f));
  // The depth no longer decides: a pixel of the same instance and normal lands whatever its depth (the old test
  // rejected 12 % and let a slat in front of the floor within 10 % through).
  CHECK(trmv_splat_same_surface(p.in, 10, 8, 11, 8));
  CHECK_FALSE(trmv_splat_same_surface(p.in, 10, 8, 12, 8));
}

TEST_CASE("a 1x1 window keeps each pixel's own vector, and an even or empty window, or planes of another size, throw") {
  Planes p;
  p.set(5, 5, {3.0f, -2.0f});
  const std::vector<glm::vec2> out = p.splat(1);
  CHECK(out[size_t(5 * kW + 5)] == glm::vec2(3.0f, -2.0f));
  CHECK(out[size_t(5 * kW + 6)] == glm::vec2(0.25f, -0.5f));
  CHECK_THROWS_AS(p.splat(8), Error);
  CHECK_THROWS_AS(p.splat(0), Error);
  TrmvSplatPlanes wrong = p.in;
  wrong.normal = RgbPlane(3, 1);
  CHECK_THROWS_AS(trmv_splat_pass(wrong, 9), Error);
  wrong = p.in;
  wrong.carried = FloatPlane(kW, kH + 1);
  CHECK_THROWS_AS(trmv_splat_pass(wrong, 9), Error);
}

TEST_CASE("the frame loop equals the per-pixel gather at every pixel, windows without a valid vector included") {
  Planes p;
  p.in.carried = FloatPlane(kW, kH, 0.0f);
  // A scattered pattern: valid vectors on some pixels, another instance on others, background on a few.
  for (int y = 0; y < kH; ++y)
    for (int x = 0; x < kW; ++x) {
      const int h = (x * 7 + y * 13) % 29;
      if (h < 2) p.set(x, y, {float(h) - 0.5f, float(x % 3)}), p.in.carried.at(x, y) = 0.1f * float(x);
      if (h == 5) p.in.instance.at(x, y) = 9u;
      if (h == 11) p.in.instance.at(x, y) = kInvalidId;
      p.in.surface_motion.at(x, y) = {float(x) * 0.25f, float(y) * -0.5f};
    }
  p.in.valid.at(3, 3) = 0u;  // and a corner far from the rest: some windows hold no valid vector
  const TrmvSplatOutput frame = trmv_splat_pass(p.in, 5);
  int empty_windows = 0;
  for (int y = 0; y < kH; ++y)
    for (int x = 0; x < kW; ++x) {
      const TrmvSplatPixel one = trmv_splat_pixel(p.in, 5, x, y);
      CHECK(frame.motion.at(x, y) == one.motion);
      CHECK(frame.landed.at(x, y) == (one.landed ? 1u : 0u));
      CHECK(frame.carried.at(x, y) == one.carried);
      empty_windows += !one.landed;
    }
  CHECK(empty_windows > 0);
}
