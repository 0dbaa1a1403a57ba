// Tests of raster/gbuffer.cpp: positions, normals, depth and its analytic gradient, materials, layers.
#include "raster/gbuffer.h"

#include "core/error.h"
#include "scene_fixtures.h"

#include <catch2/catch.hpp>

#include <glm/gtc/matrix_transform.hpp>

#include <cmath>

using namespace rtdr;
using namespace rtdr::test;

namespace {

// A camera at the origin and one slanted triangle, flat shaded (no vertex normals).
Scene slanted_triangle_scene(bool reversed) {
  Scene s = camera_scene();
  std::vector<glm::vec3> p = {{-1.0f, -0.8f, -2.0f}, {1.5f, -0.5f, -6.0f}, {-0.3f, 1.2f, -3.5f}};
  if (reversed) std::swap(p[1], p[2]);
  add_object(s, p, {{0, 1, 2}});
  return s;
}

// Analytic depth at a screen position: the pixel ray (unit view depth direction) meets the triangle's plane.
double plane_depth(const View& v, const std::array<glm::dvec3, 3>& tri, glm::dvec2 screen) {
  glm::dvec3 o, d;
  pixel_ray(v, screen, o, d);
  return intersect_plane(o, d, tri[0], tri[1], tri[2])->t;
}

bool interior(const GBuffer& g, int x, int y) {  // covered, with all 8 neighbours covered too
  for (int dy = -1; dy <= 1; ++dy)
    for (int dx = -1; dx <= 1; ++dx) {
      const int nx = x + dx, ny = y + dy;
      if (nx < 0 || ny < 0 || nx >= g.width || ny >= g.height || g.instance[g.index(nx, ny)] == kInvalidId) return false;
    }
  return true;
}

}  // namespace

TEST_CASE("position, depth and the face normal match the analytic triangle, either winding") {
  for (const bool reversed : {false, true}) {
    const Scene s = slanted_triangle_scene(reversed);
    const ScenePose pose = s.pose(0.0);
    const View view = make_view(s, pose, 96, 64);
    const GBuffer g = resolve_gbuffer(s, pose, view, rasterize(s, pose, view));
    const auto tri = world_triangle(s, pose, 0, 0);
    glm::dvec3 face = glm::normalize(glm::cross(tri[1] - tri[0], tri[2] - tri[0]));
    if (glm::dot(face, -tri[0]) < 0.0) face = -face;  // towards the eye at the origin
    double max_position_error = 0.0, max_normal_error = 0.0, max_depth_error = 0.0;
    int covered = 0;
    for (int y = 0; y < g.height; ++y)
      for (int x = 0; x < g.width; ++x) {
        const size_t i = g.index(x, y);
        if (g.instance[i] == kInvalidId) continue;
        ++covered;
        glm::dvec3 o, d;
        pixel_ray(view, {x + 0.5, y + 0.5}, o, d);
        const RayHit hit = *intersect_plane(o, d, tri[0], tri[1], tri[2]);
        max_position_error = std::max(max_position_error, glm::length(glm::dvec3(g.position[i]) - (o + hit.t * d)));
        max_depth_error = std::max(max_depth_error, std::abs(g.depth[i] - hit.t) / hit.t);
        max_normal_error = std::max(max_normal_error, glm::length(glm::dvec3(g.geo_normal[i]) - face));
        CHECK(g.normal[i] == g.geo_normal[i]);  // flat shading: the shading normal is the face normal
      }
    CHECK(covered > 500);
    CHECK(max_position_error < 1e-4);
    CHECK(max_depth_error < 1e-5);
    CHECK(max_normal_error < 1e-5);
  }
}

TEST_CASE("depth_grad matches finite differences of the analytic plane depth") {
  const Scene s = slanted_triangle_scene(false);
  const ScenePose pose = s.pose(0.0);
  for (const glm::vec2 jitter : {glm::vec2(0.0f), glm::vec2(0.3f, -0.2f)}) {
    const View view = make_view(s, pose, 96, 64, jitter);
    const GBuffer g = resolve_gbuffer(s, pose, view, rasterize(s, pose, view));
    const auto tri = world_triangle(s, pose, 0, 0);
    double max_relative_error = 0.0;
    int checked = 0;
    for (int y = 0; y < g.height; ++y)
      for (int x = 0; x < g.width; ++x) {
        if (!interior(g, x, y)) continue;
        const glm::dvec2 c(x + 0.5, y + 0.5);
        const double h = 1e-3;  // pixels; central differences of a smooth function in double
        const glm::dvec2 fd((plane_depth(view, tri, c + glm::dvec2(h, 0)) - plane_depth(view, tri, c - glm::dvec2(h, 0))) / (2 * h),
                            (plane_depth(view, tri, c + glm::dvec2(0, h)) - plane_depth(view, tri, c - glm::dvec2(0, h))) / (2 * h));
        const glm::dvec2 got(g.depth_grad[g.index(x, y)]);
        max_relative_error = std::max(max_relative_error, glm::length(got - fd) / glm::length(fd));
        ++checked;
      }
    CHECK(checked > 300);
    CHECK(max_relative_error < 1e-3);
  }
}

