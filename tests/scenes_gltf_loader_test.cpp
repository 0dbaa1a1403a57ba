// Tests of scenes/gltf_loader.cpp (and gltf_accessors.cpp, gltf_materials.cpp): the shipped scenes load
// with the layout scenes/make_scenes.py gives them, tests/data/anim_test.gltf loads every field with the
// values written in scenes/make_test_fixtures.py, and every malformed fixture gives a one-line error that
// names the file. Animation sampling is in scenes_animation_test.cpp.
#include "scenes/catalog.h"
#include "scenes/gltf_loader.h"

#include "core/error.h"

#include <catch2/catch.hpp>
#include <glm/glm.hpp>

#include <unistd.h>

#include <array>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

using namespace rtdr;

namespace {

const std::string kData = RTDR_TEST_DATA_DIR;

int node_named(const Scene& s, const std::string& name) {
  for (size_t i = 0; i < s.nodes.size(); ++i)
    if (s.nodes[i].name == name) return int(i);
  return -1;
}

int instance_named(const Scene& s, const std::string& name) {
  for (size_t i = 0; i < s.instances.size(); ++i)
    if (s.instances[i].name == name) return int(i);
  return -1;
}

// World-space bounds of one instance at time t.
std::pair<glm::vec3, glm::vec3> world_bounds(const Scene& s, int instance, double t) {
  const glm::mat4 m = s.node_to_world(s.instances[size_t(instance)].node, t);
  glm::vec3 lo(1e30f), hi(-1e30f);
  for (const glm::vec3& p : s.meshes[size_t(s.instances[size_t(instance)].mesh)].positions) {
    const glm::vec3 w = glm::vec3(m * glm::vec4(p, 1.0f));
    lo = glm::min(lo, w);
    hi = glm::max(hi, w);
  }
  return {lo, hi};
}

// Triangles whose material emits light at time t.
int emissive_triangles(const Scene& s, double t) {
  int count = 0;
  for (const Instance& inst : s.instances) {
    const Material& m = s.material_of_mesh(inst.mesh);
    if (glm::length(m.emissive) * s.emissive_strength(m, t) > 0.0f)
      count += int(s.meshes[size_t(inst.mesh)].triangles.size());
  }
  return count;
}

}  // namespace

TEST_CASE("a bare name is a shipped scene, anything else a path") {
  CHECK(resolve_scene_path("cornell") == std::string(RTDR_SCENE_DIR) + "/cornell.gltf");
  CHECK(resolve_scene_path("dir/scene") == "dir/scene");
  CHECK(resolve_scene_path("scene.gltf") == "scene.gltf");
  CHECK(resolve_scene_path("scene.glb") == "scene.glb");
}

