// Tests of motion/dual.cpp: the dual motion vector [TRMV21 Eq. 6] on the occlusion scene, whose boxes translate
// by known steps (scenes/README.md), against x^O = y + (x_i - z) computed from those steps; where x^O lands in
// the previous frame; and the pixels that keep their surface motion.
#include "motion/dual.h"

#include "motion/backproject.h"
#include "scenes/gltf_loader.h"

#include <catch2/catch.hpp>

#include <cmath>
#include <cstdio>
#include <map>
#include <string>
#include <vector>

using namespace rtdr;

namespace {

// One frame's geometry and its back-projected motion, as `rtdr render` makes them (no path tracing needed).
struct MotionFrame {
  FrameGeometry geometry;
  std::vector<glm::vec2> motion;
  std::vector<DualMotion> dual;
};

MotionFrame motion_frame(const Scene& scene, int index, int width, int height) {
  MotionFrame f{rasterize_frame(scene, index, width, height), {}, {}};
  f.motion = backproject_motion(scene, f.geometry.prev_pose, f.geometry.prev_view, f.geometry.vis);
  f.dual = dual_motion(scene, f.geometry, f.motion);
  return f;
}

int instance_named(const Scene& scene, const std::string& name) {
  for (size_t k = 0; k < scene.instances.size(); ++k)
    if (scene.instances[k].name == name) return int(k);
  FAIL("no instance " << name);
  return -1;
}

}  // namespace

TEST_CASE("occlusion: a disoccluded pixel's x^O is y + (x_i - z) from its occluder's known step, and lies off that occluder") {
  const Scene scene = load_scene("occlusion");
  // The boxes' steps per frame (scenes/README.md): orange 2 m/s along +X, blue 5/3 m/s along -X, at 30 fps.
  const std::map<int, glm::vec3> step = {{instance_named(scene, "tall_box"), {2.0f / 30.0f, 0.0f, 0.0f}},
                                         {instance_named(scene, "cube"), {-5.0f / 90.0f, 0.0f, 0.0f}}};
  const MotionFrame f = motion_frame(scene, 40, 160, 90);
  const FrameGeometry& g = f.geometry;
  const VisibilityBuffer prev_vis = previous_visibility(scene, g);
  // The previous frame at 8x the resolution: x^O is a continuous position just past the occluder's edge, so
  // whether it lies on the occluder is read at 1/8 pixel, not at the pixel centre of floor(x^O).
  constexpr int kFine = 8;
  const View fine_view = make_view(scene, g.prev_pose, kFine * g.vis.width, kFine * g.vis.height);
  const VisibilityBuffer fine_prev = rasterize(scene, g.prev_pose, fine_view);
  int disoccluded = 0, kept = 0, inside_edge = 0;
  double sum_length = 0.0;
  for (int y = 0; y < g.vis.height; ++y)
    for (int x = 0; x < g.vis.width; ++x) {
      const size_t i = g.vis.index(x, y);
      const DualMotion& d = f.dual[i];
      if (!d.disoccluded) {  // everywhere else x^O = y, bit for bit
        CHECK(d.motion == f.motion[i]);
        ++kept;
        continue;
      }
      // y, the occluder's sample there, and its known step d_k.
      const glm::vec2 x_i = glm::vec2(float(x), float(y)) + 0.5f;
      const glm::vec2 y_prev = x_i + f.motion[i];
      const SurfaceSample occluder = prev_vis.sample(int(std::floor(y_prev.x)), int(std::floor(y_prev.y)));
      INFO("pixel (" << x << ", " << y << "), occluder " << scene.instances[occluder.instance].name);
      REQUIRE(step.count(int(occluder.instance)));  // only the boxes move, so only they uncover anything
      const glm::vec3 d_k = step.at(int(occluder.instance));
      const glm::vec3 moved = glm::vec3(g.pose.instance_to_world[occluder.instance][3] -
                                        g.prev_pose.instance_to_world[occluder.instance][3]);
      REQUIRE(glm::length(moved - d_k) < 1e-5f);  // the scene moves the box as the README says
      // z: the occluder's point one step on, seen now; y': where it was [TRMV21 Eq. 6].
      const glm::vec3 p_prev = world_point(scene, g.prev_pose, occluder);
      const glm::vec2 z = glm::vec2(g.view.project(p_prev + d_k));
      const glm::vec2 y_occluder = glm::vec2(g.prev_view.project(p_prev));
      const glm::vec2 expected = y_prev + (y_occluder - z) - x_i;
      CHECK(glm::length(d.motion - expected) < 1e-3f);
      // In frame i-1, x^O is not on the box that uncovered the pixel (or is off screen).
      const glm::vec2 x_o = x_i + d.motion;
      // Under a rigid screen translation by v this is exact: x is uncovered now, so x - v was not on the box
      // then. The box's v varies over it with depth (perspective) and is read at y', so allow x^O to sit up
      // to 1/4 pixel inside the edge, and count those.
      const int ox = int(std::floor(kFine * x_o.x)), oy = int(std::floor(kFine * x_o.y));
      const auto on_occluder = [&](int fx, int fy) {
        return fx >= 0 && fy >= 0 && fx < fine_prev.width && fy < fine_prev.height &&
               fine_prev.instance[fine_prev.index(fx, fy)] == occluder.instance;
      };
      if (on_occluder(ox, oy)) {
        bool near_edge = false;
        for (int dy = -2; dy <= 2; ++dy)
          for (int dx = -2; dx <= 2; ++dx) near_edge = near_edge || !on_occluder(ox + dx, oy + dy);
        CHECK(near_edge);
        ++inside_edge;
      }
      // The pixel itself was hidden: it sees something other than its occluder now.
      CHECK(g.vis.instance[i] != occluder.instance);
      sum_length += glm::length(d.motion - f.motion[i]);
      ++disoccluded;
    }
  const double mean_shift = sum_length / std::max(disoccluded, 1);
  std::printf("occlusion frame 40, 160x90: %d disoccluded pixels (x^O within 1/4 px inside the occluder's edge at %d), "
              "%d keep the surface motion, mean |x^O - y| %.3f px\n", disoccluded, inside_edge, kept, mean_shift);
  // The orange box moves about 1.6 px per frame at this size and is 1.6 m (about 27 px) tall: a band of
  // roughly 30-50 pixels behind it, plus the blue cube's.
  CHECK(disoccluded > 20);
  CHECK(mean_shift > 0.5);
  CHECK(inside_edge * 10 < disoccluded);
}

