// Tests for trace/embree_scene: closed-form hits on a hand-built quad, then agreement with the
// rasterizer (raster/visibility.h) on every shipped scene: both must name the same (instance, triangle)
// at a pixel centre, with matching barycentrics and depth.
#include "trace/embree_scene.h"

#include "core/frame.h"
#include "raster/view.h"
#include "raster/visibility.h"
#include "scenes/catalog.h"
#include "scenes/gltf_loader.h"

#include <catch2/catch.hpp>

#include <glm/gtc/matrix_transform.hpp>

#include <algorithm>
#include <cmath>

using Catch::Detail::Approx;
using rtdr::kInvalidId;

namespace {

// A unit quad in the z = 0 plane, split along its diagonal from (0,0) to (1,1):
//   triangle 0 = (v0, v1, v2) below the diagonal (y < x), triangle 1 = (v0, v2, v3) above it.
// Instance 0 sits at z = -2; instance 1 at x + 3, z = -5.
rtdr::Scene two_quads() {
  rtdr::Scene scene;
  rtdr::Mesh quad;
  quad.positions = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}};
  quad.triangles = {{0, 1, 2}, {0, 2, 3}};
  scene.meshes.push_back(quad);
  scene.instances = {{"near", 0, 0}, {"far", 1, 0}};
  return scene;
}

rtdr::ScenePose two_quads_pose() {
  rtdr::ScenePose pose;
  pose.instance_to_world = {glm::translate(glm::mat4(1.0f), {0, 0, -2}), glm::translate(glm::mat4(1.0f), {3, 0, -5})};
  pose.normal_to_world = {glm::mat3(1.0f), glm::mat3(1.0f)};
  return pose;
}

rtdr::Ray down_minus_z(float x, float y) { return {{x, y, 0.0f}, {0.0f, 0.0f, -1.0f}}; }

}  // namespace

TEST_CASE("embree_device is one device for the whole process") {
  REQUIRE(rtdr::embree_device() != nullptr);
  CHECK(rtdr::embree_device() == rtdr::embree_device());
}