TEST_CASE("cornell: the box, two blocks, the light and the camera of the Cornell data") {
  const Scene s = load_scene("cornell");
  CHECK(s.name == "cornell");
  CHECK(s.fps == 30.0f);  // no rtdr_fps: the default
  // 5 walls + light + 2 blocks sharing one cube mesh; 4 materials, none missing, so no default appended.
  REQUIRE(s.instances.size() == 8);
  CHECK(s.meshes.size() == 7);
  REQUIRE(s.materials.size() == 4);
  const int short_box = instance_named(s, "short_box"), tall_box = instance_named(s, "tall_box");
  REQUIRE(short_box >= 0);
  REQUIRE(tall_box >= 0);
  CHECK(s.instances[size_t(short_box)].mesh == s.instances[size_t(tall_box)].mesh);
  CHECK(s.meshes[size_t(s.instances[size_t(tall_box)].mesh)].triangles.size() == 12);

  // Every vertex lies in the 2 m box x, z in [-1, 1], y in [0, 2].
  for (size_t i = 0; i < s.instances.size(); ++i) {
    const auto [lo, hi] = world_bounds(s, int(i), 0.0);
    CHECK(lo.x >= -1.0f - 1e-6f);
    CHECK(hi.x <= 1.0f + 1e-6f);
    CHECK(lo.y >= -1e-6f);
    CHECK(hi.y <= 2.0f + 1e-6f);
  }
  // The tall block is 1.2 m high and the short one 0.6 m (330 and 165 mm scaled by 2/556, rounded).
  CHECK(world_bounds(s, tall_box, 0.0).second.y == Approx(1.2f).margin(1e-5));
  CHECK(world_bounds(s, short_box, 0.0).second.y == Approx(0.6f).margin(1e-5));
  CHECK(world_bounds(s, short_box, 0.0).first.y == Approx(0.0f).margin(1e-5));

  // The light: two triangles emitting (17, 12, 4), 1 cm below the ceiling.
  CHECK(emissive_triangles(s, 0.0) == 2);
  const int light = instance_named(s, "light");
  REQUIRE(light >= 0);
  const Material& lm = s.material_of_mesh(s.instances[size_t(light)].mesh);
  const glm::vec3 radiance = lm.emissive * s.emissive_strength(lm, 0.0);
  CHECK(radiance.x == Approx(17.0f).margin(1e-4));
  CHECK(radiance.y == Approx(12.0f).margin(1e-4));
  CHECK(radiance.z == Approx(4.0f).margin(1e-4));
  CHECK(world_bounds(s, light, 0.0).first.y == Approx(1.99f).margin(1e-5));
  for (const Material& m : s.materials) CHECK(m.metallic == 0.0f);

  // Camera: 35 mm lens on 25 mm film, at mid-height 2.88 m in front of the opening, looking down -Z.
  REQUIRE(s.camera.node == node_named(s, "camera"));
  CHECK(s.camera.yfov == Approx(2.0 * std::atan(12.5 / 35.0)).margin(1e-5));
  const glm::mat4 camera = s.pose(0.0).camera_to_world;
  CHECK(camera[3].x == Approx(0.0f).margin(1e-5));
  CHECK(camera[3].y == Approx(1.0f).margin(1e-5));
  CHECK(camera[3].z == Approx(3.88f).margin(1e-5));
  CHECK(camera[2].z == Approx(1.0f).margin(1e-5));  // the view direction -Z is world -Z
}

TEST_CASE("pillars: eleven pillars sharing one mesh under one moving parent, lit from behind") {
  const Scene s = load_scene("pillars");
  const int parent = node_named(s, "pillars");
  REQUIRE(parent >= 0);
  int pillars = 0, pillar_mesh = -1;
  for (const Instance& inst : s.instances) {
    if (inst.name.rfind("pillar_", 0) != 0) continue;
    ++pillars;
    if (pillar_mesh < 0) pillar_mesh = inst.mesh;
    CHECK(inst.mesh == pillar_mesh);
    CHECK(s.nodes[size_t(inst.node)].parent == parent);
    CHECK(inst.node > parent);  // parents precede children
  }
  CHECK(pillars == 11);
  CHECK(s.instances.size() == 14);  // + floor, back wall, light
  CHECK(s.meshes.size() == 4);
  CHECK(s.nodes[size_t(parent)].translation_track.times.size() == 3);

  // At t = 1 s the parent is at x = 0, so the pillars stand at x = -2.5 ... 2.5, z = -1, 2.5 m high.
  const auto [lo, hi] = world_bounds(s, instance_named(s, "pillar_00"), 1.0);
  CHECK((lo.x + hi.x) / 2 == Approx(-2.5f).margin(1e-5));
  CHECK((lo.z + hi.z) / 2 == Approx(-1.0f).margin(1e-5));
  CHECK(hi.y - lo.y == Approx(2.5f).margin(1e-5));
  CHECK(world_bounds(s, instance_named(s, "pillar_10"), 1.0).first.x == Approx(2.4f).margin(1e-5));

  // The light is behind the pillars (smaller z) and above them, so their shadows fall towards the camera.
  const int light = instance_named(s, "light");
  REQUIRE(light >= 0);
  const auto [light_lo, light_hi] = world_bounds(s, light, 0.0);
  CHECK(light_hi.z < -1.0f);
  CHECK(light_lo.y > 2.5f);
  const Material& lm = s.material_of_mesh(s.instances[size_t(light)].mesh);
  CHECK(s.emissive_strength(lm, 0.0) == Approx(250.0f));
  CHECK(emissive_triangles(s, 0.0) == 2);
  for (const Material& m : s.materials) CHECK(m.metallic == 0.0f);

  // A static camera at (0, 1.7, 6), pitched 15 degrees down: its view axis -Z has y = -sin 15.
  const glm::mat4 camera = s.pose(0.0).camera_to_world;
  CHECK(camera[3].y == Approx(1.7f).margin(1e-5));
  CHECK(camera[3].z == Approx(6.0f).margin(1e-5));
  CHECK(-camera[2].y == Approx(-std::sin(glm::radians(15.0))).margin(1e-5));
  CHECK(s.nodes[size_t(s.camera.node)].translation_track.empty());
}

