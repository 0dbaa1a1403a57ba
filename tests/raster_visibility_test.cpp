// Tests of raster/visibility.cpp: exact coverage with the top-left rule, watertight shared edges,
// perspective-correct barycentrics, near-plane and guard-band clipping, depth order, determinism.
#include "raster/visibility.h"

#include "core/error.h"
#include "core/parallel.h"
#include "scene_fixtures.h"

#include <catch2/catch.hpp>

#include <random>

using namespace rtdr;
using namespace rtdr::test;

namespace {

// Independent coverage reference: a pixel centre p is inside a triangle when p + (eps, eps^2), for an
// infinitesimal eps > 0, is strictly inside it (symbolic perturbation). In double this is exact for the
// dyadic coordinates used here. Expanding the orientation of (a, b, p + (eps, eps^2)) in powers of eps:
// o(p) + eps * do/dpx + eps^2 * do/dpy; its sign is the first non-zero term's.
int perturbed_orientation(glm::dvec2 a, glm::dvec2 b, glm::dvec2 p) {
  const double o = (b.x - a.x) * (p.y - a.y) - (b.y - a.y) * (p.x - a.x);
  const double do_dpx = -(b.y - a.y), do_dpy = b.x - a.x;
  const double first = o != 0.0 ? o : (do_dpx != 0.0 ? do_dpx : do_dpy);
  return first > 0.0 ? 1 : -1;
}

bool centre_inside(glm::dvec2 a, glm::dvec2 b, glm::dvec2 c, glm::dvec2 p) {
  const double area = (b.x - a.x) * (c.y - a.y) - (b.y - a.y) * (c.x - a.x);
  if (area == 0.0) return false;
  const int s = area > 0.0 ? 1 : -1;
  return perturbed_orientation(a, b, p) == s && perturbed_orientation(b, c, p) == s &&
         perturbed_orientation(c, a, p) == s;
}

// Compares the coverage of one triangle against the reference on every pixel; returns the mismatches.
int coverage_mismatches(glm::vec2 a, glm::vec2 b, glm::vec2 c, int w, int h, int* covered = nullptr) {
  const VisibilityBuffer vis = rasterize_clip_triangles({screen_triangle(a, b, c, w, h)}, w, h, 0.05f);
  int mismatches = 0, count = 0;
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      const bool expected = centre_inside(a, b, c, {x + 0.5, y + 0.5});
      const bool got = vis.instance[vis.index(x, y)] != kInvalidId;
      mismatches += expected != got;
      count += got;
    }
  if (covered) *covered = count;
  return mismatches;
}

// How many times each pixel is covered when every triangle is rasterized on its own.
std::vector<int> coverage_counts(const std::vector<std::array<glm::vec2, 3>>& triangles, int w, int h) {
  std::vector<int> counts(size_t(w) * size_t(h), 0);
  for (const auto& t : triangles) {
    const VisibilityBuffer vis = rasterize_clip_triangles({screen_triangle(t[0], t[1], t[2], w, h)}, w, h, 0.05f);
    for (size_t i = 0; i < counts.size(); ++i) counts[i] += vis.instance[i] != kInvalidId;
  }
  return counts;
}

// Strictly inside a convex polygon given in either winding.
bool strictly_inside_convex(const std::vector<glm::dvec2>& poly, glm::dvec2 p) {
  int positive = 0, negative = 0;
  for (size_t i = 0; i < poly.size(); ++i) {
    const glm::dvec2 a = poly[i], b = poly[(i + 1) % poly.size()];
    const double o = (b.x - a.x) * (p.y - a.y) - (b.y - a.y) * (p.x - a.x);
    positive += o > 0.0;
    negative += o < 0.0;
  }
  return positive == int(poly.size()) || negative == int(poly.size());
}

}  // namespace

