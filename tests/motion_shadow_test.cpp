// Tests of motion/shadow.cpp: the shadow motion vector [TRMV21 Eq. 3] against closed forms of the shadow
// ray's own line (motion/shadow.h says why that line), its validity rules, and the static limit.
#include "motion/shadow.h"

#include "scene_fixtures.h"
#include "scenes/gltf_loader.h"
#include "trace/render_frame.h"

#include <catch2/catch.hpp>

#include <glm/gtc/matrix_transform.hpp>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

using namespace rtdr;
using namespace rtdr::test;

namespace {

// A frame of a shipped scene at 1 spp with its geometry, as `rtdr render` makes it.
struct RenderedFrame {
  FrameGeometry geometry;
  Frame frame;
};

RenderedFrame render(const Scene& scene, int index, int width, int height) {
  RenderedFrame r{rasterize_frame(scene, index, width, height), {}};
  r.frame = render_frame(scene, index, width, height, RenderSettings{});
  return r;
}

// A camera at the origin looking down -Z, and the same camera as the previous frame's.
View fixture_view() { return make_view(camera_scene(), camera_scene().pose(0.0), 64, 64); }

// A shadow ray over the plane y = -2 in front of the fixture camera: light above, blocker between.
ShadowRay ray_over_floor() {
  ShadowRay r;
  r.light = {0.0f, 2.0f, -6.0f};
  r.blocker = {0.2f, 0.0f, -6.2f};
  r.receiver = {0.4f, -2.0f, -6.4f};  // on the line: l + 2 (b - l)
  r.receiver_normal = {0.0f, 1.0f, 0.0f};
  r.light_instance = 0, r.blocker_instance = 1, r.receiver_instance = 2;
  return r;
}

std::vector<InstanceMotion> identities(int n) { return std::vector<InstanceMotion>(size_t(n)); }

}  // namespace

TEST_CASE("a moving light: the previous shadow point is where the light's previous line meets the plane") {
  const View view = fixture_view();
  const ShadowRay r = ray_over_floor();
  std::vector<InstanceMotion> to_previous = identities(3);
  const glm::vec3 e(0.3f, 0.0f, 0.1f);  // the light moved by e since the previous frame: T^{-1} l = l - e
  to_previous[0] = instance_motion(glm::translate(glm::mat4(1.0f), -e));
  const ShadowMotion m = shadow_motion_pixel(r, to_previous, view, view);
  REQUIRE(m.valid);
  // Closed form: l' = l - e, the line l' + t (b - l') meets y = -2 at t = (l'.y + 2) / (l'.y - b.y) = 2.
  const glm::vec3 l_prev = r.light - e;
  const glm::vec3 s_prev = l_prev + 2.0f * (r.blocker - l_prev);  // = s + e: the shadow moved against the light
  CHECK(std::abs(s_prev.y + 2.0f) < 1e-6f);
  const glm::vec2 expected = glm::vec2(view.project(s_prev)) - glm::vec2(view.project(r.receiver));
  CHECK(glm::length(m.motion - expected) < 1e-3f);
  CHECK(glm::length(m.motion) > 1.0f);  // the shadow moved by several pixels while the floor stood still
}

TEST_CASE("a moving blocker: the shadow moves t times as far as the blocker, t the receiver's place on the line") {
  const View view = fixture_view();
  const ShadowRay r = ray_over_floor();
  std::vector<InstanceMotion> to_previous = identities(3);
  const glm::vec3 d(0.1f, 0.0f, 0.0f);  // the blocker moved by d: T^{-1} b = b - d
  to_previous[1] = instance_motion(glm::translate(glm::mat4(1.0f), -d));
  const ShadowMotion m = shadow_motion_pixel(r, to_previous, view, view);
  REQUIRE(m.valid);
  const glm::vec3 s_prev = r.receiver - 2.0f * d;  // t = 2: the shadow moved 2 d
  const glm::vec2 expected = glm::vec2(view.project(s_prev)) - glm::vec2(view.project(r.receiver));
  CHECK(glm::length(m.motion - expected) < 1e-3f);
}

