// Tests for trace/lights: the emissive triangles of a posed scene and their choice by power.
//
// The main fixture, built in code (all numbers chosen so the expected values can be worked by hand):
//   instance 0  "floor":     a 4 m square facing up, NOT emissive;
//   instance 1  "small lamp": a 1 m square at height 3 facing down, Le = (1, 1, 1) x strength 2;
//   instance 2  "big lamp":   a 2 m square facing +Z, Le = (1, 0.5, 0.25) x strength 3, sliding from
//                             x, z = (5, 0) at t = 0 to (5, 2) at t = 1 (a node translation track).
// Each square is two triangles, so there are 4 lights. Power Phi = pi A luminance(Le) (lights.h), with the
// luminance weights 0.2126, 0.7152, 0.0722 (Rec. 709 Y, core/color.h):
//   small-lamp triangle: A = 1/2, luminance 2                                        -> Phi / pi = 1
//   big-lamp triangle:   A = 2,   luminance 3 (0.2126 + 0.5 x 0.7152 + 0.25 x 0.0722) = 1.76475
//                                                                                    -> Phi / pi = 3.5295
// so the pmf is 1 / 9.059 = 0.1104 for each small-lamp triangle and 3.5295 / 9.059 = 0.3896 for each big one.
#include "trace/lights.h"

#include "scene_fixtures.h"

#include <catch2/catch.hpp>

#include <glm/glm.hpp>
#include <glm/gtc/quaternion.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <random>
#include <vector>

using Catch::Detail::Approx;

