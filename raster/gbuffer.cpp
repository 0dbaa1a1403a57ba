// G-buffer resolve: per pixel, the attributes of the surface sample the visibility buffer names.
// Inputs, outputs and layer names in raster/gbuffer.h; conventions in raster/README.md.
#include "raster/gbuffer.h"

#include "core/error.h"
#include "core/parallel.h"

#include <cmath>
#include <string>

namespace rtdr {
namespace {

// What every pixel of one mesh shares at time t: the material's constants, looked up once per resolve.
struct MeshShading {
  glm::vec3 base_color;
  const Texture* texture;  // nullptr when untextured or the mesh has no uvs
  float roughness;
  float metallic;
  glm::vec3 emission;      // emissive * emissive_strength(t)
  uint32_t material;       // kInvalidId for glTF's default material
};

std::vector<MeshShading> mesh_shading(const Scene& scene, double t) {
  std::vector<MeshShading> out;
  for (size_t m = 0; m < scene.meshes.size(); ++m) {
    const Mesh& mesh = scene.meshes[m];
    const Material& mat = scene.material_of_mesh(int(m));
    const bool textured = mat.base_color_texture >= 0 && !mesh.uvs.empty();
    out.push_back({glm::vec3(mat.base_color), textured ? &scene.textures[size_t(mat.base_color_texture)] : nullptr,
                   mat.roughness, mat.metallic, mat.emissive * scene.emissive_strength(mat, t),
                   mesh.material >= 0 ? uint32_t(mesh.material) : kInvalidId});
  }
  return out;
}

// Normalises v, or `fallback` when v has no direction (a degenerate triangle or normal).
glm::vec3 normalize_or(const glm::vec3& v, const glm::vec3& fallback) {
  const float len2 = glm::dot(v, v);
  return len2 > 0.0f ? v / std::sqrt(len2) : glm::normalize(fallback);
}

// What the resolve of every pixel reads.
struct ResolveInputs {
  const Scene& scene;
  const ScenePose& pose;
  const View& view;
  std::vector<MeshShading> shading;  // per mesh
  glm::mat3 n_world_to_view;         // world-space normals to view space
};

// The resolve of one covered pixel i, centre `centre`, whose visibility sample is s at depth `depth`.
void resolve_pixel(const ResolveInputs& in, const SurfaceSample& s, glm::vec2 centre, float depth, size_t i,
                   GBuffer& g) {
  const Scene& scene = in.scene;
  const uint32_t mesh_id = uint32_t(scene.instances[s.instance].mesh);
  const Mesh& mesh = scene.meshes[mesh_id];
  const glm::uvec3& tri = mesh.triangles[s.triangle];
  const float b1 = s.bary.x, b2 = s.bary.y, b0 = 1.0f - b1 - b2;  // Embree's (u, v) convention
  const glm::mat3& normal_to_world = in.pose.normal_to_world[s.instance];

  // Position: the barycentric combination of the vertices, moved to world space.
  const glm::vec3 position = world_point(scene, in.pose, s);
  // Geometric normal: the face normal, turned towards the eye (both faces are drawn).
  const glm::vec3 p0 = mesh.positions[tri[0]], p1 = mesh.positions[tri[1]], p2 = mesh.positions[tri[2]];
  const glm::vec3 to_eye = in.view.eye - position;
  glm::vec3 geo = normalize_or(normal_to_world * glm::cross(p1 - p0, p2 - p0), to_eye);
  if (glm::dot(geo, to_eye) < 0.0f) geo = -geo;
  // Shading normal: interpolated vertex normals (or the face normal), put in the geometric normal's hemisphere.
  glm::vec3 normal = geo;
  if (!mesh.normals.empty()) {
    const glm::vec3 n = b0 * mesh.normals[tri[0]] + b1 * mesh.normals[tri[1]] + b2 * mesh.normals[tri[2]];
    normal = normalize_or(normal_to_world * n, geo);
    if (glm::dot(normal, geo) < 0.0f) normal = -normal;
  }
  // Material: albedo is base colour times texture, the factor SVGF demodulates by.
  const MeshShading& m = in.shading[mesh_id];
  glm::vec3 albedo = m.base_color;
  if (m.texture) {
    const glm::vec2 uv = b0 * mesh.uvs[tri[0]] + b1 * mesh.uvs[tri[1]] + b2 * mesh.uvs[tri[2]];
    albedo *= glm::vec3(m.texture->sample(uv));
  }

  g.instance[i] = s.instance;
  g.triangle[i] = s.triangle;
  g.bary[i] = s.bary;
  g.position[i] = position;
  g.normal[i] = normal;
  g.geo_normal[i] = geo;
  g.depth[i] = depth;
  g.depth_grad[i] = depth_gradient(in.view, centre, depth, in.n_world_to_view * geo);
  g.albedo[i] = albedo;
  g.roughness[i] = m.roughness;
  g.metallic[i] = m.metallic;
  g.emission[i] = m.emission;
  g.mesh[i] = mesh_id;
  g.material[i] = m.material;
}

// A background pixel: every id kInvalidId, every float 0.
void clear_pixel(size_t i, GBuffer& g) {
  g.instance[i] = g.triangle[i] = g.mesh[i] = g.material[i] = kInvalidId;
  g.bary[i] = g.depth_grad[i] = glm::vec2(0.0f);
  g.position[i] = g.normal[i] = g.geo_normal[i] = g.albedo[i] = g.emission[i] = glm::vec3(0.0f);
  g.depth[i] = g.roughness[i] = g.metallic[i] = 0.0f;
}

// Channel names of the two-component layers that are not X/Y.
const char* const kBaryChannels[2] = {"bary.U", "bary.V"};
const char* const kDepthGradChannels[2] = {"depth.dX", "depth.dY"};

void write_vec2(Frame& frame, const char* const names[2], const std::vector<glm::vec2>& v) {
  for (int c = 0; c < 2; ++c) {
    FloatPlane& p = frame.add_float(names[c]);
    for (size_t i = 0; i < v.size(); ++i) p.data[i] = v[i][c];
  }
}

void read_vec2(const Frame& frame, const char* const names[2], std::vector<glm::vec2>& v) {
  for (int c = 0; c < 2; ++c) {
    const FloatPlane& p = frame.float_channel(names[c]);
    for (size_t i = 0; i < v.size(); ++i) v[i][c] = p.data[i];
  }
}

}  // namespace

GBuffer::GBuffer(int w, int h) : width(w), height(h) {
  const size_t n = size_t(w) * size_t(h);
  instance.assign(n, kInvalidId);
  triangle.assign(n, kInvalidId);
  bary.assign(n, glm::vec2(0.0f));
  position.assign(n, glm::vec3(0.0f));
  normal.assign(n, glm::vec3(0.0f));
  geo_normal.assign(n, glm::vec3(0.0f));
  depth.assign(n, 0.0f);
  depth_grad.assign(n, glm::vec2(0.0f));
  albedo.assign(n, glm::vec3(0.0f));
  roughness.assign(n, 0.0f);
  metallic.assign(n, 0.0f);
  emission.assign(n, glm::vec3(0.0f));
  mesh.assign(n, kInvalidId);
  material.assign(n, kInvalidId);
}

glm::vec2 depth_gradient(const View& view, glm::vec2 screen, float depth, const glm::vec3& n_view) {
  // The view direction at unit depth, r(s) = ((2 s_x / W - 1) tan_x, (1 - 2 s_y / H) tan_y, -1), and its
  // derivatives along screen x and screen y (screen y points down, view y up: hence the minus).
  const glm::vec3 r = view.view_dir_at_unit_depth(screen);
  const glm::vec3 dr_dsx(2.0f * view.tan_half_fov_x / float(view.width), 0.0f, 0.0f);
  const glm::vec3 dr_dsy(0.0f, -2.0f * view.tan_half_fov_y / float(view.height), 0.0f);
  // n . r -> 0 at grazing angles: keep its magnitude above kDepthGradMinCosine |n| |r|.
  const float floor = kDepthGradMinCosine * std::sqrt(glm::dot(n_view, n_view) * glm::dot(r, r));
  float n_dot_r = glm::dot(n_view, r);
  if (std::abs(n_dot_r) < floor) n_dot_r = n_dot_r < 0.0f ? -floor : floor;
  // dz/ds = -z (n . dr/ds) / (n . r), from z = d / (n . r) on the plane n . P = d  [SVGF17 Eq. 3's grad z].
  return {-depth * glm::dot(n_view, dr_dsx) / n_dot_r, -depth * glm::dot(n_view, dr_dsy) / n_dot_r};
}

GBuffer resolve_gbuffer(const Scene& scene, const ScenePose& pose, const View& view, const VisibilityBuffer& vis) {
  GBuffer g;
  resolve_gbuffer_into(scene, pose, view, vis, g);
  return g;
}

void resolve_gbuffer_into(const Scene& scene, const ScenePose& pose, const View& view, const VisibilityBuffer& vis,
                          GBuffer& g) {
  if (g.width != vis.width || g.height != vis.height) g = GBuffer(vis.width, vis.height);
  // Normals go from world to view space by the inverse transpose of world_to_view's 3x3, which is the
  // transpose of view_to_world's 3x3.
  const ResolveInputs in{scene, pose, view, mesh_shading(scene, pose.t), glm::transpose(glm::mat3(view.view_to_world))};
  parallel_rows(vis.height, [&](int y) {
    for (int x = 0; x < vis.width; ++x) {
      const size_t i = vis.index(x, y);
      const SurfaceSample s = vis.sample(x, y);
      if (s.valid())
        resolve_pixel(in, s, glm::vec2(float(x) + 0.5f, float(y) + 0.5f), vis.depth[i], i, g);
      else
        clear_pixel(i, g);
    }
  });
}

void write_gbuffer(const GBuffer& g, Frame& frame) {
  if (frame.width() != g.width || frame.height() != g.height)
    throw Error("write_gbuffer: frame is " + std::to_string(frame.width()) + "x" + std::to_string(frame.height()) +
                ", G-buffer is " + std::to_string(g.width) + "x" + std::to_string(g.height));
  frame.add_uint("id.instance").data = g.instance;
  frame.add_uint("id.triangle").data = g.triangle;
  frame.add_uint("id.mesh").data = g.mesh;
  frame.add_uint("id.material").data = g.material;
  write_vec2(frame, kBaryChannels, g.bary);
  frame.set_vec3("position", g.position);
  frame.set_vec3("normal", g.normal);
  frame.set_vec3("geonormal", g.geo_normal);
  frame.add_float("depth.Z").data = g.depth;
  write_vec2(frame, kDepthGradChannels, g.depth_grad);
  frame.set_rgb("albedo", g.albedo);
  frame.add_float("material.roughness").data = g.roughness;
  frame.add_float("material.metallic").data = g.metallic;
  frame.set_rgb("emission", g.emission);
}

GBuffer read_gbuffer(const Frame& frame) {
  GBuffer g(frame.width(), frame.height());
  g.instance = frame.uint_channel("id.instance").data;
  g.triangle = frame.uint_channel("id.triangle").data;
  g.mesh = frame.uint_channel("id.mesh").data;
  g.material = frame.uint_channel("id.material").data;
  read_vec2(frame, kBaryChannels, g.bary);
  g.position = frame.get_vec3("position");
  g.normal = frame.get_vec3("normal");
  g.geo_normal = frame.get_vec3("geonormal");
  g.depth = frame.float_channel("depth.Z").data;
  read_vec2(frame, kDepthGradChannels, g.depth_grad);
  g.albedo = frame.get_rgb("albedo");
  g.roughness = frame.float_channel("material.roughness").data;
  g.metallic = frame.float_channel("material.metallic").data;
  g.emission = frame.get_rgb("emission");
  return g;
}

}  // namespace rtdr
