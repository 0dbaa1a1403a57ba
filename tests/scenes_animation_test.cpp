// Tests of scenes/animation.cpp and the node transforms of scenes/scene.cpp, on tracks built here and on
// the animated fixture tests/data/anim_test.gltf and the pillars scene. Every expected value is computed by
// hand from the key values and the formulas of glTF spec Sec. 3.11 (LINEAR, STEP, slerp).
#include "scenes/animation.h"
#include "scenes/gltf_loader.h"
#include "scenes/scene.h"

#include <catch2/catch.hpp>
#include <glm/glm.hpp>

#include <cmath>
#include <string>

using namespace rtdr;

namespace {

const double kPi = 3.14159265358979323846;

void check_vec3(const glm::vec3& v, const glm::vec3& expected) {
  CHECK(v.x == Approx(expected.x).margin(1e-5));
  CHECK(v.y == Approx(expected.y).margin(1e-5));
  CHECK(v.z == Approx(expected.z).margin(1e-5));
}

// q and -q are the same rotation: compare up to sign.
void check_rotation(const glm::quat& q, const glm::quat& expected) {
  const float sign = glm::dot(q, expected) < 0.0f ? -1.0f : 1.0f;
  for (int c = 0; c < 4; ++c) CHECK(sign * q[c] == Approx(expected[c]).margin(1e-5));
}

int node_named(const Scene& s, const std::string& name) {
  for (size_t i = 0; i < s.nodes.size(); ++i)
    if (s.nodes[i].name == name) return int(i);
  return -1;
}

}  // namespace

TEST_CASE("find_key_span brackets t between keys and clamps outside them") {
  const std::vector<float> times = {0.0f, 1.0f, 3.0f};
  CHECK(find_key_span(times, -0.5).k == -1);  // before the first key
  const KeySpan mid = find_key_span(times, 2.5);
  CHECK(mid.k == 1);
  CHECK(mid.u == Approx(0.75f).margin(1e-6));  // (2.5 - 1) / (3 - 1)
  CHECK(find_key_span(times, 1.0).k == 1);     // exactly on a key: u = 0
  CHECK(find_key_span(times, 1.0).u == 0.0f);
  CHECK(find_key_span(times, 7.0).k == 2);  // after the last key
  CHECK(find_key_span({}, 1.0).k == -1);
}

TEST_CASE("LINEAR interpolates, STEP holds, both clamp before the first and after the last key") {
  Track<glm::vec3> track;
  track.times = {1.0f, 2.0f};
  track.values = {glm::vec3(0, 10, 0), glm::vec3(4, 20, -2)};
  check_vec3(track.sample(1.25), glm::vec3(1, 12.5, -0.5));  // a + 0.25 (b - a)
  check_vec3(track.sample(0.0), glm::vec3(0, 10, 0));
  check_vec3(track.sample(9.0), glm::vec3(4, 20, -2));
  track.interpolation = Interpolation::Step;
  check_vec3(track.sample(1.99), glm::vec3(0, 10, 0));
  check_vec3(track.sample(2.0), glm::vec3(4, 20, -2));
}

TEST_CASE("rotation keys in opposite hemispheres slerp along the shorter arc") {
  // Key 0: identity. Key 1: 60 degrees about +X written as its negation -(sin 30, 0, 0, cos 30), so
  // dot(q0, q1) = -cos 30 < 0. glTF Appendix C: flip q1, then with cos theta = |dot| = cos 30,
  // slerp(u) = (sin((1 - u) theta) q0 + sin(u theta) (-q1)) / sin theta.
  Track<glm::quat> track;
  track.times = {0.0f, 1.0f};
  const float c30 = float(std::cos(kPi / 6)), s30 = float(std::sin(kPi / 6));
  track.values = {glm::quat(1, 0, 0, 0), glm::quat(-c30, -s30, 0, 0)};  // glm order (w, x, y, z)
  for (double u : {0.25, 0.5}) {
    const double theta = kPi / 6;
    const double wa = std::sin((1 - u) * theta) / std::sin(theta), wb = std::sin(u * theta) / std::sin(theta);
    const glm::quat by_formula(float(wa + wb * c30), float(wb * s30), 0, 0);
    // The same rotation in closed form: u * 60 degrees about +X, half angle u * 30 degrees.
    const glm::quat closed_form(float(std::cos(u * kPi / 6)), float(std::sin(u * kPi / 6)), 0, 0);
    check_rotation(by_formula, closed_form);
    check_rotation(track.sample(u), by_formula);
  }
}

// anim_test.gltf (keys from scenes/make_test_fixtures.py):
//   parent translation LINEAR t = 0, 1, 2 -> (0, 0, 0), (2, 0, 0), (2, 4, 0); rotation identity, scale 1
//   child  translation (0, 1, 0), child of parent
//          rotation LINEAR t = 0, 1, 2 -> 0, 90, 180 degrees about +Z, stored (0, 0, 0, 1), (0, 0, s, s),
//          (0, 0, -1, 0) with s = sin 45: the last two are in opposite hemispheres
//          scale STEP t = 0.5, 1.5 -> (0.5, 1, 1.5), (2, 3, 1)
// So node_to_world(child, t) = T_parent(t) * T_child * R_z(angle(t)) * S(t), and a point p maps to
// T_parent + (0, 1, 0) + R_z(angle) (S * p).
struct ChildPose {
  double t;
  glm::vec3 parent_translation;
  double degrees;  // about +Z
  glm::vec3 scale;
};

