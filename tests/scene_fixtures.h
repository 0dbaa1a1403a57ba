// Small Scenes built in code for the raster/ tests: a camera node plus a few triangles or quads, and the
// independent reference math (ray-triangle intersection, pinhole projection) the tests compare against.
#pragma once

#include "raster/view.h"
#include "raster/visibility.h"
#include "scenes/scene.h"

#include <glm/glm.hpp>
#include <glm/gtc/matrix_inverse.hpp>
#include <glm/gtc/quaternion.hpp>

#include <cmath>
#include <optional>
#include <vector>

namespace rtdr::test {

// A scene with only a camera: the camera node at `eye` with `rotation`, looking down its -Z axis.
inline Scene camera_scene(glm::vec3 eye = glm::vec3(0.0f), glm::quat rotation = glm::quat(1, 0, 0, 0),
                          float yfov = 0.8f, float znear = 0.05f) {
  Scene s;
  s.name = "fixture";
  Node camera;
  camera.name = "camera";
  camera.translation = eye;
  camera.rotation = rotation;
  s.nodes.push_back(camera);
  s.camera.node = 0;
  s.camera.yfov = yfov;
  s.camera.znear = znear;
  return s;
}

inline int add_material(Scene& s, const Material& m) {
  s.materials.push_back(m);
  return int(s.materials.size()) - 1;
}

// Adds a node at `translation` (rotation, scale optional), a mesh and an instance of it; returns the instance.
inline int add_object(Scene& s, std::vector<glm::vec3> positions, std::vector<glm::uvec3> triangles,
                      glm::vec3 translation = glm::vec3(0.0f), glm::quat rotation = glm::quat(1, 0, 0, 0),
                      glm::vec3 scale = glm::vec3(1.0f), int material = -1) {
  Node node;
  node.name = "node" + std::to_string(s.nodes.size());
  node.translation = translation;
  node.rotation = rotation;
  node.scale = scale;
  s.nodes.push_back(node);
  Mesh mesh;
  mesh.name = "mesh" + std::to_string(s.meshes.size());
  mesh.positions = std::move(positions);
  mesh.triangles = std::move(triangles);
  mesh.material = material;
  s.meshes.push_back(mesh);
  s.instances.push_back({node.name, int(s.nodes.size()) - 1, int(s.meshes.size()) - 1});
  return int(s.instances.size()) - 1;
}

// A square of side `size` in the object's XY plane, centred at its origin, facing +Z: two triangles
// sharing the diagonal from corner 0 to corner 2.
inline int add_quad(Scene& s, float size, glm::vec3 translation, glm::quat rotation = glm::quat(1, 0, 0, 0),
                    int material = -1) {
  const float h = 0.5f * size;
  return add_object(s, {{-h, -h, 0}, {h, -h, 0}, {h, h, 0}, {-h, h, 0}}, {{0, 1, 2}, {0, 2, 3}}, translation,
                    rotation, glm::vec3(1.0f), material);
}

// Moves instance i of a pose to a new world transform (and keeps its normal matrix consistent).
inline void set_instance_transform(ScenePose& pose, int i, const glm::mat4& m) {
  pose.instance_to_world[size_t(i)] = m;
  pose.normal_to_world[size_t(i)] = glm::inverseTranspose(glm::mat3(m));
}

// Reference ray-triangle intersection in double (Moller-Trumbore): distance t along the ray and the
// barycentrics (b1, b2) of vertices 1 and 2. Empty when the ray is parallel to the triangle's plane.
struct RayHit {
  double t;
  glm::dvec2 bary;
};
inline std::optional<RayHit> intersect_plane(glm::dvec3 origin, glm::dvec3 dir, glm::dvec3 p0, glm::dvec3 p1,
                                             glm::dvec3 p2) {
  const glm::dvec3 e1 = p1 - p0, e2 = p2 - p0;
  const glm::dvec3 q = glm::cross(dir, e2);
  const double det = glm::dot(e1, q);
  if (std::abs(det) < 1e-300) return std::nullopt;
  const glm::dvec3 o = origin - p0;
  const double b1 = glm::dot(o, q) / det;
  const glm::dvec3 r = glm::cross(o, e1);
  const double b2 = glm::dot(dir, r) / det;
  return RayHit{glm::dot(e2, r) / det, {b1, b2}};
}

// The ray through a screen position of a view, in double, built from the pinhole model directly
// (not through View::ray_through): with s = screen - jitter, the direction at unit view depth is
// ((2 s_x / W - 1) tx, (1 - 2 s_y / H) ty, -1).
inline void pixel_ray(const View& v, glm::dvec2 screen, glm::dvec3& origin, glm::dvec3& dir) {
  const glm::dvec2 s = screen - glm::dvec2(v.jitter);
  const glm::dvec3 d_view((2.0 * s.x / v.width - 1.0) * double(v.tan_half_fov_x),
                          (1.0 - 2.0 * s.y / v.height) * double(v.tan_half_fov_y), -1.0);
  const glm::dmat4 to_world(v.view_to_world);
  origin = glm::dvec3(to_world[3]);
  dir = glm::dmat3(to_world) * d_view;  // not normalised: t is then the view depth
}

// Pinhole projection in double: world point -> (screen x, screen y, depth), jitter added in pixels.
inline glm::dvec3 pinhole_project(const View& v, glm::dvec3 world) {
  const glm::dvec3 p = glm::dvec3(glm::dmat4(v.world_to_view) * glm::dvec4(world, 1.0));
  const double depth = -p.z;
  return {0.5 * v.width * (1.0 + p.x / (depth * v.tan_half_fov_x)) + v.jitter.x,
          0.5 * v.height * (1.0 - p.y / (depth * v.tan_half_fov_y)) + v.jitter.y, depth};
}

// World-space vertices of triangle `tri` of instance i at a pose, in double.
inline std::array<glm::dvec3, 3> world_triangle(const Scene& s, const ScenePose& pose, int i, int tri) {
  const Mesh& mesh = s.meshes[size_t(s.instances[size_t(i)].mesh)];
  const glm::dmat4 m(pose.instance_to_world[size_t(i)]);
  std::array<glm::dvec3, 3> out;
  for (int k = 0; k < 3; ++k)
    out[size_t(k)] = glm::dvec3(m * glm::dvec4(glm::dvec3(mesh.positions[mesh.triangles[size_t(tri)][k]]), 1.0));
  return out;
}

// Clip-space vertex for the low-level rasterizer from a screen position and depth on a width x height
// image (the inverse of View::project's screen mapping); exact for dyadic positions and power-of-two sizes.
inline glm::vec4 clip_from_screen(glm::vec2 screen, float depth, int width, int height) {
  const float ndc_x = 2.0f * screen.x / float(width) - 1.0f;
  const float ndc_y = 1.0f - 2.0f * screen.y / float(height);
  return {ndc_x * depth, ndc_y * depth, 0.0f, depth};
}

inline ClipTriangle screen_triangle(glm::vec2 a, glm::vec2 b, glm::vec2 c, int width, int height, float depth = 1.0f,
                                    uint32_t instance = 0, uint32_t triangle = 0) {
  return {{clip_from_screen(a, depth, width, height), clip_from_screen(b, depth, width, height),
           clip_from_screen(c, depth, width, height)},
          instance,
          triangle};
}

}  // namespace rtdr::test