namespace {

// Expected values of the main fixture, from the header comment.
constexpr double kSmallLampLuminance = 2.0;
constexpr double kBigLampLuminance = 3.0 * (0.2126 + 0.5 * 0.7152 + 0.25 * 0.0722);  // 1.76475
constexpr double kSmallTriangleArea = 0.5, kBigTriangleArea = 2.0;
constexpr double kTotalPowerOverPi = 2.0 * kSmallTriangleArea * kSmallLampLuminance + 2.0 * kBigTriangleArea * kBigLampLuminance;
constexpr double kSmallPmf = kSmallTriangleArea * kSmallLampLuminance / kTotalPowerOverPi;  // 0.1104
constexpr double kBigPmf = kBigTriangleArea * kBigLampLuminance / kTotalPowerOverPi;        // 0.3896
// Lights are listed instance by instance, in triangle order: small lamp (0, 1), big lamp (2, 3).
const std::array<double, 4> kPmf = {kSmallPmf, kSmallPmf, kBigPmf, kBigPmf};
const std::array<double, 4> kArea = {kSmallTriangleArea, kSmallTriangleArea, kBigTriangleArea, kBigTriangleArea};

// A rotation by `degrees` about +X: it turns add_quad's front (+Z) into (0, -sin, cos), so +90 faces down.
glm::quat about_x(float degrees) { return glm::angleAxis(glm::radians(degrees), glm::vec3(1.0f, 0.0f, 0.0f)); }

rtdr::Material emitter(glm::vec3 emissive, float strength) {
  rtdr::Material m;
  m.emissive = emissive;
  m.emissive_strength = strength;
  return m;
}

rtdr::Scene two_lamps_and_a_floor() {
  rtdr::Scene s = rtdr::test::camera_scene();
  rtdr::Material floor_material;  // glTF defaults: emissive (0, 0, 0)
  floor_material.base_color = glm::vec4(0.5f, 0.5f, 0.5f, 1.0f);
  const int floor = rtdr::test::add_material(s, floor_material);
  const int small = rtdr::test::add_material(s, emitter({1.0f, 1.0f, 1.0f}, 2.0f));
  const int big = rtdr::test::add_material(s, emitter({1.0f, 0.5f, 0.25f}, 3.0f));
  rtdr::test::add_quad(s, 4.0f, glm::vec3(0.0f), about_x(-90.0f), floor);                 // instance 0
  rtdr::test::add_quad(s, 1.0f, glm::vec3(0.0f, 3.0f, 0.0f), about_x(90.0f), small);      // instance 1
  const int big_lamp = rtdr::test::add_quad(s, 2.0f, glm::vec3(5.0f, 0.0f, 0.0f), glm::quat(1, 0, 0, 0), big);
  rtdr::Node& big_node = s.nodes[size_t(s.instances[size_t(big_lamp)].node)];
  big_node.translation_track.times = {0.0f, 1.0f};
  big_node.translation_track.values = {{5.0f, 0.0f, 0.0f}, {5.0f, 0.0f, 2.0f}};
  return s;
}

void check_vertex(const glm::vec3& got, const glm::vec3& expected) {
  INFO("got (" << got.x << ", " << got.y << ", " << got.z << "), expected (" << expected.x << ", " << expected.y
               << ", " << expected.z << ")");
  CHECK(glm::length(got - expected) < 1e-5f);
}

// Barycentric coordinates of p in triangle (a, b, c), in double: each is the signed area of the
// sub-triangle opposite its vertex over the whole, measured along the triangle's normal.
glm::dvec3 barycentric(const glm::dvec3& p, const glm::dvec3& a, const glm::dvec3& b, const glm::dvec3& c) {
  const glm::dvec3 n = glm::cross(b - a, c - a);
  const double nn = glm::dot(n, n);
  return {glm::dot(n, glm::cross(c - b, p - b)) / nn, glm::dot(n, glm::cross(a - c, p - c)) / nn,
          glm::dot(n, glm::cross(b - a, p - a)) / nn};
}

// The middle of light l's interval of u_select under the expected pmf: sample() must pick light l there.
float u_select_of_light(size_t l) {
  double before = 0.0;
  for (size_t k = 0; k < l; ++k) before += kPmf[k];
  return float(before + 0.5 * kPmf[l]);
}

// A "flickering" lamp (instance 0) whose strength track goes 4 -> 0 -> 4 over t = 0, 1, 2 (linear), and a steady
// lamp (instance 1) of strength 1, both unit quads with emissive factor (1, 1, 1), at x = 0 and x = 3.
rtdr::Scene flickering_and_steady_lamps() {
  rtdr::Scene scene = rtdr::test::camera_scene();
  rtdr::Material flicker = emitter({1.0f, 1.0f, 1.0f}, 1.0f);
  flicker.emissive_strength_track.times = {0.0f, 1.0f, 2.0f};
  flicker.emissive_strength_track.values = {4.0f, 0.0f, 4.0f};
  const int flicker_material = rtdr::test::add_material(scene, flicker);
  const int steady_material = rtdr::test::add_material(scene, emitter({1.0f, 1.0f, 1.0f}, 1.0f));
  rtdr::test::add_quad(scene, 1.0f, glm::vec3(0.0f, 2.0f, 0.0f), about_x(90.0f), flicker_material);
  rtdr::test::add_quad(scene, 1.0f, glm::vec3(3.0f, 2.0f, 0.0f), about_x(90.0f), steady_material);
  return scene;
}

}  // namespace