TEST_CASE("a triangle covers exactly the pixel centres inside it, top-left rule on edges") {
  const int w = 32, h = 32;
  int covered = 0;
  // Top edge y = 2.5 and left edge x = 2.5 run through pixel centres (covered); so does the hypotenuse
  // x + y = 23 (a right edge: not covered). 18 + 17 + ... + 1 centres: the top-left half of an 18x18 grid.
  CHECK(coverage_mismatches({2.5f, 2.5f}, {20.5f, 2.5f}, {2.5f, 20.5f}, w, h, &covered) == 0);
  CHECK(covered == 18 * 19 / 2);
  // The mirror image: bottom edge y = 20.5 and right edge x = 20.5 through centres (not covered), the
  // hypotenuse a left edge (covered): rows y + 0.5 = 4.5 .. 19.5 hold 0, 1, .., 15 centres.
  CHECK(coverage_mismatches({20.5f, 4.5f}, {20.5f, 20.5f}, {4.5f, 20.5f}, w, h, &covered) == 0);
  CHECK(covered == 16 * 15 / 2);
  // Both windings of random triangles on the half-pixel grid, partly off screen: many centres on edges
  // and vertices.
  std::mt19937 rng(7);
  std::uniform_int_distribution<int> coord(-8, 72);  // half pixels
  int total_mismatches = 0;
  for (int i = 0; i < 300; ++i) {
    const glm::vec2 a(0.5f * coord(rng), 0.5f * coord(rng)), b(0.5f * coord(rng), 0.5f * coord(rng)),
        c(0.5f * coord(rng), 0.5f * coord(rng));
    total_mismatches += coverage_mismatches(a, b, c, w, h) + coverage_mismatches(a, c, b, w, h);
  }
  CHECK(total_mismatches == 0);
}

TEST_CASE("sub-pixel vertices on the 1/256 grid are covered exactly, odd image sizes too") {
  std::mt19937 rng(11);
  for (const glm::ivec2 size : {glm::ivec2(33, 17), glm::ivec2(1, 1), glm::ivec2(7, 40)}) {
    std::uniform_int_distribution<int> cx(-256 * 4, 256 * (size.x + 4)), cy(-256 * 4, 256 * (size.y + 4));
    int total_mismatches = 0;
    for (int i = 0; i < 200; ++i) {
      const glm::vec2 a(cx(rng) / 256.0f, cy(rng) / 256.0f), b(cx(rng) / 256.0f, cy(rng) / 256.0f),
          c(cx(rng) / 256.0f, cy(rng) / 256.0f);
      total_mismatches += coverage_mismatches(a, b, c, size.x, size.y);
    }
    CHECK(total_mismatches == 0);
  }
}

TEST_CASE("a two-triangle quad covers every pixel of its area exactly once") {
  const int w = 32, h = 32;
  for (const auto& q : {std::array<glm::vec2, 4>{{{3.5f, 3.5f}, {27.5f, 3.5f}, {27.5f, 20.5f}, {3.5f, 20.5f}}},
                        std::array<glm::vec2, 4>{{{5.25f, 2.5f}, {28.5f, 9.75f}, {22.0f, 30.5f}, {1.5f, 19.0f}}}}) {
    const std::vector<int> counts = coverage_counts({{q[0], q[1], q[2]}, {q[0], q[2], q[3]}}, w, h);
    const std::vector<glm::dvec2> poly(q.begin(), q.end());
    int overlaps = 0, holes = 0, outside = 0;
    for (int y = 0; y < h; ++y)
      for (int x = 0; x < w; ++x) {
        const int n = counts[size_t(y * w + x)];
        const glm::dvec2 p(x + 0.5, y + 0.5);
        overlaps += n > 1;
        holes += n == 0 && strictly_inside_convex(poly, p);
        outside += n > 0 && !strictly_inside_convex(poly, p) && !centre_inside(q[0], q[1], q[2], p) &&
                   !centre_inside(q[0], q[2], q[3], p);
      }
    CHECK(overlaps == 0);
    CHECK(holes == 0);
    CHECK(outside == 0);
  }
}

