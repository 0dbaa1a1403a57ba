// Tests of raster/view.cpp: pixel conventions, projection, rays and jitter against the pinhole model.
#include "raster/view.h"

#include "scene_fixtures.h"

#include <catch2/catch.hpp>

#include <glm/gtc/matrix_transform.hpp>

#include <cmath>

using namespace rtdr;
using namespace rtdr::test;

TEST_CASE("make_view: field of view, aspect and the optical axis through the image centre") {
  Scene s = camera_scene(glm::vec3(0.0f), glm::quat(1, 0, 0, 0), 0.8f, 0.1f);
  const View v = make_view(s, s.pose(0.0), 64, 32);
  CHECK(v.tan_half_fov_y == Approx(std::tan(0.4f)));
  CHECK(v.tan_half_fov_x == Approx(2.0f * std::tan(0.4f)));  // aspect 2
  CHECK(v.znear == 0.1f);
  const glm::vec3 p = v.project({0.0f, 0.0f, -5.0f});
  CHECK(p.x == Approx(32.0f));
  CHECK(p.y == Approx(16.0f));
  CHECK(p.z == Approx(5.0f));  // linear depth
  // The top edge of the frustum at depth 1 is screen y = 0 (y grows down); the right edge is x = width.
  const glm::vec3 top_right = v.project({v.tan_half_fov_x, v.tan_half_fov_y, -1.0f});
  CHECK(top_right.x == Approx(64.0f));
  CHECK(top_right.y == Approx(0.0f).margin(1e-4));
}

TEST_CASE("project agrees with the pinhole model for a rotated, translated camera") {
  const glm::quat rot = glm::angleAxis(0.6f, glm::normalize(glm::vec3(0.3f, 1.0f, 0.2f)));
  Scene s = camera_scene({1.0f, -2.0f, 3.0f}, rot, 0.9f, 0.05f);
  const View v = make_view(s, s.pose(0.0), 40, 30);
  double max_error = 0.0;
  for (const glm::vec3 local : {glm::vec3(0.5f, -0.2f, -3.0f), glm::vec3(-1.0f, 0.7f, -2.0f), glm::vec3(0, 0, -9.0f)}) {
    const glm::vec3 world = glm::vec3(v.view_to_world * glm::vec4(local, 1.0f));
    const glm::vec3 got = v.project(world);
    const glm::dvec3 want = pinhole_project(v, world);
    max_error = std::max({max_error, std::abs(got.x - want.x), std::abs(got.y - want.y), std::abs(got.z - want.z)});
    CHECK(want.z == Approx(-local.z));
  }
  CHECK(max_error < 1e-3);
}

TEST_CASE("ray_through and view_dir_at_unit_depth invert project, pixel centres at +0.5") {
  const glm::quat rot = glm::angleAxis(-0.4f, glm::vec3(1.0f, 0.0f, 0.0f));
  Scene s = camera_scene({0.0f, 1.0f, 2.0f}, rot);
  const View v = make_view(s, s.pose(0.0), 33, 17);
  for (const glm::vec2 screen : {glm::vec2(0.5f, 0.5f), glm::vec2(32.5f, 16.5f), glm::vec2(10.25f, 3.75f)}) {
    const Ray ray = v.ray_through(screen);
    CHECK(glm::length(ray.direction) == Approx(1.0f));
    const glm::vec3 hit = ray.origin + 4.0f * ray.direction;
    const glm::vec3 p = v.project(hit);
    CHECK(p.x == Approx(screen.x).margin(1e-3));
    CHECK(p.y == Approx(screen.y).margin(1e-3));
    // The view-space direction at unit depth scales to the point at any depth d.
    const glm::vec3 at_depth_3 = glm::vec3(v.view_to_world * glm::vec4(3.0f * v.view_dir_at_unit_depth(screen), 1.0f));
    const glm::vec3 q = v.project(at_depth_3);
    CHECK(q.x == Approx(screen.x).margin(1e-3));
    CHECK(q.y == Approx(screen.y).margin(1e-3));
    CHECK(q.z == Approx(3.0f));
  }
}

TEST_CASE("jitter moves the projected image by exactly the jitter, in pixels") {
  Scene s = camera_scene();
  const glm::vec2 jitter(0.25f, -0.375f);
  const View plain = make_view(s, s.pose(0.0), 64, 48);
  const View jittered = make_view(s, s.pose(0.0), 64, 48, jitter);
  const glm::vec3 world(0.3f, -0.2f, -2.5f);
  const glm::vec3 a = plain.project(world), b = jittered.project(world);
  CHECK(b.x - a.x == Approx(jitter.x).margin(1e-4));
  CHECK(b.y - a.y == Approx(jitter.y).margin(1e-4));
  CHECK(b.z == Approx(a.z));
  // The jittered ray through the jittered position is the plain ray through the plain position.
  const Ray r0 = plain.ray_through(glm::vec2(a)), r1 = jittered.ray_through(glm::vec2(b));
  CHECK(glm::length(r0.direction - r1.direction) < 1e-5f);
}
