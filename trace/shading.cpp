// The noise-free shading term S of TRMV [TRMV21 Sec. 4.3], a Monte Carlo stand-in for its LTC shading: the
// estimator, its random numbers and how it is recombined with visibility are described in shading.h.
#include "trace/shading.h"

#include "trace/brdf.h"

#include <algorithm>

namespace rtdr {

// S(x_0, wo) = int_A Le f cos(theta_x) cos(theta_y) / r^2 dA, no visibility, no MIS [TRMV21 Sec. 4.3], with the
// BSDF that trace_path uses at x_0 (its first vertex is never regularized).
glm::vec3 direct_shading(const TraceContext& c, const SurfaceSample& primary, const glm::vec3& eye, uint32_t seed,
                         uint32_t samples) {
  if (c.lights.empty() || samples == 0) return glm::vec3(0.0f);
  const SurfacePoint x = c.surfaces.at(primary, eye);
  const glm::vec3 wo = glm::normalize(eye - x.position);
  const Bsdf bsdf({x.albedo, x.roughness, x.metallic}, x.normal, wo);
  auto f = [&bsdf](const glm::vec3& wi) { return bsdf.evaluate(wi).f.total(); };
  return unshadowed_direct(c.lights, x, hash_combine(seed, kShadingStream), samples, f);
}

uint32_t shading_sample_count(int shading_samples, int spp) {
  // ceil(sqrt(N)) exactly: the smallest k with k^2 >= N (N <= 2^20, so k <= 1024).
  uint32_t k = 1;
  while (uint64_t(k) * k < uint64_t(std::max(spp, 1))) ++k;
  return uint32_t(std::max(shading_samples, 0)) * k;
}

}  // namespace rtdr
