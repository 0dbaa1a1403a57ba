// load_scene: a glTF 2.0 file -> Scene (scenes/scene.h), in the order the parts depend on each other:
//   1. tinygltf parses the file (JSON or GLB, embedded base64 buffers and PNG/JPEG images);
//   2. materials and textures (gltf_materials.cpp);
//   3. meshes: every primitive of every glTF mesh becomes one Mesh, in file order;
//   4. nodes: walked from the scene's roots so that parents precede children; `matrix` -> T, R, S;
//   5. instances (one per node and primitive) and the camera (the first camera node in that order);
//   6. animations (gltf_animation.cpp), glTF's default material where a mesh has none, and the frame rate.
// Every index and byte range in the file is checked; problems throw rtdr::Error "<file>: <problem>".
#include "scenes/gltf_loader.h"

#include "scenes/catalog.h"

#include "core/error.h"
#include "core/hash.h"
#include "core/regular_file.h"
#include "scenes/gltf_parts.h"

#include <glm/gtc/quaternion.hpp>

#include <cmath>
#include <filesystem>
#include <numbers>

namespace rtdr {

using gltf::label;
using gltf::Source;

namespace {

bool ends_with(const std::string& s, const std::string& suffix) {
  return s.size() >= suffix.size() && s.compare(s.size() - suffix.size(), suffix.size(), suffix) == 0;
}

// tinygltf reports several problems as several lines; our errors are one line.
std::string one_line(std::string text) {
  for (char& c : text)
    if (c == '\n' || c == '\r') c = ';';
  while (!text.empty() && (text.back() == ';' || text.back() == ' ')) text.pop_back();
  return text.empty() ? "tinygltf could not parse it" : text;
}

// Parses the scene file at `path`; `files` reads it, and every file it names (gltf_files.cpp).
tinygltf::Model parse_file(const std::string& path, gltf::SceneFiles& files) {
  const std::string kind = describe_path_kind(path);
  if (kind == "missing")
    throw Error(path + ": no such scene file (a bare name like 'cornell' means " + shipped_scene_dir() +
                "/cornell.gltf)");
  if (kind != "a regular file") throw Error(path + ": the scene file is " + kind + ", not a regular file");
  tinygltf::TinyGLTF reader;
  files.attach(reader);
  tinygltf::Model model;
  std::string err, warn;  // warnings (unknown extensions and the like) are not errors for us
  bool ok = false;
  try {
    ok = ends_with(path, ".glb") ? reader.LoadBinaryFromFile(&model, &err, &warn, path)
                                 : reader.LoadASCIIFromFile(&model, &err, &warn, path);
  } catch (const std::exception& e) {  // tinygltf's JSON parser and containers may throw
    err = e.what();
  }
  // A refused file is an error even where tinygltf would go on without it (an image it cannot load).
  if (!files.refusal().empty()) throw Error(files.refusal());
  if (!ok) throw Error(path + ": not a valid glTF file: " + one_line(err));
  return model;
}

template <class Vec>
std::vector<Vec> group(const std::vector<float>& flat) {  // (x0, y0, z0, x1, ...) -> vectors of Vec::length()
  std::vector<Vec> out(flat.size() / size_t(Vec::length()));
  for (size_t i = 0; i < out.size(); ++i)
    for (int c = 0; c < Vec::length(); ++c) out[i][c] = flat[i * size_t(Vec::length()) + size_t(c)];
  return out;
}

// The triangles of a primitive with `n` vertices: from its index accessor, or vertices 0, 1, 2, ... when it
// has none (glTF spec Sec. 3.7.2.1). Every index must name a vertex.
std::vector<glm::uvec3> load_triangles(const Source& src, const tinygltf::Primitive& p, size_t n,
                                       const std::string& what) {
  std::vector<uint32_t> indices;
  if (p.indices >= 0) {
    indices = gltf::read_indices(src, p.indices, what + " indices");
  } else {
    for (size_t i = 0; i < n; ++i) indices.push_back(uint32_t(i));
  }
  if (indices.size() % 3 != 0)
    src.fail(what + " has " + std::to_string(indices.size()) + " indices, not a whole number of triangles");
  for (size_t i = 0; i < indices.size(); ++i)
    if (indices[i] >= n)
      src.fail(what + " index " + std::to_string(i) + " is " + std::to_string(indices[i]) + ", out of range (" +
               std::to_string(n) + " vertices)");
  std::vector<glm::uvec3> triangles;
  for (size_t i = 0; i < indices.size(); i += 3) triangles.emplace_back(indices[i], indices[i + 1], indices[i + 2]);
  return triangles;
}

// One primitive as a Mesh: POSITION, optional NORMAL and TEXCOORD_0 (one per position), the triangles and
// the material.
Mesh load_primitive(const Source& src, size_t mesh_index, size_t k) {
  const tinygltf::Mesh& gm = src.model.meshes[mesh_index];
  const tinygltf::Primitive& p = gm.primitives[k];
  const std::string what = "mesh " + label(gm.name, mesh_index) + " primitive " + std::to_string(k);
  if (p.mode != TINYGLTF_MODE_TRIANGLES)  // tinygltf fills in the default mode, 4 = TRIANGLES
    src.fail(what + " has mode " + std::to_string(p.mode) + "; only triangle lists (mode 4) are supported");
  if (!p.targets.empty()) src.fail(what + " has morph targets, which are not supported");
  auto attribute = [&](const char* key) {
    const auto it = p.attributes.find(key);
    return it == p.attributes.end() ? -1 : it->second;
  };

  Mesh mesh;
  const std::string base = gm.name.empty() ? "mesh" + std::to_string(mesh_index) : gm.name;
  mesh.name = gm.primitives.size() > 1 ? base + "/" + std::to_string(k) : base;
  if (attribute("POSITION") < 0) src.fail(what + " has no POSITION attribute");
  mesh.positions = group<glm::vec3>(gltf::read_floats(src, attribute("POSITION"), 3, what + " POSITION"));
  const size_t n = mesh.positions.size();
  if (attribute("NORMAL") >= 0)
    mesh.normals = group<glm::vec3>(gltf::read_floats(src, attribute("NORMAL"), 3, what + " NORMAL"));
  if (attribute("TEXCOORD_0") >= 0)
    mesh.uvs = group<glm::vec2>(gltf::read_floats(src, attribute("TEXCOORD_0"), 2, what + " TEXCOORD_0"));
  if (!mesh.normals.empty() && mesh.normals.size() != n)
    src.fail(what + " has " + std::to_string(mesh.normals.size()) + " normals for " + std::to_string(n) + " positions");
  if (!mesh.uvs.empty() && mesh.uvs.size() != n)
    src.fail(what + " has " + std::to_string(mesh.uvs.size()) + " TEXCOORD_0 for " + std::to_string(n) + " positions");
  mesh.triangles = load_triangles(src, p, n, what);

  if (p.material < -1 || p.material >= int(src.model.materials.size()))
    src.fail(what + " refers to material " + std::to_string(p.material) + ", out of range (the file has " +
             std::to_string(src.model.materials.size()) + ")");
  mesh.material = p.material;
  return mesh;
}

// A node's `matrix` (column-major) as T * R * S (glTF spec Sec. 3.5.3, which requires it to decompose):
// T is the last column, the scales are the lengths of the first three columns, R is what remains once the
// columns are divided by them. A mirror (negative determinant) becomes a negative x scale.
void decompose_matrix(const Source& src, const std::vector<double>& m, Node& node, const std::string& what) {
  glm::mat4 M;
  for (int i = 0; i < 16; ++i) M[i / 4][i % 4] = float(m[size_t(i)]);
  if (M[0][3] != 0.0f || M[1][3] != 0.0f || M[2][3] != 0.0f || M[3][3] != 1.0f)
    src.fail(what + " matrix is not affine (its last row must be 0 0 0 1)");
  node.translation = glm::vec3(M[3]);
  const glm::mat3 A(M);
  node.scale = glm::vec3(glm::length(A[0]), glm::length(A[1]), glm::length(A[2]));
  if (glm::determinant(A) < 0.0f) node.scale.x = -node.scale.x;
  if (node.scale.x == 0.0f || node.scale.y == 0.0f || node.scale.z == 0.0f) return;  // collapsed: no rotation to find
  const glm::mat3 R(A[0] / node.scale.x, A[1] / node.scale.y, A[2] / node.scale.z);
  node.rotation = glm::quat_cast(R);
  // A shear is not T * R * S: rebuilding R * S must give back the matrix (to float precision, relative).
  const glm::mat3 rebuilt = glm::mat3_cast(node.rotation) * glm::mat3(glm::scale(glm::mat4(1.0f), node.scale));
  float error = 0.0f, size = 1.0f;
  for (int c = 0; c < 3; ++c)
    for (int r = 0; r < 3; ++r) {
      error = std::max(error, std::abs(rebuilt[c][r] - A[c][r]));
      size = std::max(size, std::abs(A[c][r]));
    }
  if (error > 1e-4f * size) src.fail(what + " matrix has a shear, so it is not translation * rotation * scale");
}

Node load_node(const Source& src, size_t index, int parent) {
  const tinygltf::Node& gn = src.model.nodes[index];
  const std::string what = "node " + label(gn.name, index);
  Node node;
  node.name = gn.name.empty() ? "node" + std::to_string(index) : gn.name;
  node.parent = parent;
  if (gn.skin >= 0) src.fail(what + " is skinned; skins are not supported");
  for (const std::vector<double>* v : {&gn.translation, &gn.rotation, &gn.scale, &gn.matrix})
    for (double x : *v)
      if (!std::isfinite(x)) src.fail(what + " has a transform that is not finite");
  const bool trs = !gn.translation.empty() || !gn.rotation.empty() || !gn.scale.empty();
  if (!gn.matrix.empty() && trs) src.fail(what + " has both a matrix and translation/rotation/scale");
  if ((!gn.translation.empty() && gn.translation.size() != 3) || (!gn.rotation.empty() && gn.rotation.size() != 4) ||
      (!gn.scale.empty() && gn.scale.size() != 3) || (!gn.matrix.empty() && gn.matrix.size() != 16))
    src.fail(what + " has a translation, rotation, scale or matrix of the wrong length");
  if (gn.translation.size() == 3) node.translation = glm::vec3(gn.translation[0], gn.translation[1], gn.translation[2]);
  if (gn.rotation.size() == 4)
    node.rotation =
        glm::quat(float(gn.rotation[3]), float(gn.rotation[0]), float(gn.rotation[1]), float(gn.rotation[2]));
  if (gn.scale.size() == 3) node.scale = glm::vec3(gn.scale[0], gn.scale[1], gn.scale[2]);
  if (gn.matrix.size() == 16) decompose_matrix(src, gn.matrix, node, what);
  if (glm::length(node.rotation) < 1e-6f) src.fail(what + " rotation is a zero quaternion");
  return node;
}

// The scene's root nodes: those of the default scene (or of scene 0), or every node without a parent when
// the file has no scenes.
std::vector<int> root_nodes(const Source& src, const std::vector<int>& parent_of) {
  const tinygltf::Model& m = src.model;
  if (m.scenes.empty()) {
    std::vector<int> roots;
    for (size_t n = 0; n < m.nodes.size(); ++n)
      if (parent_of[n] < 0) roots.push_back(int(n));
    return roots;
  }
  const int s = m.defaultScene >= 0 ? m.defaultScene : 0;
  if (size_t(s) >= m.scenes.size()) src.fail("default scene " + std::to_string(s) + " is out of range");
  for (int n : m.scenes[size_t(s)].nodes)
    if (n < 0 || size_t(n) >= m.nodes.size())
      src.fail("scene " + std::to_string(s) + " lists node " + std::to_string(n) + ", out of range");
  return m.scenes[size_t(s)].nodes;
}

// Scene::nodes in depth-first pre-order from the roots, so every parent precedes its children.
// Returns node_of_gltf: glTF node index -> Scene node index, -1 for nodes not in the scene.
std::vector<int> load_nodes(const Source& src, Scene& scene, std::vector<int>& gltf_of_node) {
  const tinygltf::Model& m = src.model;
  // glTF spec Sec. 3.5.2: the nodes form disjoint trees, so no node has two parents.
  std::vector<int> parent_of(m.nodes.size(), -1);
  for (size_t n = 0; n < m.nodes.size(); ++n)
    for (int c : m.nodes[n].children) {
      if (c < 0 || size_t(c) >= m.nodes.size())
        src.fail("node " + std::to_string(n) + " has child " + std::to_string(c) + ", out of range");
      if (parent_of[size_t(c)] >= 0)
        src.fail("node " + std::to_string(c) + " has two parents (" + std::to_string(parent_of[size_t(c)]) + " and " +
                 std::to_string(n) + ")");
      parent_of[size_t(c)] = int(n);
    }

  // An explicit stack (a deep hierarchy must not overflow the call stack) of (glTF node, Scene parent).
  std::vector<int> node_of_gltf(m.nodes.size(), -1);
  const std::vector<int> roots = root_nodes(src, parent_of);
  std::vector<std::pair<int, int>> stack;
  for (auto r = roots.rbegin(); r != roots.rend(); ++r) stack.emplace_back(*r, -1);
  while (!stack.empty()) {
    const auto [n, parent] = stack.back();
    stack.pop_back();
    if (node_of_gltf[size_t(n)] >= 0)
      src.fail("node " + std::to_string(n) +
               " is reached twice from the scene's roots (a cycle in the node hierarchy)");
    node_of_gltf[size_t(n)] = int(scene.nodes.size());
    gltf_of_node.push_back(n);
    scene.nodes.push_back(load_node(src, size_t(n), parent));
    const std::vector<int>& children = m.nodes[size_t(n)].children;
    for (auto c = children.rbegin(); c != children.rend(); ++c) stack.emplace_back(*c, node_of_gltf[size_t(n)]);
  }
  return node_of_gltf;
}

// The first node (in Scene order) with a camera; it must be a valid perspective camera (glTF spec 3.10.2).
Camera load_camera(const Source& src, const Scene& scene, const std::vector<int>& gltf_of_node) {
  for (size_t i = 0; i < scene.nodes.size(); ++i) {
    const int c = src.model.nodes[size_t(gltf_of_node[i])].camera;
    if (c < 0) continue;
    if (size_t(c) >= src.model.cameras.size())
      src.fail("node '" + scene.nodes[i].name + "' refers to camera " + std::to_string(c) + ", out of range");
    const tinygltf::Camera& gc = src.model.cameras[size_t(c)];
    const std::string what = "camera " + label(gc.name, size_t(c));
    if (gc.type != "perspective") src.fail(what + " is " + gc.type + "; only perspective cameras are supported");
    // Checked as the floats the camera keeps, not as the JSON's doubles: a znear of 1e-300 is positive as a
    // double and 0 as a float. std::isnormal also refuses a float too small to divide by (a subnormal).
    const float yfov = float(gc.perspective.yfov), znear = float(gc.perspective.znear);
    const float zfar = float(gc.perspective.zfar);
    if (!(yfov > 0.0f && yfov < std::numbers::pi_v<float>) || !std::isnormal(yfov))
      src.fail(what + " yfov " + std::to_string(gc.perspective.yfov) + " is not in (0, pi)");
    if (!(znear > 0.0f && std::isnormal(znear)))
      src.fail(what + " znear " + std::to_string(gc.perspective.znear) + " is not a positive float");
    if (!(zfar == 0.0f || (zfar > znear && std::isfinite(zfar))))
      src.fail(what + " zfar must be 0 (infinite) or beyond znear");
    return Camera{int(i), yfov, znear, zfar};
  }
  src.fail("has no camera (add a node with a perspective camera)");
}

// glTF 2.x only: asset.version is "<major>.<minor>" (glTF spec 3.2, required), and a loader refuses a major version
// it does not know. tinygltf reads the field without checking it. minVersion, when given, names the lowest
// version that can read the asset; this loader reads 2.0.
void check_version(const Source& src) {
  const std::string& version = src.model.asset.version;
  const bool two_dot = version.size() > 2 && version.rfind("2.", 0) == 0 &&
                       version.find_first_not_of("0123456789", 2) == std::string::npos;
  if (!two_dot) src.fail("asset.version '" + version + "' is not glTF 2.x (this loader reads glTF 2.0)");
  const std::string& min_version = src.model.asset.minVersion;
  if (!min_version.empty() && min_version != "2.0")
    src.fail("asset.minVersion '" + min_version + "' needs a newer loader than this one (glTF 2.0)");
}

float load_fps(const Source& src) {
  const tinygltf::Model& m = src.model;
  const int s = m.defaultScene >= 0 ? m.defaultScene : 0;
  if (size_t(s) >= m.scenes.size() || !m.scenes[size_t(s)].extras.Has("rtdr_fps")) return 30.0f;
  const tinygltf::Value& value = m.scenes[size_t(s)].extras.Get("rtdr_fps");
  // Checked as the float the scene keeps: 1e-300 frames per second is positive as a double and 0 as a float,
  // and frame f's time f / fps would be NaN (found by fuzz/gltf_loader_fuzz too).
  const float fps = value.IsNumber() ? float(value.GetNumberAsDouble()) : 0.0f;
  if (!(fps > 0.0f && std::isnormal(fps))) src.fail("scene extras rtdr_fps must be a positive float");
  return fps;
}

// One Instance per (node, primitive) of every node with a mesh, in Scene node order.
void load_instances(const Source& src, const std::vector<int>& gltf_of_node,
                    const std::vector<int>& first_mesh_of_gltf_mesh, Scene& scene) {
  for (size_t i = 0; i < scene.nodes.size(); ++i) {
    const int m = src.model.nodes[size_t(gltf_of_node[i])].mesh;
    if (m < 0) continue;
    if (size_t(m) >= src.model.meshes.size())
      src.fail("node '" + scene.nodes[i].name + "' refers to mesh " + std::to_string(m) + ", out of range");
    const size_t primitives = src.model.meshes[size_t(m)].primitives.size();
    for (size_t k = 0; k < primitives; ++k) {
      const std::string name = primitives > 1 ? scene.nodes[i].name + "/" + std::to_string(k) : scene.nodes[i].name;
      scene.instances.push_back(Instance{name, int(i), first_mesh_of_gltf_mesh[size_t(m)] + int(k)});
    }
  }
}

// glTF spec Sec. 3.9.6: a primitive without a material uses the default material. It is appended once, so
// that every Mesh::material indexes Scene::materials.
void append_default_material(Scene& scene) {
  bool needed = false;
  for (const Mesh& mesh : scene.meshes) needed = needed || mesh.material < 0;
  if (!needed) return;
  for (Mesh& mesh : scene.meshes)
    if (mesh.material < 0) mesh.material = int(scene.materials.size());
  Material default_material;  // Material's initial values are glTF's defaults
  default_material.name = "default";
  scene.materials.push_back(default_material);
}

// Scene::content_hash: the file's bytes (those tinygltf parsed, not read again), then each buffer's bytes and each
// decoded image (size, components, bits, pixels) as tinygltf loaded them, whether embedded or from files beside
// the scene.
std::string content_hash(const std::vector<unsigned char>& bytes, const tinygltf::Model& model) {
  Fnv1a64 h;
  h.text(std::string(bytes.begin(), bytes.end()));
  for (const tinygltf::Buffer& buffer : model.buffers) h.text("buffer").bytes(buffer.data.data(), buffer.data.size());
  for (const tinygltf::Image& image : model.images) {
    const int32_t shape[4] = {image.width, image.height, image.component, image.bits};
    h.text("image").bytes(shape, sizeof shape).bytes(image.image.data(), image.image.size());
  }
  return h.hex();
}

}  // namespace

std::string resolve_scene_path(const std::string& name_or_path) {
  const bool is_path = name_or_path.find('/') != std::string::npos || ends_with(name_or_path, ".gltf") ||
                       ends_with(name_or_path, ".glb");
  return is_path ? name_or_path : shipped_scene_path(name_or_path);
}

Scene load_scene(const std::string& name_or_path) {
  Scene scene;
  scene.source = resolve_scene_path(name_or_path);
  scene.name = std::filesystem::path(scene.source).stem().string();
  gltf::SceneFiles files(scene.source);  // what tinygltf may read and decode (gltf_files.cpp)
  const tinygltf::Model model = parse_file(scene.source, files);
  const Source src{model, scene.source};
  check_version(src);
  scene.content_hash = content_hash(files.scene_bytes(), model);

  gltf::load_materials(src, scene);
  std::vector<int> first_mesh_of_gltf_mesh;  // glTF mesh -> its primitive 0's Mesh
  for (size_t m = 0; m < model.meshes.size(); ++m) {
    first_mesh_of_gltf_mesh.push_back(int(scene.meshes.size()));
    for (size_t k = 0; k < model.meshes[m].primitives.size(); ++k) scene.meshes.push_back(load_primitive(src, m, k));
  }

  std::vector<int> gltf_of_node;  // Scene node -> glTF node
  const std::vector<int> node_of_gltf = load_nodes(src, scene, gltf_of_node);
  load_instances(src, gltf_of_node, first_mesh_of_gltf_mesh, scene);
  scene.camera = load_camera(src, scene, gltf_of_node);
  gltf::load_animations(src, node_of_gltf, scene);
  append_default_material(scene);
  scene.fps = load_fps(src);
  return scene;
}

}  // namespace rtdr