TEST_CASE("depth_grad stays finite at grazing angles") {
  Scene s = camera_scene();
  // A floor y = -1 reaching 10 km away: towards the horizon the view rays graze it.
  add_object(s, {{-1e4f, -1.0f, -1.0f}, {1e4f, -1.0f, -1.0f}, {0.0f, -1.0f, -1e4f}}, {{0, 1, 2}});
  const ScenePose pose = s.pose(0.0);
  const View view = make_view(s, pose, 64, 48);
  const GBuffer g = resolve_gbuffer(s, pose, view, rasterize(s, pose, view));
  int covered = 0, finite = 0;
  for (size_t i = 0; i < g.depth_grad.size(); ++i) {
    if (g.instance[i] == kInvalidId) continue;
    ++covered;
    finite += std::isfinite(g.depth_grad[i].x) && std::isfinite(g.depth_grad[i].y);
  }
  CHECK(covered > 64 * 20);
  CHECK(finite == covered);
  // A plane containing the view ray exactly (n . r = 0): the cosine floor bounds the gradient.
  const glm::vec2 centre(10.5f, 7.5f);
  const glm::vec3 r = view.view_dir_at_unit_depth(centre);
  const glm::vec3 n = glm::normalize(glm::cross(r, glm::vec3(0.0f, 1.0f, 0.0f)));  // n . r = 0
  const glm::vec2 grad = depth_gradient(view, centre, 2.0f, n);
  CHECK(std::isfinite(grad.x));
  CHECK(std::isfinite(grad.y));
  const float expected_x = -2.0f * n.x * (2.0f * view.tan_half_fov_x / 64.0f) / (kDepthGradMinCosine * glm::length(r));
  CHECK(std::abs(grad.x) == Approx(std::abs(expected_x)).epsilon(1e-3));
}

TEST_CASE("normals face the camera, the shading normal joins the geometric normal's hemisphere") {
  Scene s = camera_scene();
  // Seen from the back: the counter-clockwise front face points away from the camera (-Z), and so do the
  // vertex normals, which also tilt differently at each vertex.
  add_object(s, {{-1.0f, -1.0f, -3.0f}, {-1.0f, 1.0f, -3.0f}, {1.0f, 0.0f, -3.0f}}, {{0, 1, 2}});
  s.meshes[0].normals = {glm::normalize(glm::vec3(0.3f, 0.0f, -1.0f)), glm::normalize(glm::vec3(0.0f, 0.4f, -1.0f)),
                         glm::vec3(0.0f, 0.0f, -1.0f)};
  // A non-uniform scale and a rotation on the instance: normals go through normal_to_world.
  s.nodes[1].scale = {2.0f, 0.5f, 1.0f};
  s.nodes[1].rotation = glm::angleAxis(0.3f, glm::vec3(0, 1, 0));
  const ScenePose pose = s.pose(0.0);
  const View view = make_view(s, pose, 64, 48);
  const GBuffer g = resolve_gbuffer(s, pose, view, rasterize(s, pose, view));
  const auto tri = world_triangle(s, pose, 0, 0);
  const glm::dvec3 face = glm::normalize(glm::cross(tri[1] - tri[0], tri[2] - tri[0]));
  const Mesh& mesh = s.meshes[0];
  int covered = 0;
  for (size_t i = 0; i < g.instance.size(); ++i) {
    if (g.instance[i] == kInvalidId) continue;
    ++covered;
    const glm::dvec3 geo(g.geo_normal[i]), n(g.normal[i]);
    const glm::dvec3 to_eye = -glm::dvec3(g.position[i]);
    CHECK(glm::dot(geo, to_eye) > 0.0);                      // faces the camera
    CHECK(std::abs(std::abs(glm::dot(geo, face)) - 1.0) < 1e-5);  // and is the face normal, up to sign
    CHECK(glm::dot(n, geo) > 0.0);                          // shading normal in its hemisphere
    // The shading normal is the interpolated vertex normal through the inverse transpose, up to the flip.
    const float b1 = g.bary[i].x, b2 = g.bary[i].y, b0 = 1.0f - b1 - b2;
    const glm::vec3 interpolated = b0 * mesh.normals[0] + b1 * mesh.normals[1] + b2 * mesh.normals[2];
    const glm::dvec3 expected = glm::normalize(glm::dvec3(pose.normal_to_world[0] * interpolated));
    CHECK(glm::length(n + expected) < 1e-5);  // flipped: the vertex normals point away from the camera
  }
  CHECK(covered > 100);
}

