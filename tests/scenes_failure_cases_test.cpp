// Tests of the six failure-case scenes that scenes/make_scenes.py writes (flicker, falling-light, glossy,
// fence, occlusion, static): every shipped scene loads and its camera sees surfaces that a light shines on
// directly, and each failure case's event happens at the time and by the amount that scenes/README.md
// documents, since the stability and lag measurements rely on those numbers.
#include "raster/gbuffer_frame.h"
#include "raster/view.h"
#include "raster/visibility.h"
#include "scenes/catalog.h"
#include "scenes/gltf_loader.h"
#include "scenes/scene.h"
#include "trace/embree_scene.h"
#include "trace/lights.h"

#include <catch2/catch.hpp>
#include <glm/glm.hpp>

#include <algorithm>
#include <cmath>
#include <string>
#include <utility>
#include <vector>

using namespace rtdr;

namespace {

const std::vector<std::string> kFailureCases = {"flicker", "falling-light", "glossy", "fence", "occlusion", "static"};

int instance_named(const Scene& s, const std::string& name) {
  for (size_t i = 0; i < s.instances.size(); ++i)
    if (s.instances[i].name == name) return int(i);
  return -1;
}

const Material& material_of_instance(const Scene& s, int instance) {
  return s.material_of_mesh(s.instances[size_t(instance)].mesh);
}

// An instance's vertex i in world space at `pose`.
glm::vec3 world_vertex(const Scene& s, const ScenePose& pose, int instance, size_t i) {
  const Mesh& mesh = s.meshes[size_t(s.instances[size_t(instance)].mesh)];
  return glm::vec3(pose.instance_to_world[size_t(instance)] * glm::vec4(mesh.positions[i], 1.0f));
}

// The mean of an instance's vertices in world space: the centre of a quad or a box.
glm::vec3 world_centre(const Scene& s, const ScenePose& pose, int instance) {
  const size_t n = s.meshes[size_t(s.instances[size_t(instance)].mesh)].positions.size();
  glm::vec3 sum(0.0f);
  for (size_t i = 0; i < n; ++i) sum += world_vertex(s, pose, instance, i);
  return sum / float(n);
}

// What the camera of one frame sees at 64x36, as fractions of the pixels.
struct Coverage {
  double surface = 0.0;  // a surface, not background
  double lit = 0.0;      // a surface point that some emissive triangle lights directly
};

// A surface point p is lit directly by an emissive triangle when it lies in front of the triangle's
// emitting (front) face, the triangle lies above p's surface, and a shadow ray from p to the triangle's
// centroid is not blocked. One centroid per triangle is enough to show that a light faces what is seen.
Coverage coverage_of_frame(const Scene& scene, int frame) {
  const int width = 64, height = 36;
  const FrameGeometry g = rasterize_frame(scene, frame, width, height);
  const LightSet lights(scene, g.pose);
  const EmbreeScene embree(scene, g.pose);
  size_t surface = 0, lit = 0;
  for (int y = 0; y < height; ++y) {
    for (int x = 0; x < width; ++x) {
      const SurfaceSample s = g.vis.sample(x, y);
      if (!s.valid()) continue;
      ++surface;
      const glm::vec3 p = world_point(scene, g.pose, s);
      const glm::uvec3 tri = scene.meshes[size_t(scene.instances[s.instance].mesh)].triangles[s.triangle];
      const int inst = int(s.instance);
      const glm::vec3 w0 = world_vertex(scene, g.pose, inst, tri[0]), w1 = world_vertex(scene, g.pose, inst, tri[1]),
                      w2 = world_vertex(scene, g.pose, inst, tri[2]);
      glm::vec3 n = glm::normalize(glm::cross(w1 - w0, w2 - w0));
      if (glm::dot(n, g.view.eye - p) < 0.0f) n = -n;  // the side the camera sees
      for (const EmissiveTriangle& e : lights.lights()) {
        if (e.instance == s.instance) continue;  // the emitter itself
        const glm::vec3 to_light = (e.p0 + e.p1 + e.p2) / 3.0f - p;
        const float d = glm::length(to_light);
        if (glm::dot(e.normal, to_light) >= 0.0f || glm::dot(n, to_light) <= 0.0f) continue;
        // The ray stops 1% short of the centroid, so it cannot hit the emitter itself.
        if (!embree.occluded({p + 1e-3f * n, to_light / d}, 0.0f, 0.99f * d)) {
          ++lit;
          break;
        }
      }
    }
  }
  const double pixels = double(width * height);
  return {double(surface) / pixels, double(lit) / pixels};
}

bool blue_light_on(const Scene& s, int frame) {
  const int blue = instance_named(s, "blue_light");
  return LightSet(s, s.pose(s.time_of_frame(frame))).find(uint32_t(blue), 0) >= 0;
}

}  // namespace