TEST_CASE("LightSet holds exactly the emissive triangles, in world space at the pose") {
  const rtdr::Scene scene = two_lamps_and_a_floor();
  const rtdr::LightSet lights(scene, scene.pose(0.5));
  REQUIRE(lights.lights().size() == 4);  // 2 lamps x 2 triangles; the floor contributes none
  CHECK_FALSE(lights.empty());
  const std::vector<rtdr::EmissiveTriangle>& e = lights.lights();

  SECTION("which (instance, triangle) each light is") {
    for (size_t l = 0; l < 4; ++l) {
      CHECK(e[l].instance == (l < 2 ? 1u : 2u));
      CHECK(e[l].triangle == uint32_t(l % 2));
    }
  }
  SECTION("the small lamp: +90 deg about X maps (x, y, 0) to (x, 0, y), then up by 3: facing -Y") {
    // add_quad's triangles are (v0, v1, v2) and (v0, v2, v3) with v = (-h,-h), (h,-h), (h,h), (-h,h), h = 0.5.
    check_vertex(e[0].p0, {-0.5f, 3.0f, -0.5f});
    check_vertex(e[0].p1, {0.5f, 3.0f, -0.5f});
    check_vertex(e[0].p2, {0.5f, 3.0f, 0.5f});
    check_vertex(e[1].p2, {-0.5f, 3.0f, 0.5f});
    check_vertex(e[0].normal, {0.0f, -1.0f, 0.0f});
    check_vertex(e[1].normal, {0.0f, -1.0f, 0.0f});
    CHECK(e[0].area == Approx(kSmallTriangleArea).epsilon(1e-6));
    check_vertex(e[0].radiance, {2.0f, 2.0f, 2.0f});
  }
  SECTION("the big lamp, moved by the pose: half way along its track at t = 0.5, i.e. centred at (5, 0, 1)") {
    check_vertex(e[2].p0, {4.0f, -1.0f, 1.0f});
    check_vertex(e[2].p1, {6.0f, -1.0f, 1.0f});
    check_vertex(e[2].p2, {6.0f, 1.0f, 1.0f});
    check_vertex(e[3].p2, {4.0f, 1.0f, 1.0f});
    check_vertex(e[3].normal, {0.0f, 0.0f, 1.0f});
    CHECK(e[3].area == Approx(kBigTriangleArea).epsilon(1e-6));
    check_vertex(e[3].radiance, {3.0f, 1.5f, 0.75f});
  }
  SECTION("the same scene at t = 0: the big lamp is back at z = 0") {
    const rtdr::LightSet at_start(scene, scene.pose(0.0));
    REQUIRE(at_start.lights().size() == 4);
    check_vertex(at_start.lights()[2].p0, {4.0f, -1.0f, 0.0f});
    check_vertex(at_start.lights()[0].p0, {-0.5f, 3.0f, -0.5f});  // the small lamp does not move
  }
}

TEST_CASE("LightSet chooses lights in proportion to pi x area x luminance") {
  const rtdr::Scene scene = two_lamps_and_a_floor();
  const rtdr::LightSet lights(scene, scene.pose(0.5));
  REQUIRE(lights.lights().size() == 4);

  SECTION("selection frequencies over 4 x 200000 stratified u_select") {
    // u_select = (k + 1/2) / N covers [0, 1) evenly, so the count of light l differs from N pmf_l by at
    // most one per boundary of its interval: the check measures the table, not Monte Carlo noise.
    constexpr int kN = 4 * 200000;
    std::array<int, 4> count{};
    int out_of_range = 0;
    for (int k = 0; k < kN; ++k) {
      const rtdr::LightSample s = lights.sample(float((k + 0.5) / kN), glm::vec2(0.25f, 0.5f));
      if (s.light < 0 || s.light >= 4)
        ++out_of_range;
      else
        ++count[size_t(s.light)];
    }
    CHECK(out_of_range == 0);
    for (size_t l = 0; l < 4; ++l) {
      INFO("light " << l << ": frequency " << double(count[l]) / kN << ", expected pmf " << kPmf[l]);
      CHECK(double(count[l]) / kN == Approx(kPmf[l]).epsilon(0.01));
    }
  }
  SECTION("pdf_area = pmf / area, from pdf_area() and from sample()") {
    for (size_t l = 0; l < 4; ++l) {
      const rtdr::EmissiveTriangle& e = lights.lights()[l];
      const double expected = kPmf[l] / kArea[l];  // 0.2208 per m^2 on the small lamp, 0.1948 on the big one
      INFO("light " << l);
      CHECK(lights.pdf_area(e.instance, e.triangle) == Approx(expected).epsilon(1e-5));
      const rtdr::LightSample s = lights.sample(u_select_of_light(l), glm::vec2(0.3f, 0.6f));
      CHECK(s.light == int(l));
      CHECK(s.pdf_area == Approx(expected).epsilon(1e-5));
      CHECK(s.normal == e.normal);
      CHECK(s.radiance == e.radiance);
    }
  }
  SECTION("the ends of [0, 1) pick the first and the last light") {
    CHECK(lights.sample(0.0f, glm::vec2(0.5f)).light == 0);
    CHECK(lights.sample(0x1.fffffep-1f, glm::vec2(0.5f)).light == 3);  // the largest float below 1
  }
}

