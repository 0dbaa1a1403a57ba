// Shared helpers of the trace/ tests: materials, a small light-over-a-plane scene, everything a
// TraceContext refers to (built from a scene and a pose), bit-exact comparison, a running mean with
// its standard error for the Monte Carlo checks, and the closed form and quadrature of a polygon light.
#pragma once

#include "scene_fixtures.h"
#include "trace/embree_scene.h"
#include "trace/lights.h"
#include "trace/path_tracer.h"

#include <glm/glm.hpp>
#include <glm/gtc/quaternion.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>
#include <type_traits>
#include <utility>

namespace rtdr::test {

// A purely "diffuse" glTF material: metallic 0, roughness 1. (The glTF model still adds a GGX specular
// lobe with F0 = 0.04 and scales the Lambert lobe by 1 - F: trace/brdf.h.)
inline Material diffuse_material(float albedo) {
  Material m;
  m.base_color = glm::vec4(albedo, albedo, albedo, 1.0f);
  m.metallic = 0.0f;
  m.roughness = 1.0f;
  return m;
}

// An emitter of radiance Le (white): emissiveFactor (1, 1, 1) times an emissive strength of Le.
inline Material emissive_material(float radiance, float albedo = 0.0f) {
  Material m = diffuse_material(albedo);
  m.emissive = glm::vec3(1.0f);
  m.emissive_strength = radiance;
  return m;
}

// A rotation by `degrees` about +X. It turns +Z (add_quad's front) into (0, -sin, cos): +90 faces a quad
// down (-Y), -90 faces it up (+Y).
inline glm::quat about_x(float degrees) { return glm::angleAxis(glm::radians(degrees), glm::vec3(1.0f, 0.0f, 0.0f)); }

// A white square emitter of side `light_size` at height `light_height`, centred above the origin and
// facing down, over a 20 m x 20 m diffuse floor in the plane y = 0 that faces up. The camera stands at
// (0, 1.5, 4) looking down -Z, so the upper part of its image is sky (background).
struct LightOverPlane {
  Scene scene;
  int floor = -1;  // instance ids
  int light = -1;
};

inline LightOverPlane light_over_plane(float floor_albedo, float radiance, float light_size, float light_height) {
  LightOverPlane s{camera_scene(glm::vec3(0.0f, 1.5f, 4.0f)), -1, -1};
  const int floor_material = add_material(s.scene, diffuse_material(floor_albedo));
  const int light_material = add_material(s.scene, emissive_material(radiance));
  s.floor = add_quad(s.scene, 20.0f, glm::vec3(0.0f), about_x(-90.0f), floor_material);
  s.light = add_quad(s.scene, light_size, glm::vec3(0.0f, light_height, 0.0f), about_x(90.0f), light_material);
  return s;
}

// Everything a TraceContext refers to, for one scene at one pose. It owns the pose, so the Embree scene,
// the lights and the surface table (which keep references to it) stay valid; it cannot be copied or moved.
struct TraceWorld {
  const Scene& scene;
  ScenePose pose;
  EmbreeScene embree;
  LightSet lights;
  SurfaceTable surfaces;

  TraceWorld(const Scene& s, ScenePose p)
      : scene(s), pose(std::move(p)), embree(s, pose), lights(s, pose), surfaces(s, pose) {}
  explicit TraceWorld(const Scene& s, double t = 0.0) : TraceWorld(s, s.pose(t)) {}
  TraceWorld(const TraceWorld&) = delete;
  TraceWorld& operator=(const TraceWorld&) = delete;

  TraceContext context(TraceOptions options) const { return {scene, pose, embree, lights, surfaces, options}; }
};

inline TraceOptions bounces(int max_bounces) {
  TraceOptions o;
  o.max_bounces = max_bounces;
  return o;
}

// Bit-exact equality of two values of a plain type (floats compared by their bits: -0 differs from +0, and
// a NaN equals the same NaN), as "the same G and seed give a bit-identical result" means.
template <class T>
bool same_bits(const T& a, const T& b) {
  static_assert(std::is_trivially_copyable_v<T>);
  return std::memcmp(&a, &b, sizeof(T)) == 0;
}

// Every field of two path samples, bit for bit (fields one by one, so padding, if any, never counts).
inline bool same_path_sample(const PathSample& a, const PathSample& b) {
  const PathRecord &ra = a.record, &rb = b.record;
  return same_bits(a.direct, b.direct) && same_bits(a.indirect, b.indirect) &&
         same_bits(a.direct_unshadowed, b.direct_unshadowed) && same_bits(a.direct_visibility, b.direct_visibility) &&
         same_bits(a.indirect_diffuse, b.indirect_diffuse) && same_bits(a.indirect_glossy, b.indirect_glossy) &&
         same_bits(a.rays, b.rays) && same_bits(ra.light_position, rb.light_position) &&
         same_bits(ra.light_instance, rb.light_instance) && same_bits(ra.blocker_position, rb.blocker_position) &&
         same_bits(ra.blocker_instance, rb.blocker_instance) &&
         same_bits(ra.secondary_position, rb.secondary_position) &&
         same_bits(ra.secondary_instance, rb.secondary_instance) &&
         same_bits(ra.secondary_direction, rb.secondary_direction);
}

// Whether point p lies on one of the emitting triangles of `instance`: within `tolerance` of the
// triangle's plane, and with barycentrics of its projection in [0, 1] (to the same tolerance, relative).
inline bool on_emitter(const LightSet& lights, uint32_t instance, const glm::vec3& p, float tolerance) {
  for (const EmissiveTriangle& e : lights.lights()) {
    if (e.instance != instance) continue;
    const float height = glm::dot(p - e.p0, e.normal);  // signed distance to the triangle's plane
    if (std::abs(height) > tolerance) continue;
    // Barycentrics (b1, b2) of the projection q = p0 + b1 e1 + b2 e2, from the 2x2 normal equations.
    const glm::vec3 e1 = e.p1 - e.p0, e2 = e.p2 - e.p0, q = p - height * e.normal - e.p0;
    const float d11 = glm::dot(e1, e1), d12 = glm::dot(e1, e2), d22 = glm::dot(e2, e2);
    const float q1 = glm::dot(q, e1), q2 = glm::dot(q, e2);
    const float det = d11 * d22 - d12 * d12;
    const float b1 = (d22 * q1 - d12 * q2) / det, b2 = (d11 * q2 - d12 * q1) / det;
    if (b1 >= -tolerance && b2 >= -tolerance && b1 + b2 <= 1.0f + tolerance) return true;
  }
  return false;
}

// The mean of independent samples and its standard error sqrt(sample variance / n), in double.
struct RunningMean {
  double n = 0.0, sum = 0.0, sum2 = 0.0;