TEST_CASE("all eight shipped scenes load, at 30 fps, with lights") {
  const std::vector<std::string> names = shipped_scene_names();
  for (const char* expected :
       {"cornell", "pillars", "flicker", "falling-light", "glossy", "fence", "occlusion", "static"})
    CHECK(std::find(names.begin(), names.end(), expected) != names.end());
  for (const std::string& name : names) {
    INFO(name);
    const Scene s = load_scene(name);
    CHECK(s.name == name);
    CHECK(s.fps == 30.0f);
    CHECK_FALSE(LightSet(s, s.pose(0.0)).empty());
  }
}

TEST_CASE("every shipped scene's camera sees surfaces, and surfaces a light shines on") {
  // Measured at 64x36: the failure cases and pillars fill the whole image (closed rooms, or a floor and a
  // wall wider than the view), cornell's square box 53% of a 16:9 image. Directly lit: 10% in occlusion,
  // where by design only the wall above the cove is, 16% in falling-light once the lamp is down, 50-100%
  // elsewhere.
  for (const std::string& name : shipped_scene_names()) {
    const Scene s = load_scene(name);
    for (int frame : {0, 30, 60}) {
      const Coverage c = coverage_of_frame(s, frame);
      INFO(name << " frame " << frame << ": surface " << c.surface << ", directly lit " << c.lit);
      CHECK(c.surface >= 0.5);
      CHECK(c.lit >= 0.05);
    }
  }
}

TEST_CASE("flicker: the blue light switches at the documented frames, the red light sweeps fast") {
  const Scene s = load_scene("flicker");
  const int blue = instance_named(s, "blue_light"), red = instance_named(s, "red_light");
  REQUIRE(blue >= 0);
  REQUIRE(red >= 0);
  const Material& blue_material = material_of_instance(s, blue);
  CHECK(blue_material.emissive.b > 2.0f * std::max(blue_material.emissive.r, blue_material.emissive.g));
  const Material& red_material = material_of_instance(s, red);
  CHECK(red_material.emissive.r > 5.0f * std::max(red_material.emissive.g, red_material.emissive.b));

  // The documented switch: off just before t = 1.0 s, on from t = 1.0 s (frame 29 dark, frame 30 lit).
  CHECK(s.emissive_strength(blue_material, 1.0 - 1e-3) == 0.0f);
  CHECK(s.emissive_strength(blue_material, 1.0) > 0.0f);
  CHECK_FALSE(blue_light_on(s, 29));
  CHECK(blue_light_on(s, 30));
  // Every switch (scenes/README.md): the first frame of each new state, and the frame before it.
  const std::vector<std::pair<int, bool>> switches = {{15, false}, {30, true}, {42, false},
                                                      {53, true},  {64, false}, {75, true}};
  for (const auto& [frame, on] : switches) {
    INFO("frame " << frame);
    CHECK(blue_light_on(s, frame) == on);
    CHECK(blue_light_on(s, frame - 1) == !on);
  }
  CHECK(blue_light_on(s, 0));
  CHECK(blue_light_on(s, 89));

  // The red light: 4.8 m in 0.75 s, so 6.4 / 30 = 0.213 m between frames away from its turns.
  for (int frame : {5, 35, 50}) {
    const glm::vec3 a = world_centre(s, s.pose(s.time_of_frame(frame)), red);
    const glm::vec3 b = world_centre(s, s.pose(s.time_of_frame(frame + 1)), red);
    CHECK(glm::distance(a, b) == Approx(6.4 / 30.0).margin(1e-4));
  }
  // The camera moves: its position differs between consecutive frames.
  const glm::vec3 eye0(s.pose(s.time_of_frame(40)).camera_to_world[3]);
  const glm::vec3 eye1(s.pose(s.time_of_frame(41)).camera_to_world[3]);
  CHECK(glm::distance(eye0, eye1) > 0.02f);
}

