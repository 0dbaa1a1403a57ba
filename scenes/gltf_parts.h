// Internal to the glTF loader: the pieces that scenes/gltf_loader.cpp assembles into a Scene.
//
//   gltf_accessors.cpp  reading accessors (vertex data, indices, key frames), with bounds checks
//   gltf_materials.cpp  materials and base colour textures, the animated emissive strength
//   gltf_animation.cpp  animation channels -> the nodes' translation, rotation and scale tracks
//
//   gltf_files.cpp      the files tinygltf may read: regular files below the scene's folder
//
// Only scenes/gltf_*.cpp include this header (tinygltf is a private dependency of rtdr_scenes).
#pragma once

#include "scenes/scene.h"

#include <tiny_gltf.h>

#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

namespace rtdr::gltf {

// The files tinygltf reads for the scene at `scene_path` (the scene file, and the buffers and images its URIs
// name): regular files below the scene file's folder, each within the memory budget, and images PNG or JPEG whose
// declared size fits the budget (gltf_files.cpp says why). attach() gives tinygltf our file and image callbacks;
// after a load, refusal() says why a file or image was refused ("<scene>: ..."), or is empty when none was.
class SceneFiles {
 public:
  explicit SceneFiles(const std::string& scene_path);
  void attach(tinygltf::TinyGLTF& reader);  // the callbacks point at this object: keep it alive while tinygltf loads
  const std::string& refusal() const { return refusal_; }
  // The scene file's bytes as tinygltf read and parsed them (empty before the load).
  const std::vector<unsigned char>& scene_bytes() const { return scene_bytes_; }
  void keep_scene_bytes(const std::vector<unsigned char>& bytes) { scene_bytes_ = bytes; }
  const std::string& scene() const { return scene_; }
  // Whether tinygltf may read `path`; records the refusal of a path outside the scene's folder.
  bool allowed(const std::string& path);
  void refuse(const std::string& why);  // keeps the first

 private:
  std::string scene_, base_;
  std::filesystem::path folder_;
  std::string refusal_;
  std::vector<unsigned char> scene_bytes_;
};

// The file being loaded: tinygltf's parsed model and the path that error messages name.
struct Source {
  const tinygltf::Model& model;
  std::string path;

  // Throws rtdr::Error("<path>: <problem>").
  [[noreturn]] void fail(const std::string& problem) const;
};

// "'name'" for a named object, "#index" for an unnamed one, as error messages name glTF objects.
std::string label(const std::string& name, size_t index);

// Reads accessor `accessor` as count * components floats; the accessor's type must have `components`
// components (1 = SCALAR ... 4 = VEC4). Integer components are converted as glTF says (normalised or not).
// Fails on a bad index, a range outside the buffer, or a NaN or infinite value. `what` names the use in
// error messages ("mesh 'box' POSITION").
std::vector<float> read_floats(const Source& src, int accessor, int components, const std::string& what);

// Reads a SCALAR accessor of UNSIGNED_BYTE, UNSIGNED_SHORT or UNSIGNED_INT as vertex indices.
std::vector<uint32_t> read_indices(const Source& src, int accessor, const std::string& what);

// Fails unless key times are strictly increasing (glTF spec Sec. 3.11: "input ... MUST be strictly
// increasing") and there is one value per key.
void check_keys(const Source& src, const std::vector<float>& times, size_t value_count, const std::string& what);

// Scene::materials and Scene::textures from the file's materials and their base colour images.
void load_materials(const Source& src, Scene& scene);

// Sets the nodes' animation tracks from every animation in the file. node_of_gltf[n] is the Scene node of
// glTF node n, or -1 when n is not part of the loaded scene (its channels are then skipped).
void load_animations(const Source& src, const std::vector<int>& node_of_gltf, Scene& scene);

}  // namespace rtdr::gltf
