// Shared fixtures of the TRMV pass tests (filters/trmv/).
#pragma once

#include "filters/image.h"

#include <random>

namespace rtdr {

// A w x h RGB plane of values uniform in [0, 1), the same for the same seed.
inline RgbPlane noise_rgb(int w, int h, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> u(0.0f, 1.0f);
  RgbPlane c(w, h);
  for (auto& v : c.data) v = glm::vec3(u(rng), u(rng), u(rng));
  return c;
}

}  // namespace rtdr