TEST_CASE("shadow motion is invalid without a blocker, parallel to the plane, before the blocker, or behind the camera") {
  const View view = fixture_view();
  const std::vector<InstanceMotion> still = identities(3);
  CHECK(shadow_motion_pixel(ray_over_floor(), still, view, view).valid);

  ShadowRay lit = ray_over_floor();
  lit.blocker_instance = kInvalidId;  // the shadow ray reached the light
  CHECK_FALSE(shadow_motion_pixel(lit, still, view, view).valid);

  ShadowRay parallel = ray_over_floor();
  // A plane that contains the line's direction: its normal is perpendicular to b - l.
  parallel.receiver_normal = glm::normalize(glm::cross(parallel.blocker - parallel.light, glm::vec3(0.0f, 0.0f, 1.0f)));
  CHECK_FALSE(shadow_motion_pixel(parallel, still, view, view).valid);

  ShadowRay in_front = ray_over_floor();
  in_front.receiver = {0.1f, 1.0f, -6.1f};  // between the light and the blocker: t = 0.5
  CHECK_FALSE(shadow_motion_pixel(in_front, still, view, view).valid);

  std::vector<InstanceMotion> behind = identities(3);
  behind[2] = instance_motion(glm::translate(glm::mat4(1.0f), glm::vec3(0.0f, 0.0f, 10.0f)));  // behind the camera
  behind[1] = behind[0] = behind[2];                                            // and so were light and blocker
  const ShadowMotion m = shadow_motion_pixel(ray_over_floor(), behind, view, view);
  CHECK_FALSE(m.valid);
  CHECK(m.motion == glm::vec2(0.0f));
}

namespace {

// Occluders translating by d per frame over the floor y = 0, light and floor still: for a floor pixel in shadow,
// with light sample l and blocker b, the ray's line meets the floor at s = l + t (b - l), t = l.y / (l.y - b.y),
// and the previous line l -> b - d meets it at s - t d [TRMV21 Eq. 3]. Returns the number of pixels checked.
int check_translating_blockers(const std::string& name, int frame_index, glm::vec3 d, double* mean_motion) {
  const Scene scene = load_scene(name);
  const RenderedFrame r = render(scene, frame_index, 160, 90);
  const FrameGeometry& g = r.geometry;
  const std::vector<glm::vec2> shadow = r.frame.get_vec2("motion.shadow");
  const std::vector<glm::vec2> surface = r.frame.get_vec2("motion");
  const std::vector<glm::vec3> light = r.frame.get_vec3("path.light"), blocker = r.frame.get_vec3("path.blocker");
  const std::vector<glm::vec3> position = r.frame.get_vec3("position");
  const UIntPlane& valid = r.frame.uint_channel("motion.shadow.valid");
  const UIntPlane& blocker_id = r.frame.uint_channel("path.blocker.instance");
  int checked = 0;
  double sum_shadow = 0.0;
  for (size_t i = 0; i < valid.data.size(); ++i) {
    if (!valid.data[i] || std::abs(position[i].y) > 1e-4f) continue;  // in shadow, on the floor y = 0
    const uint32_t k = blocker_id.data[i];
    const glm::vec3 moved = glm::vec3(g.pose.instance_to_world[k][3] - g.prev_pose.instance_to_world[k][3]);
    INFO(name << ": blocker " << scene.instances[k].name);
    REQUIRE(glm::length(moved - d) < 1e-5f);  // the occluder moved by d (scenes/README.md)
    const float t = light[i].y / (light[i].y - blocker[i].y);
    const glm::vec3 s = light[i] + t * (blocker[i] - light[i]);
    const glm::vec2 expected = glm::vec2(g.prev_view.project(s - t * d)) - glm::vec2(g.view.project(s));
    CHECK(glm::length(shadow[i] - expected) < 1e-3f);
    CHECK(glm::length(surface[i]) < 1e-3f);  // the floor does not move
    sum_shadow += glm::length(shadow[i]);
    ++checked;
  }
  *mean_motion = sum_shadow / std::max(checked, 1);
  return checked;
}

}  // namespace