TEST_CASE("a fan of triangles around a shared vertex covers each pixel once, the shared centre too") {
  const int w = 32, h = 32;
  const glm::vec2 centre(16.5f, 16.5f);  // exactly a pixel centre, on every fan edge
  const std::vector<glm::vec2> ring = {{28.5f, 16.5f}, {25.0f, 25.0f}, {16.5f, 28.5f}, {8.0f, 25.0f},
                                       {4.5f, 16.5f},  {8.0f, 8.0f},   {16.5f, 4.5f},  {25.0f, 8.0f}};
  std::vector<std::array<glm::vec2, 3>> fan;
  for (size_t i = 0; i < ring.size(); ++i) fan.push_back({centre, ring[i], ring[(i + 1) % ring.size()]});
  const std::vector<int> counts = coverage_counts(fan, w, h);
  const std::vector<glm::dvec2> poly(ring.begin(), ring.end());
  int overlaps = 0, holes = 0;
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      overlaps += counts[size_t(y * w + x)] > 1;
      holes += counts[size_t(y * w + x)] == 0 && strictly_inside_convex(poly, {x + 0.5, y + 0.5});
    }
  CHECK(overlaps == 0);
  CHECK(holes == 0);
  CHECK(counts[size_t(16 * w + 16)] == 1);
}

TEST_CASE("perspective-correct barycentrics and depth match the analytic pixel-ray intersection") {
  Scene s = camera_scene();
  add_object(s, {{-1.0f, -0.8f, -2.0f}, {1.5f, -0.5f, -6.0f}, {-0.3f, 1.2f, -3.5f}}, {{0, 1, 2}});
  const ScenePose pose = s.pose(0.0);
  const View view = make_view(s, pose, 128, 96);
  const VisibilityBuffer vis = rasterize(s, pose, view);
  const auto tri = world_triangle(s, pose, 0, 0);
  double max_bary_error = 0.0, max_depth_error = 0.0;
  int covered = 0;
  for (int y = 0; y < vis.height; ++y)
    for (int x = 0; x < vis.width; ++x) {
      if (vis.instance[vis.index(x, y)] == kInvalidId) continue;
      ++covered;
      glm::dvec3 o, d;
      pixel_ray(view, {x + 0.5, y + 0.5}, o, d);
      const RayHit hit = *intersect_plane(o, d, tri[0], tri[1], tri[2]);
      const glm::dvec2 b(vis.bary[vis.index(x, y)]);
      max_bary_error = std::max({max_bary_error, std::abs(b.x - hit.bary.x), std::abs(b.y - hit.bary.y)});
      max_depth_error = std::max(max_depth_error, std::abs(vis.depth[vis.index(x, y)] - hit.t) / hit.t);
    }
  CHECK(covered > 1000);
  CHECK(max_bary_error < 1e-4);
  CHECK(max_depth_error < 1e-5);
}

