// Tests of motion/forward_project.cpp [ASVGF18 Sec. 3.1, 3.3]: exact re-projection of a sample, the round
// trip with back-projection on a moving object, occlusion against the current depth, off-screen samples.
#include "motion/forward_project.h"

#include "motion/backproject.h"
#include "scene_fixtures.h"

#include <catch2/catch.hpp>

#include <glm/gtc/matrix_transform.hpp>

#include <cmath>

using namespace rtdr;
using namespace rtdr::test;

namespace {

// A quad that moves, turns and comes closer between t = 0 (previous) and t = 1 (current).
Scene moving_quad_scene() {
  Scene s = camera_scene();
  const int i = add_quad(s, 2.0f, {0.0f, 0.0f, 0.0f});
  Node& node = s.nodes[size_t(s.instances[size_t(i)].node)];
  node.translation_track.times = {0.0f, 1.0f};
  node.translation_track.values = {glm::vec3(-0.3f, 0.1f, -4.0f), glm::vec3(0.2f, -0.1f, -3.6f)};
  node.rotation_track.times = {0.0f, 1.0f};
  node.rotation_track.values = {glm::angleAxis(0.3f, glm::vec3(0, 1, 0)), glm::angleAxis(0.5f, glm::vec3(0.2f, 1, 0))};
  return s;
}

}  // namespace

TEST_CASE("forward projecting a current sample at the current pose returns its own pixel centre") {
  const Scene s = moving_quad_scene();
  const ScenePose cur = s.pose(1.0);
  const View view = make_view(s, cur, 64, 48, {0.25f, -0.125f});  // jitter: the same View rasterizes and projects
  const VisibilityBuffer vis = rasterize(s, cur, view);
  double max_error = 0.0;
  int covered = 0;
  for (int y = 0; y < vis.height; ++y)
    for (int x = 0; x < vis.width; ++x) {
      const SurfaceSample sample = vis.sample(x, y);
      if (!sample.valid()) continue;
      ++covered;
      const ForwardProjection f = forward_project(s, cur, view, vis, sample);
      CHECK(f.on_screen);
      CHECK(f.pixel == glm::ivec2(x, y));
      CHECK_FALSE(f.occluded);
      CHECK(f.depth == Approx(vis.depth[vis.index(x, y)]).epsilon(1e-5));
      max_error = std::max(max_error, double(glm::length(f.screen - glm::vec2(x + 0.5f, y + 0.5f))));
    }
  CHECK(covered > 300);
  CHECK(max_error < 1e-3);
}

TEST_CASE("back-projection then forward projection of the previous sample found there round-trips") {
  const Scene s = moving_quad_scene();
  const ScenePose prev = s.pose(0.0), cur = s.pose(1.0);
  const View prev_view = make_view(s, prev, 64, 48), cur_view = make_view(s, cur, 64, 48);
  const VisibilityBuffer prev_vis = rasterize(s, prev, prev_view), cur_vis = rasterize(s, cur, cur_view);
  const std::vector<glm::vec2> motion = backproject_motion(s, prev, prev_view, cur_vis);
  double max_round_trip = 0.0, max_exact = 0.0;
  int checked = 0;
  for (int y = 0; y < cur_vis.height; ++y)
    for (int x = 0; x < cur_vis.width; ++x) {
      if (!cur_vis.sample(x, y).valid()) continue;
      // Where the current pixel's surface was: p + m, and the previous visibility sample there.
      const glm::vec2 start(x + 0.5f, y + 0.5f);
      const glm::vec2 prev_pos = start + motion[cur_vis.index(x, y)];
      const glm::ivec2 q = glm::ivec2(glm::floor(prev_pos));
      if (q.x < 0 || q.y < 0 || q.x >= prev_vis.width || q.y >= prev_vis.height) continue;
      const SurfaceSample prev_sample = prev_vis.sample(q.x, q.y);
      if (!prev_sample.valid()) continue;  // the silhouette's sub-pixel fringe
      ++checked;
      // Forward: the previous sample lands within about a pixel of where we started.
      const ForwardProjection f = forward_project(s, cur, cur_view, cur_vis, prev_sample);
      REQUIRE(f.on_screen);
      CHECK_FALSE(f.occluded);
      max_round_trip = std::max(max_round_trip, double(glm::length(f.screen - start)));
      // The same sample exactly: back-projecting it from where it landed returns to its previous centre.
      const glm::vec2 m = backproject_pixel(s, prev, prev_view, prev_sample, f.screen);
      max_exact = std::max(max_exact, double(glm::length(f.screen + m - (glm::vec2(q) + 0.5f))));
    }
  CHECK(checked > 300);
  CHECK(max_round_trip < 1.0);
  CHECK(max_exact < 1e-3);
}

