// Shared helpers of the trace/ tests: materials, a small light-over-a-plane scene, everything a
// TraceContext refers to (built from a scene and a pose), bit-exact comparison, and a running mean with
// its standard error for the Monte Carlo checks.
#pragma once

#include "scene_fixtures.h"
#include "trace/embree_scene.h"
#include "trace/lights.h"
#include "trace/path_tracer.h"

#include <glm/glm.hpp>
#include <glm/gtc/quaternion.hpp>

#include <algorithm>
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

}  // namespace rtdr::test
