// The area lights of one frame: every triangle whose material emits, in world space at the pose's time,
// with a table for choosing one in proportion to its power [SVGF17 Sec. 3: next-event estimation].
//
// Emitters are Lambertian: a triangle emits radiance Le = emissive * strength(t) from its front face
// (counter-clockwise winding, glTF's front) into the hemisphere around its geometric normal, and, when its
// material is glTF `doubleSided`, from its back face too (as Blender and Cycles emit; scenes/README.md). Its
// power is Phi = pi * A * luminance(Le) per emitting face: twice that for a double-sided triangle.
//
// The choice may follow another frame's powers than the one shaded (the `choice` pose): A-SVGF re-shades a
// gradient sample with the random numbers of the frame its seed was made in, and the same numbers pick the same
// light only under that frame's powers [ASVGF18 Sec. 5.4]. The set then holds every emitter lit at either time;
// it is chosen with the choice pose's powers and shaded with this frame's geometry and radiance. That estimator
// stays unbiased wherever every light lit now has a non-zero choice probability; a light that was off at the
// choice time is found only by BSDF rays (whose MIS weight is then 1).
#pragma once

#include "scenes/scene.h"

#include <glm/glm.hpp>

#include <cmath>
#include <cstdint>
#include <vector>

namespace rtdr {

struct EmissiveTriangle {
  glm::vec3 p0, p1, p2;  // world space
  glm::vec3 normal;      // unit front-face normal, (p1 - p0) x (p2 - p0) normalised
  float area;
  glm::vec3 radiance;    // Le
  bool double_sided;     // emits from both faces (glTF doubleSided), else from the front face only
  uint32_t instance, triangle;
};

struct LightSample {
  glm::vec3 position;
  glm::vec3 normal;
  glm::vec3 radiance;
  float pdf_area;   // probability density per unit area of choosing this point (light choice included)
  int light;        // index into LightSet::lights
  bool double_sided = false;  // the light emits from both faces

  // cos(theta_y) of a unit direction w leaving the light point: n.w for a one-sided emitter (0 or less when w
  // leaves its back, which does not emit), |n.w| for a double-sided one.
  float emitted_cosine(const glm::vec3& w) const {
    const float c = glm::dot(normal, w);
    return double_sided ? std::abs(c) : c;
  }
};

class LightSet {
 public:
  LightSet() = default;  // no lights
  LightSet(const Scene& scene, const ScenePose& pose);
  // Lights at `pose`, chosen in proportion to their power at `choice` (see above).
  LightSet(const Scene& scene, const ScenePose& pose, const ScenePose& choice);

  bool empty() const { return lights_.empty(); }
  const std::vector<EmissiveTriangle>& lights() const { return lights_; }

  // Picks a light by (the choice pose's) power with u_select, then a uniform point on it with u_point (uniform on the
  // triangle by the square-root warp, Shirley and Chiu 1997 / pbrt-v4 Sec. A.5.5).
  LightSample sample(float u_select, glm::vec2 u_point) const;
  // The same choice and point from one 2D number: u.x chooses the light, and its position inside that light's
  // interval of the cdf, rescaled to [0, 1), is the point's first coordinate (sample reuse, as pbrt-v4's
  // SampleDiscrete returns uRemapped). A stratified set of u then stays stratified on each light (trace/shading.h).
  LightSample sample_reusing(glm::vec2 u) const;
  // The area density with which sample() would have produced a point on triangle `triangle` of
  // `instance` (0 when it is not a light): used for MIS when a BSDF-sampled ray hits a light.
  float pdf_area(uint32_t instance, uint32_t triangle) const;
  // Index of the light for (instance, triangle), or -1.
  int find(uint32_t instance, uint32_t triangle) const;

 private:
  float area_pdf(size_t light) const;  // pmf / area
  int choose(float u_select) const;    // the light whose cdf interval holds u_select
  LightSample point_on(int light, glm::vec2 u_point) const;

  std::vector<EmissiveTriangle> lights_;
  std::vector<float> cdf_;                  // cdf_[i] = sum of the powers of lights 0..i, normalised to 1
  std::vector<float> pmf_;                  // probability of choosing light i
  std::vector<int> first_light_of_instance_;  // lights of an instance are contiguous, in triangle order
  std::vector<int> instance_triangle_count_;
};

}  // namespace rtdr