TEST_CASE("EmbreeScene: closed-form hits on two quads") {
  const rtdr::Scene scene = two_quads();
  const rtdr::EmbreeScene embree(scene, two_quads_pose());

  SECTION("below the diagonal: triangle 0, p = v0 + u (v1 - v0) + v (v2 - v0) = (u + v, v)") {
    const rtdr::Hit hit = embree.intersect(down_minus_z(0.7f, 0.2f));
    CHECK(hit.instance == 0);
    CHECK(hit.triangle == 0);
    CHECK(hit.bary.x == Approx(0.5f).margin(1e-6));  // u = x - y
    CHECK(hit.bary.y == Approx(0.2f).margin(1e-6));  // v = y
    CHECK(hit.t == Approx(2.0f).margin(1e-6));
  }
  SECTION("above the diagonal: triangle 1, p = u (1, 1) + v (0, 1) = (u, u + v)") {
    const rtdr::Hit hit = embree.intersect(down_minus_z(0.2f, 0.7f));
    CHECK(hit.instance == 0);
    CHECK(hit.triangle == 1);
    CHECK(hit.bary.x == Approx(0.2f).margin(1e-6));  // u = x
    CHECK(hit.bary.y == Approx(0.5f).margin(1e-6));  // v = y - x
  }
  SECTION("the second instance: geomID is the instance index") {
    const rtdr::Hit hit = embree.intersect(down_minus_z(3.7f, 0.2f));
    CHECK(hit.instance == 1);
    CHECK(hit.triangle == 0);
    CHECK(hit.t == Approx(5.0f).margin(1e-6));
  }
  SECTION("an oblique ray: t is the distance along the normalised direction") {
    const glm::vec3 origin{0.0f, 0.0f, 1.0f}, target{0.6f, 0.3f, -2.0f};  // target on instance 0, triangle 0
    const rtdr::Hit hit = embree.intersect({origin, glm::normalize(target - origin)});
    CHECK(hit.instance == 0);
    CHECK(hit.triangle == 0);
    CHECK(hit.t == Approx(glm::length(target - origin)).margin(1e-5));
    CHECK(hit.bary.x == Approx(0.3f).margin(1e-5));
    CHECK(hit.bary.y == Approx(0.3f).margin(1e-5));
  }
  SECTION("misses: outside the quads, and behind the ray") {
    for (const rtdr::Ray& ray : {down_minus_z(1.5f, 0.5f), down_minus_z(-0.1f, 0.5f), down_minus_z(0.5f, 1.01f),
                                 rtdr::Ray{{0.5f, 0.5f, 0.0f}, {0.0f, 0.0f, 1.0f}}}) {
      const rtdr::Hit hit = embree.intersect(ray);
      CHECK(hit.instance == kInvalidId);
      CHECK(hit.triangle == kInvalidId);
    }
  }
  SECTION("the [tnear, tfar] interval") {
    CHECK(embree.intersect(down_minus_z(0.5f, 0.2f), 0.0f, 1.9f).instance == kInvalidId);
    CHECK(embree.intersect(down_minus_z(3.5f, 0.2f), 0.0f, 4.9f).instance == kInvalidId);
    CHECK(embree.intersect(down_minus_z(3.5f, 0.2f), 0.0f, 5.1f).instance == 1);
  }
  SECTION("occluded agrees with intersect") {
    CHECK(embree.occluded(down_minus_z(0.7f, 0.2f), 0.0f, 3.0f));
    CHECK_FALSE(embree.occluded(down_minus_z(0.7f, 0.2f), 0.0f, 1.5f));  // stops short of z = -2
    CHECK_FALSE(embree.occluded(down_minus_z(0.7f, 0.2f), 2.5f, 100.0f));  // starts past it
    CHECK_FALSE(embree.occluded(down_minus_z(1.5f, 0.5f), 0.0f, 100.0f));  // a miss
    CHECK(embree.occluded(down_minus_z(3.5f, 0.5f), 0.0f, 100.0f));
  }
}

TEST_CASE("EmbreeScene: a scene without triangles is hit by nothing") {
  rtdr::Scene scene;
  scene.meshes.push_back(rtdr::Mesh{});
  scene.instances = {{"empty", 0, 0}};
  rtdr::ScenePose pose;
  pose.instance_to_world = {glm::mat4(1.0f)};
  const rtdr::EmbreeScene embree(scene, pose);
  CHECK(embree.intersect(down_minus_z(0.0f, 0.0f)).instance == kInvalidId);
  CHECK_FALSE(embree.occluded(down_minus_z(0.0f, 0.0f), 0.0f, 1e30f));
}

// ---- Agreement with the rasterizer ---------------------------------------------------------------------
// The rasterizer samples each pixel centre; so does a primary ray through it. Where a pixel centre lies
// exactly on a triangle's edge, both answers are right but may differ: the rasterizer applies the top-left
// rule (and, between surfaces at equal depth, the lower index), Embree's watertight test counts the whole
// boundary as inside. The Cornell box has many such centres: its corners project onto exact pixel
// diagonals, and at 320x180 the open front edge of the right wall runs exactly through a column of pixel
// centres (Embree: wall, rasterizer: background). Such a "tie" is a pixel where each answer is either
// background or a point on an edge of its triangle, and where both name a surface, the same world point.
// Every other pixel must name the same (instance, triangle), bar the rare centre within float rounding of
// an edge or a depth tie: hence >= 99.9% rather than 100%.

