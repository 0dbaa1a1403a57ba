// The area lights of one frame and their power-proportional choice, for next-event estimation [SVGF17 Sec. 3].
// See lights.h.
#include "trace/lights.h"

#include "core/color.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <numbers>

namespace rtdr {

namespace {

// Triangle t of an instance, in world space by `to_world`.
std::array<glm::vec3, 3> world_triangle(const Mesh& mesh, size_t t, const glm::mat4& to_world) {
  std::array<glm::vec3, 3> p;
  for (int k = 0; k < 3; ++k) p[size_t(k)] = glm::vec3(to_world * glm::vec4(mesh.positions[mesh.triangles[t][k]], 1.0f));
  return p;
}

float triangle_area(const std::array<glm::vec3, 3>& p) { return 0.5f * glm::length(glm::cross(p[1] - p[0], p[2] - p[0])); }

}  // namespace

LightSet::LightSet(const Scene& scene, const ScenePose& pose) : LightSet(scene, pose, pose) {}

// Chosen by the powers at `choice`, shaded at `pose`: re-shaded gradient samples choose as their seed's frame did
// [ASVGF18 Sec. 5.4].
LightSet::LightSet(const Scene& scene, const ScenePose& pose, const ScenePose& choice) {
  first_light_of_instance_.assign(scene.instances.size(), -1);
  instance_triangle_count_.assign(scene.instances.size(), 0);
  std::vector<double> power;  // Phi of each light at the choice pose
  for (size_t i = 0; i < scene.instances.size(); ++i) {
    const Mesh& mesh = scene.meshes[size_t(scene.instances[i].mesh)];
    const Material& material = scene.material_of_mesh(scene.instances[i].mesh);
    const glm::vec3 radiance = material.emissive * scene.emissive_strength(material, pose.t);
    const glm::vec3 radiance_at_choice = material.emissive * scene.emissive_strength(material, choice.t);
    // Not a light, or switched off at both times.
    if (luminance(radiance) <= 0.0f && luminance(radiance_at_choice) <= 0.0f) continue;
    first_light_of_instance_[i] = int(lights_.size());
    instance_triangle_count_[i] = int(mesh.triangles.size());
    for (size_t t = 0; t < mesh.triangles.size(); ++t) {
      const std::array<glm::vec3, 3> p = world_triangle(mesh, t, pose.instance_to_world[i]);
      EmissiveTriangle e;
      e.p0 = p[0];
      e.p1 = p[1];
      e.p2 = p[2];
      e.area = triangle_area(p);
      e.normal = e.area > 0.0f ? glm::cross(e.p1 - e.p0, e.p2 - e.p0) / (2.0f * e.area) : glm::vec3(0.0f, 1.0f, 0.0f);
      e.radiance = radiance;
      e.double_sided = material.double_sided;
      e.instance = uint32_t(i);
      e.triangle = uint32_t(t);
      lights_.push_back(e);
      // Power of a Lambertian emitter: Phi = pi * A * L per emitting face (luminance, so the choice follows
      // brightness); a double-sided triangle has two. (With choice = pose, area_at_choice is e.area, bit for bit.)
      const float area_at_choice = triangle_area(world_triangle(mesh, t, choice.instance_to_world[i]));
      const double faces = e.double_sided ? 2.0 : 1.0;
      power.push_back(faces * std::numbers::pi * double(area_at_choice) * double(luminance(radiance_at_choice)));
    }
  }
  double total = 0.0;
  for (double p : power) total += p;
  cdf_.resize(lights_.size());
  pmf_.resize(lights_.size());
  double running = 0.0;
  for (size_t l = 0; l < lights_.size(); ++l) {
    pmf_[l] = total > 0.0 ? float(power[l] / total) : 0.0f;
    running += power[l];
    cdf_[l] = total > 0.0 ? float(running / total) : 0.0f;
  }
  if (!cdf_.empty()) cdf_.back() = 1.0f;  // guard the last bin against rounding
  // No power to choose by: emissive triangles that all have zero area, or every light off at the choice time.
  if (total <= 0.0) *this = LightSet();
}

int LightSet::choose(float u_select) const {
  // The first light whose cumulative power exceeds u_select; zero-power lights (empty bins) are skipped.
  return std::min(int(std::upper_bound(cdf_.begin(), cdf_.end(), u_select) - cdf_.begin()), int(cdf_.size()) - 1);
}

LightSample LightSet::point_on(int l, glm::vec2 u_point) const {
  const EmissiveTriangle& e = lights_[size_t(l)];
  // Uniform point on the triangle: b0 = 1 - sqrt(u1), b1 = u2 sqrt(u1) (Shirley and Chiu 1997).
  const float s = std::sqrt(u_point.x);
  const float b0 = 1.0f - s, b1 = u_point.y * s;
  LightSample ls;
  ls.position = b0 * e.p0 + b1 * e.p1 + (1.0f - b0 - b1) * e.p2;
  ls.normal = e.normal;
  ls.radiance = e.radiance;
  ls.pdf_area = area_pdf(size_t(l));
  ls.light = l;
  ls.double_sided = e.double_sided;
  return ls;
}

LightSample LightSet::sample(float u_select, glm::vec2 u_point) const { return point_on(choose(u_select), u_point); }

LightSample LightSet::sample_reusing(glm::vec2 u) const {
  const int l = choose(u.x);
  // u.x lies in [cdf[l - 1], cdf[l]); its place in that interval is again uniform, and independent of the choice.
  const float lower = l > 0 ? cdf_[size_t(l) - 1] : 0.0f, width = cdf_[size_t(l)] - lower;
  const float reused = width > 0.0f ? std::clamp((u.x - lower) / width, 0.0f, 0x1.fffffep-1f) : 0.0f;
  return point_on(l, {reused, u.y});
}

float LightSet::area_pdf(size_t light) const {
  // A zero-area triangle has zero power and is never chosen: density 0, not 0/0.
  return lights_[light].area > 0.0f ? pmf_[light] / lights_[light].area : 0.0f;
}

int LightSet::find(uint32_t instance, uint32_t triangle) const {
  if (instance >= first_light_of_instance_.size()) return -1;
  const int first = first_light_of_instance_[instance];
  if (first < 0 || triangle >= uint32_t(instance_triangle_count_[instance])) return -1;
  return first + int(triangle);
}

float LightSet::pdf_area(uint32_t instance, uint32_t triangle) const {
  const int l = find(instance, triangle);
  return l < 0 ? 0.0f : area_pdf(size_t(l));
}

}  // namespace rtdr
