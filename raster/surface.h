// The surface a sample names: position, normals and material at one point of one triangle, at time t; the
// G-buffer attributes of [ASVGF18 Sec. 3.1] and the albedo SVGF demodulates by [SVGF17 Sec. 3].
//
// One definition for every consumer: the G-buffer resolve (primary hits, seen from the eye) and the path
// tracer (primary hits re-shaded from the visibility buffer, and secondary hits found by Embree), so the
// two can never disagree on what a surface is.
#pragma once

#include "raster/visibility.h"
#include "scenes/scene.h"

#include <glm/glm.hpp>

#include <cstdint>
#include <vector>

namespace rtdr {

struct SurfacePoint {
  glm::vec3 position{0.0f};    // world space
  glm::vec3 geo_normal{0.0f};  // unit face normal, turned towards the viewer (both faces are drawn)
  glm::vec3 normal{0.0f};      // unit shading normal (interpolated vertex normals), in geo_normal's hemisphere
  bool front_face = true;      // the viewer sees the counter-clockwise (glTF front) side
  glm::vec3 albedo{0.0f};      // base colour times texture, linear rgb
  float roughness = 1.0f;
  float metallic = 0.0f;
  glm::vec3 emission{0.0f};    // emissive * strength(t) when the viewer sees an emitting face (the front, or
                               // either face of a doubleSided material), else 0 (trace/lights.h)
  uint32_t mesh = kInvalidId;
  uint32_t material = kInvalidId;  // kInvalidId for glTF's default material
};

// The material constants of every mesh at one time t, looked up once per frame.
class SurfaceTable {
 public:
  SurfaceTable(const Scene& scene, const ScenePose& pose);

  // The surface at `sample`, seen from `viewer` (the eye, or the origin of the ray that found it).
  SurfacePoint at(const SurfaceSample& sample, const glm::vec3& viewer) const;

 private:
  struct MeshShading {
    glm::vec3 base_color;
    const Texture* texture;  // nullptr when untextured or the mesh has no uvs
    float roughness;
    float metallic;
    glm::vec3 emission;
    bool double_sided;  // glTF doubleSided: both faces emit
    uint32_t material;
  };
  const Scene& scene_;
  const ScenePose& pose_;
  std::vector<MeshShading> meshes_;
};

}  // namespace rtdr
