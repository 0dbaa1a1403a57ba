// Surface attributes at a sample: the barycentric combination of the triangle's vertex data, moved to
// world space at the pose, and the mesh's material at the pose's time. See surface.h.
#include "raster/surface.h"

#include <cmath>

namespace rtdr {
namespace {

// Normalises v, or `fallback` when v has no direction (a degenerate triangle or normal).
glm::vec3 normalize_or(const glm::vec3& v, const glm::vec3& fallback) {
  const float len2 = glm::dot(v, v);
  return len2 > 0.0f ? v / std::sqrt(len2) : glm::normalize(fallback);
}

}  // namespace

SurfaceTable::SurfaceTable(const Scene& scene, const ScenePose& pose) : scene_(scene), pose_(pose) {
  meshes_.reserve(scene.meshes.size());
  for (size_t m = 0; m < scene.meshes.size(); ++m) {
    const Mesh& mesh = scene.meshes[m];
    const Material& mat = scene.material_of_mesh(int(m));
    const bool textured = mat.base_color_texture >= 0 && !mesh.uvs.empty();
    meshes_.push_back({glm::vec3(mat.base_color), textured ? &scene.textures[size_t(mat.base_color_texture)] : nullptr,
                       mat.roughness, mat.metallic, mat.emissive * scene.emissive_strength(mat, pose.t),
                       mat.double_sided, mesh.material >= 0 ? uint32_t(mesh.material) : kInvalidId});
  }
}

SurfacePoint SurfaceTable::at(const SurfaceSample& s, const glm::vec3& viewer) const {
  SurfacePoint p;
  p.mesh = uint32_t(scene_.instances[s.instance].mesh);
  const Mesh& mesh = scene_.meshes[p.mesh];
  const glm::uvec3& tri = mesh.triangles[s.triangle];
  const float b1 = s.bary.x, b2 = s.bary.y, b0 = 1.0f - b1 - b2;  // Embree's (u, v) convention
  const glm::mat3& normal_to_world = pose_.normal_to_world[s.instance];

  // Position: the barycentric combination of the vertices, moved to world space.
  p.position = world_point(scene_, pose_, s);
  // Geometric normal: the face normal (counter-clockwise winding is the front), turned towards the viewer.
  const glm::vec3 p0 = mesh.positions[tri[0]], p1 = mesh.positions[tri[1]], p2 = mesh.positions[tri[2]];
  const glm::vec3 to_viewer = viewer - p.position;
  p.geo_normal = normalize_or(normal_to_world * glm::cross(p1 - p0, p2 - p0), to_viewer);
  p.front_face = glm::dot(p.geo_normal, to_viewer) >= 0.0f;
  if (!p.front_face) p.geo_normal = -p.geo_normal;
  // Shading normal: interpolated vertex normals (or the face normal), put in the geometric normal's hemisphere.
  p.normal = p.geo_normal;
  if (!mesh.normals.empty()) {
    const glm::vec3 n = b0 * mesh.normals[tri[0]] + b1 * mesh.normals[tri[1]] + b2 * mesh.normals[tri[2]];
    p.normal = normalize_or(normal_to_world * n, p.geo_normal);
    if (glm::dot(p.normal, p.geo_normal) < 0.0f) p.normal = -p.normal;
  }
  // Material: albedo is base colour times texture, the factor SVGF demodulates by [SVGF17 Sec. 3].
  const MeshShading& m = meshes_[p.mesh];
  p.albedo = m.base_color;
  if (m.texture) {
    const glm::vec2 uv = b0 * mesh.uvs[tri[0]] + b1 * mesh.uvs[tri[1]] + b2 * mesh.uvs[tri[2]];
    p.albedo *= glm::vec3(m.texture->sample(uv));
  }
  p.roughness = m.roughness;
  p.metallic = m.metallic;
  // A single-sided emitter emits from its front face only; a glTF doubleSided one from both (trace/lights.h).
  p.emission = (p.front_face || m.double_sided) ? m.emission : glm::vec3(0.0f);
  p.material = m.material;
  return p;
}

}  // namespace rtdr
