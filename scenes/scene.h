// The Scene model: what a glTF file becomes, and what every later stage reads.
//
// Geometry is flattened: each glTF mesh primitive (triangles only) becomes one Mesh with one material,
// and each (node, primitive) pair becomes one Instance. Node transforms are evaluated at any time t from
// the node hierarchy and its animation tracks; ScenePose holds them for one t so passes never re-walk
// the hierarchy per pixel. Colours are linear (sRGB textures are decoded on load).
#pragma once

#include "scenes/animation.h"

#include <glm/glm.hpp>
#include <glm/gtc/quaternion.hpp>

#include <cstdint>
#include <string>
#include <vector>

namespace rtdr {

struct Mesh {
  std::string name;
  std::vector<glm::vec3> positions;    // object space
  std::vector<glm::vec3> normals;      // per vertex; empty means flat shading (glTF spec: use face normals)
  std::vector<glm::vec2> uvs;          // TEXCOORD_0; may be empty
  std::vector<glm::uvec3> triangles;   // vertex indices, counter-clockwise front faces
  int material = -1;                   // index into Scene::materials; -1 is glTF's default material
};

struct Texture {
  int width = 0;
  int height = 0;
  std::vector<glm::vec4> texels;  // linear RGBA, row-major, row 0 at v = 0 (glTF's UV origin is top-left)

  // Bilinear lookup with REPEAT wrapping and texel centres at (i + 0.5) / width.
  glm::vec4 sample(glm::vec2 uv) const;
};

// glTF metallic-roughness material (glTF spec Sec. 3.9.2) plus KHR_materials_emissive_strength.
struct Material {
  std::string name;
  glm::vec4 base_color{1.0f};    // baseColorFactor, linear
  int base_color_texture = -1;   // index into Scene::textures, multiplied with base_color
  float roughness = 1.0f;        // roughnessFactor (glTF default 1)
  float metallic = 1.0f;         // metallicFactor (glTF default 1)
  glm::vec3 emissive{0.0f};      // emissiveFactor, linear, each in [0, 1]
  float emissive_strength = 1.0f;  // KHR_materials_emissive_strength
  // glTF `doubleSided` (default false). RTDR reads it for emission only: a double-sided emitter emits from both
  // faces, as Blender and Cycles do; a single-sided one from its counter-clockwise front face (scenes/README.md).
  // Both faces of every triangle are drawn and shaded either way.
  bool double_sided = false;
  // An animated emissive strength (a flickering light): material extras "rtdr_emissive_strength",
  // documented in scenes/README.md. Empty when the strength is constant.
  Track<float> emissive_strength_track;
};

// The smallest GGX alpha used, so a mirror (roughness 0) keeps a finite, sampleable lobe.
inline constexpr float kMinGgxAlpha = 1e-3f;
// The GGX alpha of a material's roughness: glTF's perceptual roughness squared (glTF spec Appendix B, "alpha =
// roughness^2"), at least kMinGgxAlpha. Here, beside the material, because both the path tracer's BRDF
// (trace/brdf.h) and the glossy motion vector (motion/glossy.h) read a lobe's width from it.
inline float ggx_alpha(float roughness) {
  const float alpha = roughness * roughness;
  return alpha > kMinGgxAlpha ? alpha : kMinGgxAlpha;  // std::max(kMinGgxAlpha, alpha), NaN included
}

struct Node {
  std::string name;
  int parent = -1;
  // Rest transform. A glTF `matrix` is decomposed into TRS on load (the spec forbids animating it).
  glm::vec3 translation{0.0f};
  glm::quat rotation{1.0f, 0.0f, 0.0f, 0.0f};  // glm order: w, x, y, z
  glm::vec3 scale{1.0f};
  Track<glm::vec3> translation_track;
  Track<glm::quat> rotation_track;
  Track<glm::vec3> scale_track;

  // T * R * S at time t, with animated channels replacing the rest values.
  glm::mat4 local_matrix(double t) const;
};

struct Instance {
  std::string name;  // "<node name>" or "<node name>/<primitive index>" when a mesh has several
  int node = -1;
  int mesh = -1;
};

// glTF perspective camera. The image's width/height overrides aspectRatio, so any --size works.
struct Camera {
  int node = -1;          // the camera looks down the node's -Z axis, +Y up (glTF spec Sec. 3.10)
  float yfov = 0.8f;      // vertical field of view, radians
  float znear = 0.05f;
  float zfar = 0.0f;      // 0 = infinite projection
};

struct ScenePose;

struct Scene {
  std::string name;    // file stem, e.g. "cornell"
  std::string source;  // the file it was loaded from
  // The scene's identity: FNV-1a (core/hash.h) of the glTF file's bytes and of every buffer and image it loads
  // (external .bin and image files included), as 16 hex digits. Two files of one name but other content differ
  // here; frames record it (rtdr.scene.hash, trace/render_key.h) and the frame cache keys on it. Empty for a
  // scene built in code.
  std::string content_hash;
  float fps = 30.0f;   // frame f is at time t = f / fps (scene extras "rtdr_fps", default 30)

  std::vector<Mesh> meshes;
  std::vector<Material> materials;
  std::vector<Texture> textures;
  std::vector<Node> nodes;          // parents always precede children
  std::vector<Instance> instances;
  Camera camera;

  double time_of_frame(int frame) const { return double(frame) / double(fps); }

  glm::mat4 node_to_world(int node, double t) const;
  ScenePose pose(double t) const;

  // Material of an instance; glTF's default material when the mesh has none.
  const Material& material_of_mesh(int mesh) const;
  float emissive_strength(const Material& m, double t) const;
};

// The scene's transforms at one time t.
struct ScenePose {
  double t = 0.0;
  std::vector<glm::mat4> instance_to_world;  // one per Scene::instances
  std::vector<glm::mat3> normal_to_world;    // inverse transpose of the upper 3x3
  glm::mat4 camera_to_world{1.0f};
};

}  // namespace rtdr