TEST_CASE("falling-light: the light drops 2.5 m between t = 1.0 s and t = 1.5 s") {
  const Scene s = load_scene("falling-light");
  const int light = instance_named(s, "light");
  REQUIRE(light >= 0);
  const auto height = [&](double t) { return world_centre(s, s.pose(t), light).y; };
  CHECK(height(0.0) == Approx(3.0f).margin(1e-5));
  CHECK(height(1.0) == Approx(3.0f).margin(1e-5));   // frame 30: still up
  CHECK(height(1.25) == Approx(1.75f).margin(1e-5));  // LINEAR: half way
  CHECK(height(1.5) == Approx(0.5f).margin(1e-5));   // frame 45: down
  CHECK(height(3.0) == Approx(0.5f).margin(1e-5));
  CHECK(height(s.time_of_frame(30)) - height(s.time_of_frame(45)) == Approx(2.5f).margin(1e-5));

  // It is the scene's only light, and it faces down (its front-face normal is -Y).
  const LightSet lights(s, s.pose(1.5));
  REQUIRE_FALSE(lights.empty());
  for (const EmissiveTriangle& e : lights.lights()) {
    CHECK(e.instance == uint32_t(light));
    CHECK(e.normal.y == Approx(-1.0f).margin(1e-5));
  }
  const glm::vec3 eye0(s.pose(s.time_of_frame(40)).camera_to_world[3]);
  const glm::vec3 eye1(s.pose(s.time_of_frame(41)).camera_to_world[3]);
  CHECK(glm::distance(eye0, eye1) > 0.02f);
}

TEST_CASE("glossy: a metallic floor with roughness 0.15 and a fast camera") {
  const Scene s = load_scene("glossy");
  const int floor = instance_named(s, "room_floor");
  REQUIRE(floor >= 0);
  const Material& m = material_of_instance(s, floor);
  CHECK(m.name == "floor_metal");
  CHECK(m.roughness == Approx(0.15f).margin(1e-6));
  CHECK(m.metallic == 1.0f);
  for (const Material& other : s.materials)
    if (other.name != "floor_metal") CHECK(other.metallic == 0.0f);
  // 80 degrees of a 5.5 m circle in 2 s: 3.84 m/s, 0.128 m per frame.
  for (int frame : {10, 30, 50}) {
    const glm::vec3 a(s.pose(s.time_of_frame(frame)).camera_to_world[3]);
    const glm::vec3 b(s.pose(s.time_of_frame(frame + 1)).camera_to_world[3]);
    CHECK(glm::distance(a, b) == Approx(5.5 * glm::radians(80.0) / 60.0).epsilon(0.01));
  }
}

TEST_CASE("fence: the fence moves at least 6 px per frame at 640x360, in front of its light") {
  const Scene s = load_scene("fence");
  const int slat = instance_named(s, "slat_24");  // the middle of the fence
  REQUIRE(slat >= 0);
  const size_t vertex = 0;
  for (int frame : {5, 45, 75}) {  // away from the turns at frames 30 and 60
    const ScenePose p0 = s.pose(s.time_of_frame(frame)), p1 = s.pose(s.time_of_frame(frame + 1));
    const glm::vec3 a = make_view(s, p0, 640, 360).project(world_vertex(s, p0, slat, vertex));
    const glm::vec3 b = make_view(s, p1, 640, 360).project(world_vertex(s, p1, slat, vertex));
    INFO("frame " << frame << ": x " << a.x << " -> " << b.x);
    CHECK(a.z > 0.0f);
    CHECK((a.x >= 0.0f && a.x < 640.0f && a.y >= 0.0f && a.y < 360.0f));
    CHECK(std::abs(b.x - a.x) >= 6.0f);
  }
  // The light is behind the fence (further from the camera) and above its slats, so the slats' shadows
  // fall on the floor between the fence and the camera.
  const ScenePose pose = s.pose(0.0);
  const glm::vec3 light = world_centre(s, pose, instance_named(s, "light"));
  CHECK(light.z < -1.0f);
  CHECK(light.y > 3.0f);
  const LightSet lights(s, pose);
  REQUIRE_FALSE(lights.empty());
  for (const EmissiveTriangle& e : lights.lights()) CHECK(e.normal.z > 0.5f);  // tilted towards the camera
}