TEST_CASE("near-plane clipping keeps the barycentrics of the original triangle") {
  // Vertex 2 is behind the camera (view z = +1): the triangle crosses the near plane.
  Scene s = camera_scene(glm::vec3(0.0f), glm::quat(1, 0, 0, 0), 0.8f, 0.5f);
  add_object(s, {{-1.0f, -1.0f, -2.0f}, {1.0f, -0.5f, -2.5f}, {0.2f, 0.8f, 1.0f}}, {{0, 1, 2}});
  const ScenePose pose = s.pose(0.0);
  const View view = make_view(s, pose, 96, 64);
  const VisibilityBuffer vis = rasterize(s, pose, view);
  const auto tri = world_triangle(s, pose, 0, 0);
  double max_bary_error = 0.0;
  int covered = 0, disagreements = 0;
  for (int y = 0; y < vis.height; ++y)
    for (int x = 0; x < vis.width; ++x) {
      glm::dvec3 o, d;
      pixel_ray(view, {x + 0.5, y + 0.5}, o, d);
      const RayHit hit = *intersect_plane(o, d, tri[0], tri[1], tri[2]);
      const double b0 = 1.0 - hit.bary.x - hit.bary.y;
      const double inside_margin = std::min({b0, hit.bary.x, hit.bary.y, (hit.t - 0.5) / hit.t});
      const bool is_covered = vis.instance[vis.index(x, y)] != kInvalidId;
      if (std::abs(inside_margin) > 1e-3) disagreements += is_covered != (inside_margin > 0.0);
      if (!is_covered) continue;
      ++covered;
      CHECK(vis.depth[vis.index(x, y)] >= 0.5f * (1.0f - 1e-5f));
      const glm::dvec2 b(vis.bary[vis.index(x, y)]);
      max_bary_error = std::max({max_bary_error, std::abs(b.x - hit.bary.x), std::abs(b.y - hit.bary.y)});
    }
  CHECK(covered > 500);
  CHECK(disagreements == 0);
  CHECK(max_bary_error < 1e-4);

  // Entirely behind the near plane: nothing drawn.
  Scene behind = camera_scene(glm::vec3(0.0f), glm::quat(1, 0, 0, 0), 0.8f, 0.5f);
  add_object(behind, {{-1.0f, -1.0f, -0.4f}, {1.0f, -1.0f, -0.3f}, {0.0f, 1.0f, 2.0f}}, {{0, 1, 2}});
  const VisibilityBuffer none = rasterize(behind, behind.pose(0.0), make_view(behind, behind.pose(0.0), 16, 16));
  CHECK(std::count(none.instance.begin(), none.instance.end(), kInvalidId) == 16 * 16);
}

TEST_CASE("a triangle reaching far beyond the guard band is clipped to it and still exact") {
  // At depth 2, x = +-2000 lands about 100,000 pixels off a 64-pixel-wide screen.
  Scene s = camera_scene();
  add_object(s, {{-2000.0f, -1000.0f, -2.0f}, {2000.0f, -1000.0f, -3.0f}, {0.0f, 2000.0f, -2.5f}}, {{0, 1, 2}});
  const ScenePose pose = s.pose(0.0);
  const View view = make_view(s, pose, 64, 48);
  const VisibilityBuffer vis = rasterize(s, pose, view);
  const auto tri = world_triangle(s, pose, 0, 0);
  double max_bary_error = 0.0;
  for (int y = 0; y < vis.height; ++y)
    for (int x = 0; x < vis.width; ++x) {
      REQUIRE(vis.instance[vis.index(x, y)] == 0);
      glm::dvec3 o, d;
      pixel_ray(view, {x + 0.5, y + 0.5}, o, d);
      const RayHit hit = *intersect_plane(o, d, tri[0], tri[1], tri[2]);
      const glm::dvec2 b(vis.bary[vis.index(x, y)]);
      max_bary_error = std::max({max_bary_error, std::abs(b.x - hit.bary.x), std::abs(b.y - hit.bary.y)});
    }
  CHECK(max_bary_error < 1e-6);
}

