// Tests of motion/backproject.cpp: motion vectors [TRMV21 Eq. 1] against analytically moved points.
#include "motion/backproject.h"

#include "core/error.h"
#include "scene_fixtures.h"

#include <catch2/catch.hpp>

#include <glm/gtc/matrix_transform.hpp>

#include <cmath>

using namespace rtdr;
using namespace rtdr::test;

namespace {

// For every covered current pixel: the surface point hit by its centre ray (analytic, current pose),
// moved by `cur_to_prev` (the inverse of the object's motion), projected by the previous camera with the
// pinhole model. Returns the largest distance to centre + motion, in pixels.
double max_motion_error(const Scene& s, const ScenePose& cur, const View& cur_view, const ScenePose& prev,
                        const View& prev_view, const glm::dmat4& cur_to_prev, int* covered) {
  const VisibilityBuffer vis = rasterize(s, cur, cur_view);
  const std::vector<glm::vec2> motion = backproject_motion(s, prev, prev_view, vis);
  double max_error = 0.0;
  *covered = 0;
  for (int y = 0; y < vis.height; ++y)
    for (int x = 0; x < vis.width; ++x) {
      const size_t i = vis.index(x, y);
      if (vis.instance[i] == kInvalidId) {
        CHECK(motion[i] == glm::vec2(0.0f));
        continue;
      }
      ++*covered;
      const auto tri = world_triangle(s, cur, int(vis.instance[i]), int(vis.triangle[i]));
      glm::dvec3 o, d;
      pixel_ray(cur_view, {x + 0.5, y + 0.5}, o, d);
      const glm::dvec3 hit = o + intersect_plane(o, d, tri[0], tri[1], tri[2])->t * d;
      const glm::dvec3 prev_point = glm::dvec3(cur_to_prev * glm::dvec4(hit, 1.0));
      const glm::dvec2 expected_prev = glm::dvec2(pinhole_project(prev_view, prev_point));
      const glm::dvec2 got_prev = glm::dvec2(x + 0.5, y + 0.5) + glm::dvec2(motion[i]);  // x_{i-1} = x_i + m
      max_error = std::max(max_error, glm::length(got_prev - expected_prev));
    }
  return max_error;
}

Scene quad_scene() {
  Scene s = camera_scene();
  add_quad(s, 2.0f, {0.0f, 0.0f, -4.0f}, glm::angleAxis(0.5f, glm::normalize(glm::vec3(1.0f, 0.4f, 0.0f))));
  return s;
}

}  // namespace

TEST_CASE("motion of a translated object lands on the analytic previous pixel") {
  const Scene s = quad_scene();
  const ScenePose cur = s.pose(0.0);
  ScenePose prev = cur;
  const glm::dvec3 shift(0.3, -0.2, 0.5);  // the object moved by -shift from prev to cur
  set_instance_transform(prev, 0, glm::translate(glm::mat4(1.0f), glm::vec3(shift)) * cur.instance_to_world[0]);
  const View view = make_view(s, cur, 80, 60);
  int covered = 0;
  const double err = max_motion_error(s, cur, view, prev, view, glm::translate(glm::dmat4(1.0), shift), &covered);
  CHECK(covered > 500);
  CHECK(err < 1e-3);
}

TEST_CASE("motion of a rotated object lands on the analytic previous pixel") {
  const Scene s = quad_scene();
  const ScenePose cur = s.pose(0.0);
  ScenePose prev = cur;
  // prev = R * cur about the quad's centre: the previous point is R applied to the current one.
  const glm::dvec3 centre(0.0, 0.0, -4.0);
  const glm::dmat4 rotate_about_centre = glm::translate(glm::dmat4(1.0), centre) *
                                         glm::rotate(glm::dmat4(1.0), 0.2, glm::dvec3(0.0, 1.0, 0.3)) *
                                         glm::translate(glm::dmat4(1.0), -centre);
  set_instance_transform(prev, 0, glm::mat4(rotate_about_centre) * cur.instance_to_world[0]);
  const View view = make_view(s, cur, 80, 60);
  int covered = 0;
  const double err = max_motion_error(s, cur, view, prev, view, rotate_about_centre, &covered);
  CHECK(covered > 500);
  CHECK(err < 1e-3);
}

TEST_CASE("camera motion alone: a static object's motion follows the previous camera") {
  Scene s = quad_scene();
  // The camera node moves and turns between the two times (an animation track on the camera node).
  s.nodes[0].translation_track.times = {0.0f, 1.0f};
  s.nodes[0].translation_track.values = {glm::vec3(0.4f, 0.1f, 0.3f), glm::vec3(0.0f)};
  s.nodes[0].rotation_track.times = {0.0f, 1.0f};
  s.nodes[0].rotation_track.values = {glm::angleAxis(0.1f, glm::vec3(0, 1, 0)), glm::quat(1, 0, 0, 0)};
  const ScenePose prev = s.pose(0.0), cur = s.pose(1.0);
  const View prev_view = make_view(s, prev, 80, 60), cur_view = make_view(s, cur, 80, 60);
  REQUIRE(prev_view.eye != cur_view.eye);
  int covered = 0;
  const double err = max_motion_error(s, cur, cur_view, prev, prev_view, glm::dmat4(1.0), &covered);
  CHECK(covered > 500);
  CHECK(err < 1e-3);
}

TEST_CASE("sign convention, points behind the previous camera, write_motion") {
  const Scene s = quad_scene();
  const ScenePose cur = s.pose(0.0);
  const View view = make_view(s, cur, 40, 30);
  const VisibilityBuffer vis = rasterize(s, cur, view);
  // The object was 0.5 to the right (+x world = +x screen) in the previous frame: motion.x > 0.
  ScenePose prev = cur;
  set_instance_transform(prev, 0, glm::translate(glm::mat4(1.0f), {0.5f, 0.0f, 0.0f}) * cur.instance_to_world[0]);
  const std::vector<glm::vec2> right = backproject_motion(s, prev, view, vis);
  const size_t centre = vis.index(20, 15);
  REQUIRE(vis.instance[centre] == 0);
  CHECK(right[centre].x > 1.0f);
  CHECK(std::abs(right[centre].y) < 0.5f);
  // Previously behind the camera: the previous position is pushed far off screen.
  set_instance_transform(prev, 0, glm::translate(glm::mat4(1.0f), {0.0f, 0.0f, 8.0f}) * cur.instance_to_world[0]);
  const std::vector<glm::vec2> behind = backproject_motion(s, prev, view, vis);
  CHECK(behind[centre] == glm::vec2(kMotionBehindCamera));
  // No motion without motion; background 0.
  const std::vector<glm::vec2> still = backproject_motion(s, cur, view, vis);
  CHECK(glm::length(still[centre]) < 1e-3f);
  CHECK(still[0] == glm::vec2(0.0f));

  Frame frame(40, 30);
  write_motion(right, frame);
  CHECK(frame.float_channel("motion.X").data[centre] == right[centre].x);
  CHECK(frame.float_channel("motion.Y").data[centre] == right[centre].y);
  Frame wrong(10, 10);
  CHECK_THROWS_AS(write_motion(right, wrong), Error);
}