TEST_CASE("occlusion: a textured back wall that no light reaches directly, a hidden light, objects crossing") {
  const Scene s = load_scene("occlusion");
  const int wall = instance_named(s, "back_wall");
  REQUIRE(wall >= 0);
  const Material& m = material_of_instance(s, wall);
  REQUIRE(m.base_color_texture >= 0);
  const Texture& texture = s.textures[size_t(m.base_color_texture)];
  CHECK(texture.width == 32);
  CHECK(texture.height == 32);
  // A checker: the corner cells differ, diagonal cells match.
  CHECK(texture.texels[0] != texture.texels[8]);
  CHECK(texture.texels[0] == texture.texels[8 * 32 + 8]);

  // Every wall vertex lies behind every emitter's plane: the wall gets bounced light only.
  const ScenePose pose = s.pose(1.0);
  const LightSet lights(s, pose);
  REQUIRE_FALSE(lights.empty());
  const size_t wall_vertices = s.meshes[size_t(s.instances[size_t(wall)].mesh)].positions.size();
  for (const EmissiveTriangle& e : lights.lights())
    for (size_t i = 0; i < wall_vertices; ++i) CHECK(glm::dot(e.normal, world_vertex(s, pose, wall, i) - e.p0) < 0.0f);
  // The light lies inside the camera's frustum, and the valance hides it: no pixel sees it, at 640x360 or
  // 1280x720, at any time.
  const int light = instance_named(s, "light");
  REQUIRE(light >= 0);
  const glm::vec3 on_screen = make_view(s, pose, 640, 360).project(world_centre(s, pose, light));
  CHECK(on_screen.z > 0.0f);
  CHECK((on_screen.x > 0.0f && on_screen.x < 640.0f && on_screen.y > 0.0f && on_screen.y < 360.0f));
  for (auto [width, height] : {std::pair{640, 360}, std::pair{1280, 720}})
    for (int frame : {0, 30, 60, 90}) {
      const VisibilityBuffer vis = rasterize_frame(s, frame, width, height).vis;
      INFO(width << "x" << height << " frame " << frame);
      CHECK(std::count(vis.instance.begin(), vis.instance.end(), uint32_t(light)) == 0);
    }

  // The tall box crosses the room left to right over 3 s, the cube right to left.
  const int tall = instance_named(s, "tall_box"), cube = instance_named(s, "cube");
  REQUIRE(tall >= 0);
  REQUIRE(cube >= 0);
  CHECK(world_centre(s, s.pose(0.0), tall).x == Approx(-3.0f).margin(1e-5));
  CHECK(world_centre(s, s.pose(3.0), tall).x == Approx(3.0f).margin(1e-5));
  CHECK(world_centre(s, s.pose(0.0), cube).x == Approx(2.5f).margin(1e-5));
  CHECK(world_centre(s, s.pose(3.0), cube).x == Approx(-2.5f).margin(1e-5));
}

TEST_CASE("static: nothing moves and no light changes between t = 0 and t = 2 s") {
  const Scene s = load_scene("static");
  for (const Node& node : s.nodes) {
    INFO(node.name);
    CHECK(node.translation_track.empty());
    CHECK(node.rotation_track.empty());
    CHECK(node.scale_track.empty());
  }
  for (const Material& m : s.materials) CHECK(m.emissive_strength_track.empty());
  const ScenePose a = s.pose(0.0), b = s.pose(2.0);
  REQUIRE(a.instance_to_world.size() == b.instance_to_world.size());
  for (size_t i = 0; i < a.instance_to_world.size(); ++i) CHECK(a.instance_to_world[i] == b.instance_to_world[i]);
  CHECK(a.camera_to_world == b.camera_to_world);
  const LightSet la(s, a), lb(s, b);
  REQUIRE(la.lights().size() == lb.lights().size());
  for (size_t i = 0; i < la.lights().size(); ++i) CHECK(la.lights()[i].radiance == lb.lights()[i].radiance);
}
