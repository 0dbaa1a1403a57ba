// G-buffer resolve: per pixel, the attributes of the surface sample the visibility buffer names.
// Inputs, outputs and layer names in raster/gbuffer.h; conventions in raster/README.md.
#include "raster/gbuffer.h"

#include "raster/surface.h"

#include "core/error.h"
#include "core/parallel.h"

#include <cmath>
#include <string>

namespace rtdr {
namespace {

// What the resolve of every pixel reads.
struct ResolveInputs {
  const View& view;
  SurfaceTable surfaces;      // materials at the pose's time
  glm::mat3 n_world_to_view;  // world-space normals to view space
};

// The resolve of one covered pixel i, centre `centre`, whose visibility sample is s at depth `depth`.
void resolve_pixel(const ResolveInputs& in, const SurfaceSample& s, glm::vec2 centre, float depth, size_t i,
                   GBuffer& g) {
  const SurfacePoint p = in.surfaces.at(s, in.view.eye);
  g.instance[i] = s.instance;
  g.triangle[i] = s.triangle;
  g.bary[i] = s.bary;
  g.position[i] = p.position;
  g.normal[i] = p.normal;
  g.geo_normal[i] = p.geo_normal;
  g.depth[i] = depth;
  g.depth_grad[i] = depth_gradient(in.view, centre, depth, in.n_world_to_view * p.geo_normal);
  g.albedo[i] = p.albedo;
  g.roughness[i] = p.roughness;
  g.metallic[i] = p.metallic;
  g.emission[i] = p.emission;
  g.mesh[i] = p.mesh;
  g.material[i] = p.material;
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
  const ResolveInputs in{view, SurfaceTable(scene, pose), glm::transpose(glm::mat3(view.view_to_world))};
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