TEST_CASE("LightSet samples points uniformly inside the chosen triangle") {
  // 1000000 points per light from std::mt19937. For a uniform point the fraction in the middle
  // sub-triangle (vertices at the edge midpoints, every barycentric <= 1/2) is its area share 1/4, with
  // standard deviation sqrt(1/4 x 3/4 / 10^6) = 0.00043, so 1% of 1/4 (0.0025) is 5.8 sigma. The mean
  // point is the centroid; its error per axis is below edge / sqrt(12 x 10^6), far inside 1% of an edge.
  const rtdr::Scene scene = two_lamps_and_a_floor();
  const rtdr::LightSet lights(scene, scene.pose(0.5));
  REQUIRE(lights.lights().size() == 4);
  std::mt19937 rng(1997);
  const auto uniform01 = [&rng] { return float(rng() >> 8) * 0x1p-24f; };  // 24 random bits, never 1
  constexpr int kPoints = 1000000;
  for (size_t l = 0; l < 4; ++l) {
    const rtdr::EmissiveTriangle& e = lights.lights()[l];
    const glm::dvec3 a(e.p0), b(e.p1), c(e.p2);
    const double edge = std::max({glm::length(b - a), glm::length(c - b), glm::length(a - c)});
    glm::dvec3 sum(0.0);
    int outside = 0, in_middle = 0;
    for (int i = 0; i < kPoints; ++i) {
      const rtdr::LightSample s = lights.sample(u_select_of_light(l), glm::vec2(uniform01(), uniform01()));
      const glm::dvec3 p(s.position);
      const glm::dvec3 bary = barycentric(p, a, b, c);
      const double off_plane = std::abs(glm::dot(p - a, glm::dvec3(e.normal)));
      if (bary.x < -1e-6 || bary.y < -1e-6 || bary.z < -1e-6 || off_plane > 1e-5 * edge) ++outside;
      if (bary.x <= 0.5 && bary.y <= 0.5 && bary.z <= 0.5) ++in_middle;
      sum += p;
    }
    const glm::dvec3 centroid = (a + b + c) / 3.0;
    INFO("light " << l << ": mean point off the centroid by " << glm::length(sum / double(kPoints) - centroid)
                  << ", fraction in the middle sub-triangle " << double(in_middle) / kPoints);
    CHECK(outside == 0);
    CHECK(glm::length(sum / double(kPoints) - centroid) < 0.01 * edge);
    CHECK(double(in_middle) / kPoints == Approx(0.25).epsilon(0.01));
  }
}

// sample_reusing(u) is sample(u.x, (r, u.y)) with r = (u.x - cdf before the light) / the light's pmf: the same
// light, and a point placed by u.x's position inside that light's share, rescaled to [0, 1). Compared with the
// test's own pmf (in double), so only float rounding of the cdf separates them: 1e-5 of the lamps' metre scale.
TEST_CASE("LightSet::sample_reusing chooses as sample does and reuses u.x inside the light's share") {
  const rtdr::Scene scene = two_lamps_and_a_floor();
  const rtdr::LightSet lights(scene, scene.pose(0.5));
  REQUIRE(lights.lights().size() == 4);
  std::array<double, 4> smallest_r, largest_r;
  smallest_r.fill(1.0);
  largest_r.fill(0.0);
  constexpr int kSteps = 4096;
  for (int k = 0; k < kSteps; ++k) {
    const glm::vec2 u((float(k) + 0.5f) / kSteps, 0.3f);
    const rtdr::LightSample reused = lights.sample_reusing(u);
    const size_t l = size_t(reused.light);
    REQUIRE(l < 4);
    double before = 0.0;
    for (size_t m = 0; m < l; ++m) before += kPmf[m];
    const double r = (double(u.x) - before) / kPmf[l];
    INFO("u.x = " << u.x << ", light " << l << ", r = " << r);
    CHECK(reused.light == lights.sample(u.x, glm::vec2(0.5f)).light);
    CHECK(glm::length(reused.position - lights.sample(u.x, glm::vec2(float(r), u.y)).position) < 1e-5f);
    smallest_r[l] = std::min(smallest_r[l], r);
    largest_r[l] = std::max(largest_r[l], r);
  }
  for (size_t l = 0; l < 4; ++l) {  // every light's share is rescaled onto the whole of [0, 1)
    INFO("light " << l);
    CHECK(smallest_r[l] < 0.01);
    CHECK(largest_r[l] > 0.99);
    CHECK(largest_r[l] < 1.0);
  }
}

