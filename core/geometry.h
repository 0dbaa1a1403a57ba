// Small geometric helpers shared by the renderer, the motion vectors and the filters.
#pragma once

#include <glm/glm.hpp>

#include <cmath>

namespace rtdr {

// An orthonormal basis (t, b) around the unit vector n, right-handed (t x b = n), continuous everywhere but on the
// seam n.z = 0 where the sign flips: Duff et al. 2017, "Building an Orthonormal Basis, Revisited", Listing 3.
// copysign keeps n.z = -1 (where Frisvad's original divides by zero) and -0 safe. The BSDF's tangent frame
// (trace/brdf.h), the glossy vector's lobe (motion/glossy.h) and the cones' layout (filters/trmv/cones.h) use it.
inline void orthonormal_basis(const glm::vec3& n, glm::vec3& t, glm::vec3& b) {
  const float sign = std::copysign(1.0f, n.z);
  const float a = -1.0f / (sign + n.z);
  const float c = n.x * n.y * a;
  t = glm::vec3(1.0f + sign * n.x * n.x * a, sign * c, -sign * n.x);
  b = glm::vec3(c, sign + n.y * n.y * a, -n.y);
}

}  // namespace rtdr