  void add(double x) {
    n += 1.0;
    sum += x;
    sum2 += x * x;
  }
  void add(const RunningMean& other) {
    n += other.n;
    sum += other.sum;
    sum2 += other.sum2;
  }
  double mean() const { return sum / n; }
  double standard_error() const {
    const double variance = (sum2 - sum * sum / n) / (n - 1.0);
    return std::sqrt(std::max(0.0, variance) / n);
  }
};

// The mean of an rgb value's three channels, in double.
inline double grey(const glm::vec3& c) { return (double(c.r) + double(c.g) + double(c.b)) / 3.0; }

// ---------------------------------------------------------------------------------------------------------
// Direct light from a polygon emitter, independently of the tracer: Lambert's formula and a quadrature
// (checked against each other in tests/trace_path_tracer_test.cpp), and the floor's surface samples.

// The corners of instance i's mesh in world space, in the mesh's order (a quad: a polygon loop).
inline std::array<glm::dvec3, 4> world_corners(const Scene& s, const ScenePose& pose, int i) {
  const Mesh& mesh = s.meshes[size_t(s.instances[size_t(i)].mesh)];
  const glm::dmat4 m(pose.instance_to_world[size_t(i)]);
  std::array<glm::dvec3, 4> out;
  for (size_t k = 0; k < 4; ++k) out[k] = glm::dvec3(m * glm::dvec4(glm::dvec3(mesh.positions[k]), 1.0));
  return out;
}

// Lambert's polygon formula (Lambert 1760; Arvo 1995, "Applications of Irradiance Tensors to the Simulation
// of Non-Lambertian Phenomena", Sec. 2):
// the irradiance at p, normal n, from a polygon of uniform radiance Le entirely above p's tangent plane,
//   E = Le / 2 | sum_i Theta_i (n . g_i) |,   r_i = unit(q_i - p),  Theta_i = acos(r_i . r_i+1),
//   g_i = unit(r_i x r_i+1),
// the absolute value taking care of the winding (the sign says whether the loop turns left or right).
inline double lambert_polygon_irradiance(const glm::dvec3& p, const glm::dvec3& n, const std::array<glm::dvec3, 4>& q,
                                  double radiance) {
  double sum = 0.0;
  for (size_t i = 0; i < q.size(); ++i) {
    const glm::dvec3 r0 = glm::normalize(q[i] - p), r1 = glm::normalize(q[(i + 1) % q.size()] - p);
    sum += std::acos(std::clamp(glm::dot(r0, r1), -1.0, 1.0)) * glm::dot(n, glm::normalize(glm::cross(r0, r1)));
  }
  return 0.5 * radiance * std::abs(sum);
}

// int_quad Le k(wi) cos_p cos_l / r^2 dA by the midpoint rule on a grid x grid lattice of the quad
// q(s, t) = q0 + s (q1 - q0) + t (q3 - q0): the area form of the light integral, independent of how the
// path tracer samples it. cos_p = n . wi at p; cos_l = n_l . (-wi) at the light, n_l its front normal
// (counter-clockwise, trace/lights.h); a point seen from behind does not count.
template <class Kernel>
double emitter_quadrature(const glm::dvec3& p, const glm::dvec3& n, const std::array<glm::dvec3, 4>& q,
                          double radiance, int grid, Kernel kernel) {
  const glm::dvec3 es = q[1] - q[0], et = q[3] - q[0];
  const glm::dvec3 area_normal = glm::cross(es, et);  // |es x et| ds dt = dA
  const glm::dvec3 n_light = glm::normalize(area_normal);
  const double dA = glm::length(area_normal) / (double(grid) * grid);
  double sum = 0.0;
  for (int i = 0; i < grid; ++i)
    for (int j = 0; j < grid; ++j) {
      const glm::dvec3 point = q[0] + ((i + 0.5) / grid) * es + ((j + 0.5) / grid) * et;
      const glm::dvec3 d = point - p;
      const double r2 = glm::dot(d, d);
      const glm::dvec3 wi = d / std::sqrt(r2);
      const double cos_p = glm::dot(n, wi), cos_l = -glm::dot(n_light, wi);
      if (cos_p > 0.0 && cos_l > 0.0) sum += kernel(wi) * cos_p * cos_l / r2;
    }
  return radiance * sum * dA;
}

// The floor's surface sample at a point of the floor, found by a ray straight down from 0.5 m above it
// (below the light at 1 m, so nothing else is in the way).
inline SurfaceSample floor_sample(const EmbreeScene& embree, const glm::vec3& point) {
  const Hit hit = embree.intersect({point + glm::vec3(0.0f, 0.5f, 0.0f), glm::vec3(0.0f, -1.0f, 0.0f)});
  return {hit.instance, hit.triangle, hit.bary};
}

}  // namespace rtdr::test