TEST_CASE("a static scene has no disocclusions: x^O equals the surface motion everywhere") {
  const Scene scene = load_scene("static");
  const MotionFrame f = motion_frame(scene, 3, 96, 54);
  for (size_t i = 0; i < f.dual.size(); ++i) {
    CHECK_FALSE(f.dual[i].disoccluded);
    CHECK(f.dual[i].motion == f.motion[i]);
  }
}

TEST_CASE("the dual motion layers are written beside the surface motion, and a wrong-sized motion is refused") {
  const Scene scene = load_scene("occlusion");
  const FrameGeometry g = rasterize_frame(scene, 40, 64, 36);
  Frame frame(64, 36);
  write_motion_layers(scene, g, frame);
  write_dual_motion_layers(scene, g, frame);
  const std::vector<glm::vec2> dual = frame.get_vec2("motion.dual"), motion = frame.get_vec2("motion");
  const UIntPlane& valid = frame.uint_channel("motion.dual.valid");
  const std::vector<DualMotion> direct = dual_motion(scene, g, motion);
  int landed = 0;
  for (size_t i = 0; i < dual.size(); ++i) {
    CHECK(dual[i] == direct[i].motion);
    CHECK(valid.data[i] == (direct[i].disoccluded ? 1u : 0u));
    landed += int(valid.data[i]);
  }
  CHECK(landed > 0);
  CHECK_THROWS_WITH(dual_motion(scene, g, std::vector<glm::vec2>(10)),
                    "dual_motion: 10 motion vectors for a 64x36 frame");
}