TEST_CASE("shipped scenes: every triangle winds counter-clockwise around its vertex normals") {
  // Emitters are one-sided (trace/lights.h): a flipped light triangle would shine away from its scene.
  for (const std::string& name : shipped_scene_names()) {
    INFO(name);
    const Scene s = load_scene(name);
    for (const Mesh& mesh : s.meshes) {
      REQUIRE(mesh.normals.size() == mesh.positions.size());
      for (const glm::uvec3& t : mesh.triangles) {
        // The geometric normal (p1 - p0) x (p2 - p0) of a counter-clockwise triangle points to its front.
        const glm::vec3 p0 = mesh.positions[t[0]], p1 = mesh.positions[t[1]], p2 = mesh.positions[t[2]];
        const glm::vec3 face = glm::normalize(glm::cross(p1 - p0, p2 - p0));
        for (int k = 0; k < 3; ++k) CHECK(glm::dot(face, mesh.normals[t[k]]) == Approx(1.0f).margin(1e-5));
      }
    }
  }
}

TEST_CASE("cornell: the walls face into the box") {
  const Scene s = load_scene("cornell");
  for (const char* wall : {"floor", "ceiling", "back_wall", "left_wall", "right_wall"}) {
    INFO(wall);
    const Mesh& mesh = s.meshes[size_t(s.instances[size_t(instance_named(s, wall))].mesh)];
    // From any vertex, the box's centre (0, 1, 0) lies on the side the normal points to.
    CHECK(glm::dot(mesh.normals[0], glm::vec3(0, 1, 0) - mesh.positions[0]) == Approx(1.0f).margin(1e-5));
  }
}

TEST_CASE("anim_test.gltf: nodes, meshes, instances, camera and frame rate") {
  const Scene s = load_scene(kData + "/anim_test.gltf");
  CHECK(s.name == "anim_test");
  CHECK(s.fps == 24.0f);
  CHECK(s.time_of_frame(12) == Approx(0.5));

  // The file lists child before parent; the loader puts the parent first.
  REQUIRE(s.nodes.size() == 5);  // parent, child, camera, matrix_node, mirror_node
  const int parent = node_named(s, "parent"), child = node_named(s, "child");
  CHECK(parent == 0);
  CHECK(child == 1);
  CHECK(s.nodes[size_t(child)].parent == parent);
  CHECK(s.nodes[size_t(parent)].translation.x == 5.0f);  // the rest value, replaced by the track when sampled

  // Mesh "parts" has two primitives: two Meshes, two instances named node/k.
  REQUIRE(s.meshes.size() == 2);
  CHECK(s.meshes[0].name == "parts/0");
  CHECK(s.meshes[1].name == "parts/1");
  REQUIRE(s.instances.size() == 2);
  CHECK(s.instances[0].name == "child/0");
  CHECK(s.instances[1].name == "child/1");
  CHECK(s.instances[1].node == child);
  CHECK(s.instances[1].mesh == 1);

  // Primitive 0: a quad with UNSIGNED_BYTE indices 0 1 2 0 2 3, normals +Z, uv (0, 1) at (-1, -1, 0).
  const Mesh& quad = s.meshes[0];
  REQUIRE(quad.triangles.size() == 2);
  CHECK(quad.triangles[1] == glm::uvec3(0, 2, 3));
  REQUIRE(quad.positions.size() == 4);
  CHECK(quad.positions[2] == glm::vec3(1, 1, 0));
  REQUIRE(quad.normals.size() == 4);
  CHECK(quad.normals[3] == glm::vec3(0, 0, 1));
  REQUIRE(quad.uvs.size() == 4);
  CHECK(quad.uvs[0] == glm::vec2(0, 1));
  // Primitive 1: non-indexed, so triangle (0, 1, 2); no normals, no uvs.
  const Mesh& triangle = s.meshes[1];
  REQUIRE(triangle.triangles.size() == 1);
  CHECK(triangle.triangles[0] == glm::uvec3(0, 1, 2));
  CHECK(triangle.normals.empty());
  CHECK(triangle.uvs.empty());

  REQUIRE(s.camera.node == node_named(s, "camera"));
  CHECK(s.camera.yfov == Approx(0.5f).margin(1e-6));
  CHECK(s.camera.znear == Approx(0.1f).margin(1e-6));
  CHECK(s.camera.zfar == Approx(100.0f).margin(1e-4));
  CHECK(s.pose(0.0).camera_to_world[3].z == Approx(10.0f).margin(1e-5));
}

