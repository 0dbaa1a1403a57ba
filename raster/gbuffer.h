// G-buffer resolve: the surface attributes of every pixel's visibility sample [ASVGF18 Sec. 3.1].
//
// Pass: resolve_gbuffer(scene, pose, view, vis) -> GBuffer.
//   in:  the Scene at `pose`, the View the visibility buffer was rasterized with, the VisibilityBuffer
//   out: per pixel world position, shading and geometric normals, depth and its screen-space gradient,
//        albedo (the SVGF demodulation factor), roughness, metallic, emission, mesh and material ids.
//
// Layer names written by write_gbuffer (the contract, listed in docs/buffers.md):
//   uint:  id.instance id.triangle id.mesh id.material
//   float: bary.U bary.V  position.X/Y/Z  normal.X/Y/Z  geonormal.X/Y/Z  depth.Z depth.dX depth.dY
//          albedo.R/G/B  material.roughness material.metallic  emission.R/G/B
// Background pixels: every id kInvalidId, every float 0.
#pragma once

#include "core/frame.h"
#include "raster/view.h"
#include "raster/visibility.h"
#include "scenes/scene.h"

#include <glm/glm.hpp>

#include <cstdint>
#include <vector>

namespace rtdr {

struct GBuffer {
  int width = 0;
  int height = 0;
  // Kept from the visibility buffer.
  std::vector<uint32_t> instance;
  std::vector<uint32_t> triangle;
  std::vector<glm::vec2> bary;
  // Surface attributes.
  std::vector<glm::vec3> position;     // world space
  std::vector<glm::vec3> normal;       // shading normal, world space, unit, in geo_normal's hemisphere
  std::vector<glm::vec3> geo_normal;   // face normal, world space, unit, facing the camera
  std::vector<float> depth;            // linear view depth (the visibility buffer's)
  std::vector<glm::vec2> depth_grad;   // (d depth / d screen x, d depth / d screen y), per pixel
  std::vector<glm::vec3> albedo;       // base_color * texture(uv), linear rgb
  std::vector<float> roughness;
  std::vector<float> metallic;
  std::vector<glm::vec3> emission;     // emissive * emissive_strength(t), linear rgb
  std::vector<uint32_t> mesh;          // index into Scene::meshes
  std::vector<uint32_t> material;      // index into Scene::materials; kInvalidId for glTF's default material

  GBuffer() = default;
  GBuffer(int w, int h);  // all background

  size_t index(int x, int y) const { return size_t(y) * size_t(width) + size_t(x); }
  SurfaceSample sample(int x, int y) const {
    const size_t i = index(x, y);
    return {instance[i], triangle[i], bary[i]};
  }
};

// Cosine floor for the depth gradient at grazing angles: |n . r| / |r| is kept >= this (about 0.06 degrees
// from the plane), so depth_grad stays finite where the exact gradient diverges. SVGF's depth weight
// [SVGF17 Eq. 3] only needs its magnitude, and at such angles it is huge either way.
inline constexpr float kDepthGradMinCosine = 1.0e-3f;

GBuffer resolve_gbuffer(const Scene& scene, const ScenePose& pose, const View& view, const VisibilityBuffer& vis);
// The same, reusing the storage of `out` (every pixel is rewritten; reallocated only if the size differs).
void resolve_gbuffer_into(const Scene& scene, const ScenePose& pose, const View& view, const VisibilityBuffer& vis,
                          GBuffer& out);

// The screen-space depth gradient at `screen` of the plane with view-space normal n_view, at depth `depth`
// [SVGF17 Eq. 3 needs it]: with P = z r(s) on the plane n . P = d, z = d / (n . r) and
// dz/ds = -z (n . dr/ds) / (n . r).
glm::vec2 depth_gradient(const View& view, glm::vec2 screen, float depth, const glm::vec3& n_view);

// Writes every layer listed above (adding or replacing channels). The frame must have the same size.
void write_gbuffer(const GBuffer& g, Frame& frame);
// Reads every layer listed above; throws rtdr::Error naming the first missing channel.
GBuffer read_gbuffer(const Frame& frame);

}  // namespace rtdr