TEST_CASE("the nearest triangle wins, on equal depth the earlier one") {
  const int w = 16, h = 16;
  const ClipTriangle far_tri = screen_triangle({0, 0}, {16, 0}, {0, 16}, w, h, 3.0f, 0, 0);
  const ClipTriangle near_tri = screen_triangle({2, 2}, {14, 2}, {2, 14}, w, h, 2.0f, 1, 0);
  for (const auto& order : {std::vector<ClipTriangle>{far_tri, near_tri}, std::vector<ClipTriangle>{near_tri, far_tri}}) {
    const VisibilityBuffer vis = rasterize_clip_triangles(order, w, h, 0.05f);
    CHECK(vis.instance[vis.index(4, 4)] == 1);
    CHECK(vis.depth[vis.index(4, 4)] == 2.0f);
    CHECK(vis.instance[vis.index(1, 1)] == 0);
    CHECK(vis.depth[vis.index(1, 1)] == 3.0f);
    CHECK(vis.instance[vis.index(15, 15)] == kInvalidId);
    CHECK(vis.depth[vis.index(15, 15)] == 0.0f);
  }
  // Two copies of the same triangle: the first in the list keeps every pixel.
  const ClipTriangle first = screen_triangle({0, 0}, {16, 0}, {0, 16}, w, h, 2.0f, 3, 7);
  const ClipTriangle second = screen_triangle({0, 0}, {16, 0}, {0, 16}, w, h, 2.0f, 4, 0);
  const VisibilityBuffer tie = rasterize_clip_triangles({first, second}, w, h, 0.05f);
  int first_wins = 0, second_wins = 0, inside = 0;
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      first_wins += tie.instance[tie.index(x, y)] == 3 && tie.triangle[tie.index(x, y)] == 7;
      second_wins += tie.instance[tie.index(x, y)] == 4;
      inside += centre_inside({0, 0}, {16, 0}, {0, 16}, {x + 0.5, y + 0.5});
    }
  CHECK(inside == 15 * 16 / 2);  // centres with x + y <= 14; those on the hypotenuse (a right edge) are out
  CHECK(first_wins == inside);
  CHECK(second_wins == 0);
}

TEST_CASE("the buffer is identical with 1 and 2 threads") {
  Scene s = camera_scene();
  std::mt19937 rng(3);
  std::uniform_real_distribution<float> u(-1.0f, 1.0f);
  std::vector<glm::vec3> positions;
  std::vector<glm::uvec3> triangles;
  for (uint32_t t = 0; t < 300; ++t) {
    const glm::vec3 c(2.0f * u(rng), 1.5f * u(rng), -4.0f + 2.0f * u(rng));
    for (int k = 0; k < 3; ++k) positions.push_back(c + 0.6f * glm::vec3(u(rng), u(rng), u(rng)));
    triangles.push_back({3 * t, 3 * t + 1, 3 * t + 2});
  }
  add_object(s, positions, triangles);
  add_quad(s, 8.0f, {0.0f, 0.0f, -4.0f});  // coplanar ties with the random triangles are possible too
  const ScenePose pose = s.pose(0.0);
  const View view = make_view(s, pose, 97, 61);
  set_thread_count(1);
  const VisibilityBuffer one = rasterize(s, pose, view);
  set_thread_count(2);
  const VisibilityBuffer two = rasterize(s, pose, view);
  set_thread_count(0);
  CHECK(one.instance == two.instance);
  CHECK(one.triangle == two.triangle);
  CHECK(one.bary == two.bary);
  CHECK(one.depth == two.depth);
  CHECK(std::count(one.instance.begin(), one.instance.end(), kInvalidId) == 0);  // the quad fills the view
}

TEST_CASE("object_point and world_point rebuild the sample's point, bad sizes are rejected") {
  Scene s = camera_scene();
  add_object(s, {{0, 0, 0}, {2, 0, 0}, {0, 4, 0}}, {{0, 1, 2}}, {1.0f, 2.0f, -3.0f});
  const SurfaceSample sample{0, 0, {0.25f, 0.5f}};
  CHECK(object_point(s, sample).x == Approx(0.5f));
  CHECK(object_point(s, sample).y == Approx(2.0f));
  const glm::vec3 world = world_point(s, s.pose(0.0), sample);
  CHECK(world.x == Approx(1.5f));
  CHECK(world.y == Approx(4.0f));
  CHECK(world.z == Approx(-3.0f));
  CHECK_THROWS_AS(rasterize_clip_triangles({}, 0, 10, 0.05f), Error);
  CHECK_THROWS_AS(rasterize_clip_triangles({}, kMaxImageSize + 1, 10, 0.05f), Error);
}