TEST_CASE("anim_test.gltf: node_to_world between keys is the hand-computed T * R * S") {
  const Scene s = load_scene(std::string(RTDR_TEST_DATA_DIR) + "/anim_test.gltf");
  const int child = node_named(s, "child");
  REQUIRE(child >= 0);
  const ChildPose poses[] = {
      {-1.0, {0, 0, 0}, 0.0, {0.5, 1, 1.5}},     // before every key: first values
      {0.25, {0.5, 0, 0}, 22.5, {0.5, 1, 1.5}},  // 0.25 of 0 -> 90; scale before its first key
      {0.75, {1.5, 0, 0}, 67.5, {0.5, 1, 1.5}},  // STEP holds the key at t = 0.5
      {1.25, {2, 1, 0}, 112.5, {0.5, 1, 1.5}},   // 90 -> 180 the short way; LINEAR scale would be 1.625
      {1.5, {2, 2, 0}, 135.0, {2, 3, 1}},        // exactly on the STEP key at 1.5
      {3.0, {2, 4, 0}, 180.0, {2, 3, 1}},        // after every key: last values
  };
  for (const ChildPose& p : poses) {
    INFO("t = " << p.t);
    const glm::mat4 m = s.node_to_world(child, p.t);
    const double a = p.degrees * kPi / 180.0;
    const float c = float(std::cos(a)), sn = float(std::sin(a));
    const glm::vec3 origin = p.parent_translation + glm::vec3(0, 1, 0);
    // Images of the child's unit axes: column k of the upper 3x3 is R_z (scale_k e_k).
    check_vec3(glm::vec3(m[0]), glm::vec3(c, sn, 0) * p.scale.x);
    check_vec3(glm::vec3(m[1]), glm::vec3(-sn, c, 0) * p.scale.y);
    check_vec3(glm::vec3(m[2]), glm::vec3(0, 0, 1) * p.scale.z);
    check_vec3(glm::vec3(m[3]), origin);
    // The pose's instance matrices are the same transform (instances child/0 and child/1).
    const ScenePose pose = s.pose(p.t);
    for (int k = 0; k < 4; ++k) check_vec3(glm::vec3(pose.instance_to_world[1][k]), glm::vec3(m[k]));
  }
}

TEST_CASE("anim_test.gltf: the 90 -> 180 degree keys slerp as the formula says") {
  const Scene s = load_scene(std::string(RTDR_TEST_DATA_DIR) + "/anim_test.gltf");
  const Track<glm::quat>& rotation = s.nodes[size_t(node_named(s, "child"))].rotation_track;
  REQUIRE(rotation.values.size() == 3);
  CHECK(glm::dot(rotation.values[1], rotation.values[2]) < 0.0f);  // opposite hemispheres, as written
  // Between t = 1 and 2 at u = 0.25: flip q2 = (0, 0, -1, 0) to (0, 0, 1, 0); cos theta = s = cos 45 deg.
  const double s45 = std::sin(kPi / 4), theta = kPi / 4, u = 0.25;
  const double wa = std::sin((1 - u) * theta) / std::sin(theta), wb = std::sin(u * theta) / std::sin(theta);
  const glm::quat by_formula(float(wa * s45), 0, 0, float(wa * s45 + wb));  // (w, x, y, z)
  check_rotation(rotation.sample(1.25), by_formula);
  // = 112.5 degrees about +Z: half angle 56.25 degrees.
  check_rotation(by_formula, glm::quat(float(std::cos(56.25 * kPi / 180)), 0, 0, float(std::sin(56.25 * kPi / 180))));
}

TEST_CASE("pillars: the parent moves left to right, carrying the eleven pillars") {
  const Scene s = load_scene("pillars");
  const int parent = node_named(s, "pillars");
  REQUIRE(parent >= 0);
  // Keys t = 0, 1, 2 s -> x = -1, 0, 1 (scenes/make_scenes.py): 1 m/s.
  CHECK(s.node_to_world(parent, 0.0)[3].x == Approx(-1.0f).margin(1e-5));
  CHECK(s.node_to_world(parent, 0.5)[3].x == Approx(-0.5f).margin(1e-5));
  CHECK(s.node_to_world(parent, 2.0)[3].x == Approx(1.0f).margin(1e-5));
  float previous = -1e30f;
  for (int frame = 0; frame <= 60; ++frame) {  // 2 s at the default 30 fps
    const double t = s.time_of_frame(frame);
    const float x = s.node_to_world(parent, t)[3].x;
    CHECK(x == Approx(-1.0 + t).margin(1e-5));
    CHECK(x > previous);
    previous = x;
    // pillar_05, the middle one, sits at the parent's origin; z and y do not move.
    const glm::mat4 middle = s.node_to_world(node_named(s, "pillar_05"), t);
    CHECK(middle[3].x == Approx(x).margin(1e-5));
    CHECK(middle[3].z == Approx(-1.0f).margin(1e-5));
  }
}

TEST_CASE("find_key_span stays inside the track for a NaN time and for a time that rounds up to the last key") {
  const std::vector<float> times = {0.0f, 1.0f, 2.0f};
  CHECK(find_key_span(times, std::nan("")).k == -1);  // holds the first key (it read times[3] before)
  // Just below 2 as a double, exactly 2 as a float: upper_bound finds no key after it.
  const double below_last = std::nextafter(2.0, 0.0);
  REQUIRE(float(below_last) == 2.0f);
  const KeySpan s = find_key_span(times, below_last);
  CHECK(s.k == 1);
  CHECK(s.u == 1.0f);
}
