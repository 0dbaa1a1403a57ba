// Which faces of an emitter emit: a glTF material with doubleSided: true emits from both faces, as
// Blender and Cycles do; a single-sided one from its counter-clockwise front face only (trace/lights.h,
// raster/surface.h, scenes/README.md). Every place emission is met must agree:
// - the light set: a double-sided triangle has twice the power, pi A Le per face, and is chosen accordingly;
// - primary hits (SurfaceTable, the `emission` layer): the back face's emission is Le or 0;
// - next-event estimation, the BSDF rays that hit a light (weighted by MIS) and TRMV's shading term
//   (trace/shading.h): the direct light above the back of a double-sided light matches the quadrature over its
//   area, by light sampling alone (B = 0) and with MIS (B = 1); above a single-sided light's back it is 0.
#include "scenes/catalog.h"
#include "scenes/gltf_loader.h"
#include "trace/brdf.h"
#include "trace/path_tracer.h"
#include "trace/shading.h"
#include "trace_fixtures.h"

#include <catch2/catch.hpp>

#include <array>
#include <cmath>
#include <string>

using namespace rtdr;
using namespace rtdr::test;

namespace {

// light_over_plane's scene (a 0.5 m light at 1 m facing down over a floor) with a ceiling at 2 m facing down,
// so the light's back face looks at the ceiling; the light double-sided or not.
struct LightBetweenPlanes {
  LightOverPlane s;
  int ceiling = -1;
};

LightBetweenPlanes light_between_planes(bool double_sided) {
  LightBetweenPlanes out{light_over_plane(0.5f, 10.0f, 0.5f, 1.0f), -1};
  Scene& scene = out.s.scene;
  scene.materials[size_t(scene.meshes[size_t(scene.instances[size_t(out.s.light)].mesh)].material)].double_sided =
      double_sided;
  const int ceiling_material = add_material(scene, diffuse_material(0.5f));
  out.ceiling = add_quad(scene, 20.0f, glm::vec3(0.0f, 2.0f, 0.0f), about_x(90.0f), ceiling_material);
  return out;
}

// The ceiling's surface sample above a floor point, by a ray straight up from 1.5 m (above the light).
SurfaceSample ceiling_sample(const EmbreeScene& embree, const glm::vec3& point) {
  const Hit hit = embree.intersect({glm::vec3(point.x, 1.5f, point.z), glm::vec3(0.0f, 1.0f, 0.0f)});
  return {hit.instance, hit.triangle, hit.bary};
}

}  // namespace

TEST_CASE("doubleSided: a double-sided light has the power of two faces and is chosen twice as often") {
  // Two equal lights, one of them double-sided: powers pi A Le and 2 pi A Le, so choice probabilities 1/3 and 2/3.
  LightOverPlane s = light_over_plane(0.5f, 10.0f, 0.5f, 1.0f);
  Material twin = emissive_material(10.0f);
  twin.double_sided = true;
  const int twin_light = add_quad(s.scene, 0.5f, glm::vec3(2.0f, 1.0f, 0.0f), about_x(90.0f), add_material(s.scene, twin));
  const TraceWorld world(s.scene);
  // Each quad is two triangles of 0.125 m^2; a triangle's choice probability is pdf_area * area: 1/6 and 2/6.
  const float area = world.lights.lights()[0].area;
  CHECK(area == Approx(0.125f).epsilon(1e-5));
  CHECK(world.lights.pdf_area(uint32_t(s.light), 0) * area == Approx(1.0f / 6.0f).epsilon(1e-5));
  CHECK(world.lights.pdf_area(uint32_t(twin_light), 0) * area == Approx(2.0f / 6.0f).epsilon(1e-5));
  // A sample's emitted cosine: the back (up, +Y) counts only for the double-sided light.
  const LightSample single = world.lights.sample(0.1f, glm::vec2(0.5f));
  const LightSample both = world.lights.sample(0.9f, glm::vec2(0.5f));
  REQUIRE(!single.double_sided);
  REQUIRE(both.double_sided);
  CHECK(single.emitted_cosine(glm::vec3(0.0f, -1.0f, 0.0f)) == Approx(1.0f));
  CHECK(single.emitted_cosine(glm::vec3(0.0f, 1.0f, 0.0f)) == Approx(-1.0f));
  CHECK(both.emitted_cosine(glm::vec3(0.0f, 1.0f, 0.0f)) == Approx(1.0f));
}

TEST_CASE("doubleSided: primary hits see emission on both faces, single-sided on the front face only") {
  for (const bool double_sided : {false, true}) {
    const LightBetweenPlanes b = light_between_planes(double_sided);
    const TraceWorld world(b.s.scene);
    const SurfaceSample on_light{uint32_t(b.s.light), 0u, glm::vec2(1.0f / 3.0f)};
    const SurfacePoint below = world.surfaces.at(on_light, glm::vec3(0.1f, 0.0f, 0.1f));  // the front, facing down
    const SurfacePoint above = world.surfaces.at(on_light, glm::vec3(0.1f, 2.0f, 0.1f));  // the back
    INFO("double-sided " << double_sided);
    CHECK(below.front_face);
    CHECK(!above.front_face);
    CHECK(below.emission == glm::vec3(10.0f));
    CHECK(above.emission == (double_sided ? glm::vec3(10.0f) : glm::vec3(0.0f)));
  }
}