TEST_CASE("a sample hidden by a nearer object in the current frame is reported occluded") {
  Scene s = camera_scene();
  add_quad(s, 4.0f, {0.0f, 0.0f, -4.0f});                  // instance 0: the wall
  const int blocker = add_quad(s, 0.6f, {0.0f, 0.0f, -2.0f});  // instance 1: moves in front of the wall
  s.nodes[size_t(s.instances[size_t(blocker)].node)].translation_track.times = {0.0f, 1.0f};
  s.nodes[size_t(s.instances[size_t(blocker)].node)].translation_track.values = {glm::vec3(5.0f, 0.0f, -2.0f),
                                                                               glm::vec3(0.0f, 0.0f, -2.0f)};
  const ScenePose prev = s.pose(0.0), cur = s.pose(1.0);
  const View view = make_view(s, prev, 64, 48);
  const VisibilityBuffer prev_vis = rasterize(s, prev, view), cur_vis = rasterize(s, cur, view);
  REQUIRE(prev_vis.instance[prev_vis.index(32, 24)] == 0);
  REQUIRE(cur_vis.instance[cur_vis.index(32, 24)] == uint32_t(blocker));
  const ForwardProjection hidden = forward_project(s, cur, view, cur_vis, prev_vis.sample(32, 24));
  CHECK(hidden.on_screen);
  CHECK(hidden.pixel == glm::ivec2(32, 24));
  CHECK(hidden.occluded);
  CHECK(hidden.depth == Approx(4.0f));
  const ForwardProjection visible = forward_project(s, cur, view, cur_vis, prev_vis.sample(4, 4));
  CHECK(visible.on_screen);
  CHECK_FALSE(visible.occluded);

  // A blocker only 0.5 % nearer is within the default 1 % tolerance, but not within 0.1 %.
  ScenePose close = cur;
  set_instance_transform(close, blocker, glm::translate(glm::mat4(1.0f), {0.0f, 0.0f, -3.98f}));
  const VisibilityBuffer close_vis = rasterize(s, close, view);
  REQUIRE(close_vis.instance[close_vis.index(32, 24)] == uint32_t(blocker));
  CHECK_FALSE(forward_project(s, close, view, close_vis, prev_vis.sample(32, 24)).occluded);
  CHECK(forward_project(s, close, view, close_vis, prev_vis.sample(32, 24), 0.001f).occluded);
}

TEST_CASE("samples that leave the screen, go behind the camera or lie far off (damaged barycentrics) are off screen") {
  Scene s = camera_scene();
  add_quad(s, 1.0f, {0.0f, 0.0f, -4.0f});
  const ScenePose prev = s.pose(0.0);
  const View view = make_view(s, prev, 32, 24);
  const VisibilityBuffer prev_vis = rasterize(s, prev, view);
  const SurfaceSample sample = prev_vis.sample(16, 12);
  REQUIRE(sample.valid());
  for (const glm::vec3 moved : {glm::vec3(20.0f, 0.0f, -4.0f), glm::vec3(0.0f, -20.0f, -4.0f), glm::vec3(0.0f, 0.0f, 3.0f)}) {
    ScenePose cur = prev;
    set_instance_transform(cur, 0, glm::translate(glm::mat4(1.0f), moved));
    const VisibilityBuffer cur_vis = rasterize(s, cur, view);
    const ForwardProjection f = forward_project(s, cur, view, cur_vis, sample);
    CHECK_FALSE(f.on_screen);
    CHECK(f.pixel == glm::ivec2(-1, -1));
    CHECK_FALSE(f.occluded);
  }
  // Frame i-1 of render --gradients comes from a file: its barycentrics can be anything, finite or not. The point
  // they name projects to a huge, infinite or NaN position, which must be off screen before it becomes an int.
  CHECK(forward_project(s, prev, view, prev_vis, sample).on_screen);  // control: as rendered
  for (const glm::vec2 bary : {glm::vec2(1e30f, 0.0f), glm::vec2(0.0f, -1e20f), glm::vec2(3e38f, 3e38f),
                               glm::vec2(NAN, 0.0f), glm::vec2(0.0f, INFINITY)}) {
    INFO(bary.x << ", " << bary.y);
    SurfaceSample damaged = sample;
    damaged.bary = bary;
    const ForwardProjection f = forward_project(s, prev, view, prev_vis, damaged);
    CHECK_FALSE(f.on_screen);
    CHECK(f.pixel == glm::ivec2(-1, -1));
  }
}