TEST_CASE("albedo, roughness, metallic, emission and ids come from the material at time t") {
  Scene s = camera_scene();
  Texture tex;
  tex.width = 2;
  tex.height = 1;
  tex.texels = {{0.5f, 0.25f, 1.0f, 1.0f}, {1.0f, 0.5f, 0.0f, 1.0f}};
  s.textures.push_back(tex);
  Material m;
  m.base_color = {0.8f, 0.6f, 0.4f, 1.0f};
  m.base_color_texture = 0;
  m.roughness = 0.3f;
  m.metallic = 0.1f;
  m.emissive = {1.0f, 0.5f, 0.25f};
  m.emissive_strength_track.times = {0.0f, 1.0f};
  m.emissive_strength_track.values = {1.0f, 3.0f};  // 2 at t = 0.5
  const int mat = add_material(s, m);
  add_quad(s, 2.0f, {-0.6f, 0.0f, -3.0f}, glm::quat(1, 0, 0, 0), mat);  // instance 0, textured
  s.meshes[0].uvs = {{0.0f, 0.0f}, {1.0f, 0.0f}, {1.0f, 1.0f}, {0.0f, 1.0f}};
  add_quad(s, 1.0f, {0.8f, 0.0f, -3.0f});  // instance 1, glTF's default material
  const ScenePose pose = s.pose(0.5);
  const View view = make_view(s, pose, 64, 32);
  const GBuffer g = resolve_gbuffer(s, pose, view, rasterize(s, pose, view));
  int textured = 0, plain = 0;
  for (size_t i = 0; i < g.instance.size(); ++i) {
    if (g.instance[i] == 0) {
      ++textured;
      const glm::uvec3 t = s.meshes[0].triangles[g.triangle[i]];
      const float b1 = g.bary[i].x, b2 = g.bary[i].y, b0 = 1.0f - b1 - b2;
      const glm::vec2 uv = b0 * s.meshes[0].uvs[t[0]] + b1 * s.meshes[0].uvs[t[1]] + b2 * s.meshes[0].uvs[t[2]];
      const glm::vec3 expected = glm::vec3(m.base_color) * glm::vec3(tex.sample(uv));
      CHECK(glm::length(g.albedo[i] - expected) < 1e-6f);
      CHECK(g.roughness[i] == 0.3f);
      CHECK(g.metallic[i] == 0.1f);
      CHECK(glm::length(g.emission[i] - glm::vec3(2.0f, 1.0f, 0.5f)) < 1e-6f);
      CHECK(g.mesh[i] == 0);
      CHECK(g.material[i] == uint32_t(mat));
    } else if (g.instance[i] == 1) {
      ++plain;
      CHECK(g.albedo[i] == glm::vec3(1.0f));  // glTF default: base colour 1, roughness 1, metallic 1
      CHECK(g.roughness[i] == 1.0f);
      CHECK(g.metallic[i] == 1.0f);
      CHECK(g.emission[i] == glm::vec3(0.0f));
      CHECK(g.mesh[i] == 1);
      CHECK(g.material[i] == kInvalidId);
    }
  }
  CHECK(textured > 100);
  CHECK(plain > 50);
}

TEST_CASE("write_gbuffer / read_gbuffer: the layer names, background zeros, a round trip") {
  const Scene s = slanted_triangle_scene(false);
  const ScenePose pose = s.pose(0.0);
  const View view = make_view(s, pose, 33, 17);
  const GBuffer g = resolve_gbuffer(s, pose, view, rasterize(s, pose, view));
  Frame frame(33, 17);
  write_gbuffer(g, frame);
  for (const char* name : {"id.instance", "id.triangle", "id.mesh", "id.material"})
    CHECK_NOTHROW(frame.uint_channel(name));
  for (const char* name : {"bary.U", "bary.V", "position.X", "position.Y", "position.Z", "normal.X", "normal.Y",
                           "normal.Z", "geonormal.X", "geonormal.Y", "geonormal.Z", "depth.Z", "depth.dX", "depth.dY",
                           "albedo.R", "albedo.G", "albedo.B", "material.roughness", "material.metallic",
                           "emission.R", "emission.G", "emission.B"})
    CHECK_NOTHROW(frame.float_channel(name));
  CHECK(frame.float_channels().size() == 22);
  CHECK(frame.uint_channels().size() == 4);
  // Background: the corner (0, 0) sees nothing.
  REQUIRE(g.instance[0] == kInvalidId);
  for (const auto& [name, plane] : frame.float_channels()) CHECK(plane.data[0] == 0.0f);
  for (const auto& [name, plane] : frame.uint_channels()) CHECK(plane.data[0] == kInvalidId);

  const GBuffer r = read_gbuffer(frame);
  CHECK(r.width == 33);
  CHECK(r.height == 17);
  CHECK(r.instance == g.instance);
  CHECK(r.triangle == g.triangle);
  CHECK(r.bary == g.bary);
  CHECK(r.position == g.position);
  CHECK(r.normal == g.normal);
  CHECK(r.geo_normal == g.geo_normal);
  CHECK(r.depth == g.depth);
  CHECK(r.depth_grad == g.depth_grad);
  CHECK(r.albedo == g.albedo);
  CHECK(r.roughness == g.roughness);
  CHECK(r.metallic == g.metallic);
  CHECK(r.emission == g.emission);
  CHECK(r.mesh == g.mesh);
  CHECK(r.material == g.material);

  Frame missing(33, 17);
  write_gbuffer(g, missing);
  missing.add_uint("depth.dY");  // now a uint: the float channel is gone
  CHECK_THROWS_AS(read_gbuffer(missing), Error);
  CHECK_THROWS_AS(read_gbuffer(Frame(33, 17)), Error);
}