namespace {

struct Agreement {
  size_t pixels = 0;
  size_t same_triangle = 0;  // same (instance, triangle), background included
  size_t ties = 0;           // different answers, both right: the pixel centre lies on an edge
  float max_bary_error = 0.0f;            // over pixels with the same triangle
  float max_depth_relative_error = 0.0f;  // likewise
};

// True when (b1, b2) is within `tolerance` of an edge of its triangle: some barycentric, b0 = 1 - b1 - b2
// included, is near zero. 1e-4 of a triangle's extent is well below a pixel for any visible triangle.
bool on_an_edge(glm::vec2 bary, float tolerance = 1e-4f) {
  return std::min({bary.x, bary.y, 1.0f - bary.x - bary.y}) <= tolerance;
}

Agreement compare_with_rasterizer(const rtdr::Scene& scene, double t, int width, int height) {
  const rtdr::ScenePose pose = scene.pose(t);
  const rtdr::View view = rtdr::make_view(scene, pose, width, height);
  const rtdr::VisibilityBuffer visibility = rtdr::rasterize(scene, pose, view);
  const rtdr::EmbreeScene embree(scene, pose);
  // The camera's viewing axis in world space (-Z of the camera node): depth = t * cos(ray, axis).
  const glm::vec3 axis = glm::normalize(glm::vec3(view.view_to_world * glm::vec4(0.0f, 0.0f, -1.0f, 0.0f)));

  Agreement a;
  for (int y = 0; y < height; ++y) {
    for (int x = 0; x < width; ++x) {
      ++a.pixels;
      const rtdr::Ray ray = view.ray_through({float(x) + 0.5f, float(y) + 0.5f});
      const float cosine = glm::dot(ray.direction, axis);
      // The rasterizer clips at depth znear; the ray starts at the same depth.
      const rtdr::Hit hit = embree.intersect(ray, view.znear / cosine);
      const rtdr::SurfaceSample s = visibility.sample(x, y);
      const float depth = visibility.depth[visibility.index(x, y)];
      if (hit.instance != s.instance || hit.triangle != s.triangle) {
        const bool embree_on_edge = hit.instance == kInvalidId || on_an_edge(hit.bary);
        const bool raster_on_edge = !s.valid() || on_an_edge(s.bary);
        const bool both_surfaces = hit.instance != kInvalidId && s.valid();
        const glm::vec3 embree_point = ray.origin + hit.t * ray.direction;
        const bool same_point =
            !both_surfaces || glm::distance(embree_point, rtdr::world_point(scene, pose, s)) <= 1e-4f * depth;
        if (embree_on_edge && raster_on_edge && same_point) ++a.ties;
        continue;
      }
      ++a.same_triangle;
      if (!s.valid()) continue;
      a.max_bary_error = std::max({a.max_bary_error, std::abs(hit.bary.x - s.bary.x), std::abs(hit.bary.y - s.bary.y)});
      a.max_depth_relative_error = std::max(a.max_depth_relative_error, std::abs(hit.t * cosine - depth) / depth);
    }
  }
  return a;
}

}  // namespace

TEST_CASE("EmbreeScene agrees with the rasterizer on every shipped scene") {
  const std::vector<std::string> names = rtdr::shipped_scene_names();
  REQUIRE_FALSE(names.empty());
  for (const std::string& name : names) {
    const rtdr::Scene scene = rtdr::load_scene(rtdr::shipped_scene_path(name));
    for (int frame : {0, 17, 40}) {
      for (auto [width, height] : {std::pair{160, 90}, std::pair{320, 180}}) {
        const Agreement a = compare_with_rasterizer(scene, scene.time_of_frame(frame), width, height);
        INFO(name << " frame " << frame << " at " << width << "x" << height << ": of " << a.pixels << " pixels, "
                  << a.same_triangle << " name the same triangle and " << a.ties << " are edge ties; "
                  << "max bary error " << a.max_bary_error << ", max relative depth error "
                  << a.max_depth_relative_error);
        CHECK(double(a.same_triangle + a.ties) >= 0.999 * double(a.pixels));
        CHECK(a.max_bary_error <= 1e-3f);
        CHECK(a.max_depth_relative_error <= 1e-4f);
      }
    }
  }
}