TEST_CASE("anim_test.gltf: node matrices are decomposed into T, R, S that give back the matrix") {
  const Scene s = load_scene(kData + "/anim_test.gltf");
  // matrix_node: T(1, 2, 3) R(90 degrees about +Y) S(2, 3, 4). R maps x -> -z, z -> x; columns are
  // R(2 e_x) = (0, 0, -2), R(3 e_y) = (0, 3, 0), R(4 e_z) = (4, 0, 0), then the translation.
  const Node& m = s.nodes[size_t(node_named(s, "matrix_node"))];
  CHECK(m.translation == glm::vec3(1, 2, 3));
  CHECK(m.scale.x == Approx(2.0f).margin(1e-5));
  CHECK(m.scale.y == Approx(3.0f).margin(1e-5));
  CHECK(m.scale.z == Approx(4.0f).margin(1e-5));
  const float half = float(std::sqrt(0.5));  // quaternion of 90 degrees about +Y: (cos 45, 0, sin 45, 0)
  CHECK(std::abs(m.rotation.w) == Approx(half).margin(1e-5));
  CHECK(std::abs(m.rotation.y) == Approx(half).margin(1e-5));
  const glm::mat4 expected_m(0, 0, -2, 0, 0, 3, 0, 0, 4, 0, 0, 0, 1, 2, 3, 1);  // column-major, as in the file
  const glm::mat4 world_m = s.node_to_world(node_named(s, "matrix_node"), 0.0);
  for (int c = 0; c < 4; ++c)
    for (int r = 0; r < 4; ++r) CHECK(world_m[c][r] == Approx(expected_m[c][r]).margin(1e-5));

  // mirror_node: T(0, -1, 0) R(30 degrees about +Z) S(-1, 1, 1); the negative determinant becomes a
  // negative x scale, and T * R * S gives back the columns (-cos 30, -sin 30, 0), (-sin 30, cos 30, 0).
  const Node& mirror = s.nodes[size_t(node_named(s, "mirror_node"))];
  CHECK(mirror.scale.x == Approx(-1.0f).margin(1e-5));
  const float c30 = float(std::cos(glm::radians(30.0))), s30 = 0.5f;
  const glm::mat4 expected_mirror(-c30, -s30, 0, 0, -s30, c30, 0, 0, 0, 0, 1, 0, 0, -1, 0, 1);
  const glm::mat4 world_mirror = s.node_to_world(node_named(s, "mirror_node"), 0.0);
  for (int c = 0; c < 4; ++c)
    for (int r = 0; r < 4; ++r) CHECK(world_mirror[c][r] == Approx(expected_mirror[c][r]).margin(1e-5));
}