TEST_CASE("doubleSided: the direct light above a light's back matches the quadrature (NEE, MIS, shading term)") {
  // At ceiling points, L_direct = int_light Le f cos_p cos_l / r^2 dA over the light's back face: the same
  // quadrature as tests/trace_path_tracer_test.cpp's, with the corners in the opposite order (its normal is the
  // back's). 16384 independent samples, within 1% (>= 4 standard errors). B = 1 adds BSDF rays that hit the
  // back face (emission from raster/surface.h, MIS density from the light set), B = 0 is light sampling alone.
  constexpr int kSamples = 16384;
  const LightBetweenPlanes b = light_between_planes(true);
  const TraceWorld world(b.s.scene);
  const auto front = world_corners(b.s.scene, world.pose, b.s.light);
  const std::array<glm::dvec3, 4> back = {front[0], front[3], front[2], front[1]};
  const glm::vec3 eye(0.0f, 1.8f, 4.0f);  // between the light and the ceiling, looking at the ceiling
  const SurfaceBsdf bsdf{glm::vec3(0.5f), 1.0f, 0.0f};
  for (const glm::vec3 point : {glm::vec3(0.0f), glm::vec3(0.6f, 0.0f, 0.3f)}) {
    const SurfaceSample g = ceiling_sample(world.embree, point);
    REQUIRE(g.instance == uint32_t(b.ceiling));
    const SurfacePoint x = world.surfaces.at(g, eye);
    const glm::vec3 wo = glm::normalize(eye - x.position);
    auto brdf = [&](const glm::dvec3& wi) { return grey(bsdf_eval(bsdf, x.normal, wo, glm::vec3(wi)).total()); };
    const double expected = emitter_quadrature(glm::dvec3(x.position), glm::dvec3(x.normal), back, 10.0, 256, brdf);
    REQUIRE(expected > 0.1);
    for (const int bounces_b : {0, 1}) {
      const TraceContext c = world.context(bounces(bounces_b));
      RunningMean direct;
      for (int i = 0; i < kSamples; ++i)
        direct.add(grey(trace_path(c, g, eye, pixel_seed(6u, bounces_b, i, 0), 0).direct));
      INFO("ceiling point (" << point.x << ", " << point.z << "), max_bounces " << bounces_b << ": direct "
                             << direct.mean() << " +- " << direct.standard_error() << ", quadrature " << expected);
      CHECK(4.0 * direct.standard_error() < 0.01 * expected);
      CHECK(direct.mean() == Approx(expected).epsilon(0.01));
    }
    // TRMV's shading term, from 4096 light samples of one (0, 2)-net (no visibility: nothing is in the way).
    const double shading = grey(direct_shading(world.context(bounces(1)), g, eye, 7u, 4096));
    INFO("shading term " << shading << ", quadrature " << expected);
    CHECK(shading == Approx(expected).epsilon(0.01));
  }
  // The same ceiling over a single-sided light receives nothing directly, by any strategy.
  const LightBetweenPlanes one = light_between_planes(false);
  const TraceWorld one_world(one.s.scene);
  const SurfaceSample g = ceiling_sample(one_world.embree, glm::vec3(0.0f));
  const TraceContext c = one_world.context(bounces(1));
  double sum = 0.0;
  for (int i = 0; i < 1024; ++i) sum += grey(trace_path(c, g, eye, pixel_seed(8u, 0, i, 0), 0).direct);
  CHECK(sum == 0.0);
  CHECK(grey(direct_shading(c, g, eye, 7u, 256)) == 0.0);
}

TEST_CASE("doubleSided is read from glTF, and the shipped scenes' emitters are all single-sided") {
  // tests/data/diffuse-room.gltf (tools/make_diffuse_room.py) marks its light double-sided and nothing else.
  const Scene room = load_scene(std::string(RTDR_TEST_DATA_DIR) + "/diffuse-room.gltf");
  int double_sided = 0;
  for (const Material& m : room.materials) {
    INFO(m.name);
    CHECK(m.double_sided == (m.name == "light"));
    double_sided += m.double_sided;
  }
  CHECK(double_sided == 1);
  // scenes/make_scenes.py writes no doubleSided: the shipped lights keep shining from their fronts only, so
  // their events and tests are those they were measured with (scenes/README.md).
  for (const std::string& name : shipped_scene_names()) {
    const Scene scene = load_scene(name);
    for (const Material& m : scene.materials) {
      INFO(name << " material " << m.name);
      CHECK(!m.double_sided);
    }
  }
}