TEST_CASE("LightSet::find maps (instance, triangle) to the light, and anything else to -1") {
  const rtdr::Scene scene = two_lamps_and_a_floor();
  const rtdr::LightSet lights(scene, scene.pose(0.5));
  CHECK(lights.find(1, 0) == 0);  // small lamp
  CHECK(lights.find(1, 1) == 1);
  CHECK(lights.find(2, 0) == 2);  // big lamp
  CHECK(lights.find(2, 1) == 3);
  CHECK(lights.find(0, 0) == -1);  // the floor is not a light
  CHECK(lights.find(0, 1) == -1);
  CHECK(lights.pdf_area(0, 0) == 0.0f);
  CHECK(lights.find(1, 2) == -1);           // a quad has no triangle 2
  CHECK(lights.find(3, 0) == -1);           // there is no instance 3
  CHECK(lights.find(0xFFFFFFFFu, 0) == -1);  // kInvalidId: a ray that hit nothing
  // Triangle ids of 2^31 and more (kInvalidId = 0xFFFFFFFF) must not wrap to negative indices: this once
  // returned first + (-1), the small lamp's second triangle.
  CHECK(lights.find(2, 0xFFFFFFFFu) == -1);
  CHECK(lights.pdf_area(2, 0xFFFFFFFFu) == 0.0f);
}

TEST_CASE("LightSet follows an animated emissive strength") {
  rtdr::Scene scene = flickering_and_steady_lamps();

  SECTION("at t = 0.5 the track is half way from 4 to 0: Le = 2, and the flickering lamp is a light") {
    const rtdr::LightSet lights(scene, scene.pose(0.5));
    REQUIRE(lights.lights().size() == 4);
    check_vertex(lights.lights()[0].radiance, {2.0f, 2.0f, 2.0f});
    check_vertex(lights.lights()[2].radiance, {1.0f, 1.0f, 1.0f});
    // Equal areas, luminance 2 against 1: the flickering lamp's triangles carry 2/3 of the power.
    CHECK(lights.pdf_area(0, 0) == Approx((1.0 / 3.0) / 0.5).epsilon(1e-5));
  }
  SECTION("at t = 1 the strength is 0: only the steady lamp is left") {
    const rtdr::LightSet lights(scene, scene.pose(1.0));
    REQUIRE(lights.lights().size() == 2);
    CHECK(lights.lights()[0].instance == 1u);
    CHECK(lights.lights()[1].instance == 1u);
    CHECK(lights.find(0, 0) == -1);
    CHECK(lights.pdf_area(0, 0) == 0.0f);
    CHECK(lights.find(1, 0) == 0);
    CHECK(lights.pdf_area(1, 0) == Approx(0.5 / 0.5).epsilon(1e-5));  // pmf 1/2 over area 1/2
  }
  SECTION("with the steady lamp removed, the scene at t = 1 has no lights at all") {
    scene.instances.pop_back();
    CHECK(rtdr::LightSet(scene, scene.pose(1.0)).empty());
    CHECK_FALSE(rtdr::LightSet(scene, scene.pose(0.0)).empty());
  }
}