TEST_CASE("pillars and fence: motion.shadow equals the closed form of the ray's line, while the floor's own motion is 0") {
  double mean = 0.0;
  // The pillars move at 1 m/s: d = (1/30, 0, 0) m per frame.
  const int pillars = check_translating_blockers("pillars", 10, {1.0f / 30.0f, 0.0f, 0.0f}, &mean);
  INFO("pillars: " << pillars << " floor pixels in a pillar's shadow, mean |m^V| " << mean << " px");
  CHECK(pillars > 200);
  CHECK(mean > 0.5);  // the shadows move: about t |d| / the pixel's footprint
  // The fence moves at 3 m/s: d = (0.1, 0, 0) m per frame, frames 1-30.
  const int fence = check_translating_blockers("fence", 10, {0.1f, 0.0f, 0.0f}, &mean);
  INFO("fence: " << fence << " floor pixels in a slat's shadow, mean |m^V| " << mean << " px");
  CHECK(fence > 200);
  CHECK(mean > 1.0);
}

TEST_CASE("cornell, nothing moves: where valid, motion.shadow equals the surface motion, and lit pixels are invalid") {
  const Scene scene = load_scene("cornell");
  const RenderedFrame r = render(scene, 3, 64, 64);
  const std::vector<glm::vec2> shadow = r.frame.get_vec2("motion.shadow");
  const std::vector<glm::vec2> surface = r.frame.get_vec2("motion");
  const UIntPlane& valid = r.frame.uint_channel("motion.shadow.valid");
  const UIntPlane& blocker_id = r.frame.uint_channel("path.blocker.instance");
  int in_shadow = 0;
  double max_difference = 0.0;
  for (size_t i = 0; i < valid.data.size(); ++i) {
    if (blocker_id.data[i] == kInvalidId) {  // lit, or no surface: no Eq. 3 vector
      CHECK(valid.data[i] == 0u);
      CHECK(shadow[i] == glm::vec2(0.0f));
      continue;
    }
    if (!valid.data[i]) continue;
    ++in_shadow;
    max_difference = std::max(max_difference, double(glm::length(shadow[i] - surface[i])));
  }
  INFO("valid in-shadow pixels: " << in_shadow);
  REQUIRE(in_shadow > 50);
  CHECK(max_difference < 1e-3);
}

TEST_CASE("shadow-fold: with the light moving and the slab still, motion.shadow follows the light's previous line") {
  const Scene scene = load_scene("shadow-fold");
  const RenderedFrame r = render(scene, 20, 160, 90);
  const FrameGeometry& g = r.geometry;
  // The light slides along x at 2 m/s (scenes/README.md): e = (2/30, 0, 0) m per frame; the slab stands still.
  const glm::vec3 e(2.0f / 30.0f, 0.0f, 0.0f);
  const std::vector<glm::vec2> shadow = r.frame.get_vec2("motion.shadow");
  const std::vector<glm::vec3> light = r.frame.get_vec3("path.light"), blocker = r.frame.get_vec3("path.blocker");
  const std::vector<glm::vec3> position = r.frame.get_vec3("position");
  const UIntPlane& valid = r.frame.uint_channel("motion.shadow.valid");
  int checked = 0;
  double max_error = 0.0;
  for (size_t i = 0; i < valid.data.size(); ++i) {
    if (!valid.data[i] || std::abs(position[i].y) > 1e-4f) continue;  // in shadow, on the floor y = 0
    // Now: s = l + t (b - l) on y = 0. Before: the light was at l' = l - e, and the line l' -> b meets y = 0 at
    // s' = l' + t' (b - l'), t' = l'.y / (l'.y - b.y).
    const float t = light[i].y / (light[i].y - blocker[i].y);
    const glm::vec3 s = light[i] + t * (blocker[i] - light[i]);
    const glm::vec3 l_prev = light[i] - e;
    const float t_prev = l_prev.y / (l_prev.y - blocker[i].y);
    const glm::vec3 s_prev = l_prev + t_prev * (blocker[i] - l_prev);
    const glm::vec2 expected = glm::vec2(g.prev_view.project(s_prev)) - glm::vec2(g.view.project(s));
    max_error = std::max(max_error, double(glm::length(shadow[i] - expected)));
    ++checked;
  }
  INFO("floor pixels in the slab's shadow: " << checked);
  REQUIRE(checked > 20);
  CHECK(max_error < 1e-3);
}