TEST_CASE("anim_test.gltf: materials, the default material, the sRGB texture, the emissive track") {
  const Scene s = load_scene(kData + "/anim_test.gltf");
  REQUIRE(s.materials.size() == 2);
  const Material& checker = s.materials[0];
  CHECK(checker.name == "checker");
  CHECK(checker.roughness == 0.5f);
  CHECK(checker.metallic == 0.0f);
  CHECK(checker.emissive == glm::vec3(1.0f, 0.5f, 0.25f));
  CHECK(checker.emissive_strength == 3.0f);
  CHECK(s.meshes[0].material == 0);

  // The triangle has no material: glTF's default one is appended (base colour 1, metallic 1, roughness 1).
  CHECK(s.meshes[1].material == 1);
  const Material& fallback = s.materials[1];
  CHECK(fallback.name == "default");
  CHECK(fallback.base_color == glm::vec4(1.0f));
  CHECK(fallback.metallic == 1.0f);
  CHECK(fallback.roughness == 1.0f);
  CHECK(fallback.base_color_texture == -1);

  // The 2x2 PNG, decoded with the sRGB function: 255 -> 1, 0 -> 0, 128 -> ((128/255 + 0.055)/1.055)^2.4
  // = 0.2158605; alpha is linear, 128 -> 128/255 = 0.5019608. Texel centres are at (i + 0.5) / 2.
  REQUIRE(checker.base_color_texture == 0);
  REQUIRE(s.textures.size() == 1);
  const Texture& tex = s.textures[0];
  CHECK(tex.width == 2);
  CHECK(tex.height == 2);
  const float grey = 0.2158605f, half = 128.0f / 255.0f;
  const glm::vec4 expected[2][2] = {{glm::vec4(1, 1, 1, 1), glm::vec4(0, 0, 0, 1)},
                                    {glm::vec4(grey, grey, grey, 1), glm::vec4(1, 0, grey, half)}};
  for (int y = 0; y < 2; ++y)
    for (int x = 0; x < 2; ++x) {
      const glm::vec4 v = tex.sample(glm::vec2((x + 0.5f) / 2.0f, (y + 0.5f) / 2.0f));
      for (int c = 0; c < 4; ++c) CHECK(v[c] == Approx(expected[y][x][c]).margin(1e-5));
    }
  // Halfway between the top two texels: the bilinear mean of white and black.
  CHECK(tex.sample(glm::vec2(0.5f, 0.25f)).r == Approx(0.5f).margin(1e-5));

  // The extras track LINEAR t = 0, 1, 2 -> 2, 4, 0 overrides the static strength 3.
  REQUIRE(checker.emissive_strength_track.times.size() == 3);
  CHECK(checker.emissive_strength_track.interpolation == Interpolation::Linear);
  CHECK(s.emissive_strength(checker, -1.0) == Approx(2.0f).margin(1e-5));  // before the first key
  CHECK(s.emissive_strength(checker, 0.25) == Approx(2.5f).margin(1e-5));  // 2 + 0.25 * (4 - 2)
  CHECK(s.emissive_strength(checker, 1.5) == Approx(2.0f).margin(1e-5));   // 4 + 0.5 * (0 - 4)
  CHECK(s.emissive_strength(checker, 9.0) == Approx(0.0f).margin(1e-5));   // after the last key
  CHECK(s.emissive_strength(fallback, 0.25) == 1.0f);
}

TEST_CASE("every malformed file throws one line that names the file and the problem") {
  // fixture (tests/data/<name>.gltf, written by scenes/make_test_fixtures.py) and a piece of the message
  const std::pair<const char*, const char*> cases[] = {
      {"bad_not_json", "not a valid glTF file"},
      {"bad_truncated", "not a valid glTF file"},
      {"bad_accessor_range", "out of range"},
      {"bad_buffer_view_range", "out of range"},
      {"bad_empty_buffer", "not a valid glTF file"},  // tinygltf rejects the empty data URI
      {"bad_index_range", "index 2 is 7, out of range (3 vertices)"},
      {"bad_lines", "only triangle lists"},
      {"bad_material_index", "material 5, out of range"},
      {"bad_nan_position", "not a finite number"},
      {"bad_no_camera", "has no camera"},
      {"bad_orthographic", "only perspective cameras"},
      {"bad_node_cycle", "cycle"},
      {"bad_unsorted_keys", "not strictly increasing"},
      {"bad_key_count", "3 key times but 2 values"},
      {"bad_cubicspline", "CUBICSPLINE"},
      {"bad_weights", "morph target weights"},
      {"bad_matrix_shear", "has a shear"},
      {"bad_emissive_track", "2 key times but 1 values"},
  };
  for (const auto& [name, problem] : cases) {
    const std::string file = std::string(name) + ".gltf";
    INFO(file);
    try {
      load_scene(kData + "/" + file);
      FAIL("no error");
    } catch (const Error& e) {
      const std::string message = e.what();
      INFO(message);
      CHECK(message.find('\n') == std::string::npos);
      CHECK(message.find(file) != std::string::npos);
      CHECK(message.find(problem) != std::string::npos);
    }
  }
}