TEST_CASE("LightSet with a choice pose chooses by that pose's powers and shades with this pose's radiance") {
  // flickering_and_steady_lamps(), with the flickering lamp also moving 1 m along x from t = 0 to 1, so that its
  // geometry comes from the shaded pose.
  rtdr::Scene scene = flickering_and_steady_lamps();
  rtdr::Node& lamp = scene.nodes[size_t(scene.instances[0].node)];
  lamp.translation_track.times = {0.0f, 1.0f};
  lamp.translation_track.values = {glm::vec3(0.0f, 2.0f, 0.0f), glm::vec3(1.0f, 2.0f, 0.0f)};

  SECTION("choosing by the pose itself is the ordinary set, bit for bit") {
    const rtdr::ScenePose pose = scene.pose(0.5);
    const rtdr::LightSet plain(scene, pose), chosen(scene, pose, pose);
    REQUIRE(plain.lights().size() == chosen.lights().size());
    for (uint32_t t = 0; t < 2; ++t)
      for (uint32_t i = 0; i < 2; ++i) CHECK(plain.pdf_area(i, t) == chosen.pdf_area(i, t));
    for (float u : {0.1f, 0.4f, 0.7f, 0.95f}) CHECK(plain.sample(u, {0.3f, 0.6f}).light == chosen.sample(u, {0.3f, 0.6f}).light);
  }
  SECTION("shaded at t = 1 (the lamp off) and chosen at t = 0 (Le 4 against 1): the lamp stays a light of Le 0") {
    const rtdr::LightSet lights(scene, scene.pose(1.0), scene.pose(0.0));
    REQUIRE(lights.lights().size() == 4);
    check_vertex(lights.lights()[0].radiance, {0.0f, 0.0f, 0.0f});
    check_vertex(lights.lights()[2].radiance, {1.0f, 1.0f, 1.0f});
    // Powers at t = 0: 4 against 1 over equal areas, so the lamp's two triangles carry 4/5, 2/5 each.
    CHECK(lights.pdf_area(0, 0) == Approx((2.0 / 5.0) / 0.5).epsilon(1e-5));
    CHECK(lights.pdf_area(1, 1) == Approx((1.0 / 10.0) / 0.5).epsilon(1e-5));
    // Its triangles are where the lamp is at t = 1, 1 m along x from t = 0.
    const rtdr::LightSet at_zero(scene, scene.pose(0.0));
    CHECK(lights.lights()[0].p0.x == Approx(at_zero.lights()[0].p0.x + 1.0f).margin(1e-6));
  }
  SECTION("shaded at t = 0 and chosen at t = 1, when the lamp was off: it is never chosen, nor weighted") {
    const rtdr::LightSet lights(scene, scene.pose(0.0), scene.pose(1.0));
    REQUIRE(lights.lights().size() == 4);
    CHECK(lights.pdf_area(0, 0) == 0.0f);  // so a BSDF ray that hits it has MIS weight 1
    CHECK(lights.pdf_area(1, 0) == Approx(0.5 / 0.5).epsilon(1e-5));
    for (float u = 0.0f; u < 1.0f; u += 0.0625f) CHECK(lights.lights()[size_t(lights.sample(u, {0.5f, 0.5f}).light)].instance == 1u);
  }
}

TEST_CASE("A scene without emitters gives an empty LightSet") {
  rtdr::Scene scene = rtdr::test::camera_scene();
  rtdr::Material grey;
  grey.base_color = glm::vec4(0.5f, 0.5f, 0.5f, 1.0f);
  rtdr::test::add_quad(scene, 4.0f, glm::vec3(0.0f), about_x(-90.0f), rtdr::test::add_material(scene, grey));
  rtdr::test::add_quad(scene, 1.0f, glm::vec3(0.0f, 1.0f, 0.0f));  // material -1: glTF's default, not emissive
  const rtdr::LightSet lights(scene, scene.pose(0.0));
  CHECK(lights.empty());
  CHECK(lights.lights().empty());
  CHECK(lights.find(0, 0) == -1);
  CHECK(lights.pdf_area(1, 0) == 0.0f);
  CHECK(rtdr::LightSet().empty());  // the default-constructed set, too
}