TEST_CASE("a missing file or scene name throws one line naming it") {
  for (const std::string name : {"no_such_scene", "/no/such/dir/scene.gltf"}) {
    try {
      load_scene(name);
      FAIL("no error");
    } catch (const Error& e) {
      const std::string message = e.what();
      CHECK(message.find('\n') == std::string::npos);
      CHECK(message.find(resolve_scene_path(name)) != std::string::npos);
      CHECK(message.find("no such scene file") != std::string::npos);
    }
  }
}

TEST_CASE("glTF 2.x only: asset.version must be 2.<minor>, and minVersion at most 2.0") {
  const std::string cornell = [] {
    std::ifstream in(std::string(RTDR_SOURCE_DIR) + "/scenes/cornell.gltf");
    std::stringstream ss;
    ss << in.rdbuf();
    return ss.str();
  }();
  const std::string asset = "\"version\": \"2.0\"";
  REQUIRE(cornell.find(asset) != std::string::npos);
  const std::string path = (std::filesystem::temp_directory_path() / ("rtdr_version_" + std::to_string(::getpid()) + ".gltf")).string();
  auto load_with = [&](const std::string& replacement) {
    std::string text = cornell;
    text.replace(text.find(asset), asset.size(), replacement);
    std::ofstream(path) << text;
    return load_scene(path);
  };
  CHECK(load_with("\"version\": \"2.1\"").instances.size() > 0);
  for (const char* bad : {"\"version\": \"1.0\"", "\"version\": \"3.0\"", "\"version\": \"2\"", "\"version\": \"2.0b\""})
    CHECK_THROWS_WITH(load_with(bad), Catch::Contains("asset.version"));
  CHECK_THROWS_WITH(load_with("\"version\": \"2.1\", \"minVersion\": \"2.1\""), Catch::Contains("minVersion"));
  std::filesystem::remove(path);
}

TEST_CASE("numbers are checked as the floats they become") {
  // fuzz/gltf_loader_fuzz: rtdr_fps 1e-300 is a positive double but 0 as a float, so frame 0's time was
  // 0 / 0 = NaN, and sampling a track at NaN read past its last key. The same holds for znear, and 1e39 is a
  // finite double but an infinite float. Each case edits one number of anim_test.gltf.
  std::ifstream in(kData + "/anim_test.gltf");
  std::stringstream text;
  text << in.rdbuf();
  const std::string original = text.str();
  const std::vector<std::array<std::string, 3>> cases = {
      // {text in anim_test.gltf, replacement, expected problem}
      {"\"rtdr_fps\": 24", "\"rtdr_fps\": 1e-300", "rtdr_fps must be a positive"},
      {"\"rtdr_fps\": 24", "\"rtdr_fps\": 1e39", "rtdr_fps must be a positive"},
      {"\"rtdr_fps\": 24", "\"rtdr_fps\": \"24\"", "rtdr_fps must be a positive"},
      {"\"znear\": 0.1", "\"znear\": 1e-300", "znear"},
      {"\"zfar\": 100.0", "\"zfar\": 1e39", "zfar must be 0 (infinite) or beyond znear"},
      {"\"emissiveStrength\": 3.0", "\"emissiveStrength\": 1e39", "emissiveStrength is"},
  };
  int count = 0;
  for (const auto& [key, replacement, problem] : cases) {
    std::string modified = original;
    REQUIRE(modified.find(key) != std::string::npos);
    modified.replace(modified.find(key), key.size(), replacement);
    const std::string path =
        (std::filesystem::temp_directory_path() / ("rtdr_float_test_" + std::to_string(count++) + ".gltf")).string();
    std::ofstream(path) << modified;
    INFO(replacement);
    try {
      load_scene(path);
      FAIL("no error");
    } catch (const Error& e) {
      const std::string message = e.what();
      CHECK(message.find(path) != std::string::npos);
      CHECK(message.find(problem) != std::string::npos);
    }
    std::filesystem::remove(path);
  }
}
