// The splat of shadow motion vectors [TRMV21 Sec. 4.1]. Window, weights and fallback: motion/shadow_splat.h.
#include "motion/shadow_splat.h"

#include "core/error.h"
#include "core/parallel.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <string>

namespace rtdr {

SplatMotion splat_shadow_motion_pixel(const std::vector<ShadowMotion>& shadow, const std::vector<glm::vec2>& surface_motion,
                                    const std::vector<float>& depth, int width, int height, int size, int x, int y) {
  const size_t p = size_t(y) * size_t(width) + size_t(x);
  const float z_p = depth[p];
  if (z_p <= 0.0f) return {};  // no surface: (0, 0)
  const int radius = size / 2;
  glm::vec2 sum(0.0f);
  int count = 0;  // splats landed: every weight is 1 (a box)
  for (int qy = std::max(0, y - radius); qy <= std::min(height - 1, y + radius); ++qy) {
    for (int qx = std::max(0, x - radius); qx <= std::min(width - 1, x + radius); ++qx) {
      const size_t q = size_t(qy) * size_t(width) + size_t(qx);
      if (!shadow[q].valid) continue;  // only in-shadow pixels with an Eq. 3 vector splat
      // The same surface: depths within kShadowSplatDepthRelative of the larger (symmetric in p and q).
      if (std::abs(depth[q] - z_p) > kShadowSplatDepthRelative * std::max(depth[q], z_p)) continue;
      sum += shadow[q].motion;
      ++count;
    }
  }
  // "weight averaged into the center of each filter" [TRMV21 Sec. 4.1]; nothing landed: the surface motion.
  if (count == 0) return {surface_motion[p], false};
  return {sum / float(count), true};
}

namespace {

// valid_before[(y + 1) (width + 1) + x + 1] = the number of valid vectors in rows 0..y, columns 0..x: a summed-area
// table, from which the count of any window is four look-ups.
std::vector<uint32_t> valid_counts(const std::vector<ShadowMotion>& shadow, int width, int height) {
  const size_t stride = size_t(width) + 1;
  std::vector<uint32_t> table(stride * (size_t(height) + 1), 0u);
  for (int y = 0; y < height; ++y) {
    uint32_t row = 0;
    for (int x = 0; x < width; ++x) {
      row += shadow[size_t(y) * size_t(width) + size_t(x)].valid ? 1u : 0u;
      table[(size_t(y) + 1) * stride + size_t(x) + 1] = table[size_t(y) * stride + size_t(x) + 1] + row;
    }
  }
  return table;
}

}  // namespace

void check_splat_inputs(const std::vector<ShadowMotion>& shadow, const std::vector<glm::vec2>& surface_motion,
                        const std::vector<float>& depth, int width, int height, int size) {
  const size_t pixels = size_t(width) * size_t(height);
  if (shadow.size() != pixels || surface_motion.size() != pixels || depth.size() != pixels)
    throw Error("splat_shadow_motion: planes of " + std::to_string(shadow.size()) + ", " +
                std::to_string(surface_motion.size()) + " and " + std::to_string(depth.size()) + " pixels for " +
                std::to_string(width) + "x" + std::to_string(height));
  if (size < 1 || size % 2 == 0)
    throw Error("splat_shadow_motion: the window's side must be odd and at least 1, not " + std::to_string(size));
}

std::vector<SplatMotion> splat_shadow_motion(const std::vector<ShadowMotion>& shadow,
                                           const std::vector<glm::vec2>& surface_motion, const std::vector<float>& depth,
                                           int width, int height, int size) {
  check_splat_inputs(shadow, surface_motion, depth, width, height, size);
  const size_t pixels = size_t(width) * size_t(height);
  // Speed only, the same result: a pixel whose window holds no valid vector at all keeps its surface motion (or
  // (0, 0) without a surface) without visiting the window's size^2 pixels, which most pixels far from any shadow
  // would do for nothing (rtdr bench --stage motion; tests/motion_shadow_splat_test.cpp compares both).
  const std::vector<uint32_t> counts = valid_counts(shadow, width, height);
  const size_t stride = size_t(width) + 1;
  const int radius = size / 2;
  std::vector<SplatMotion> out(pixels);
  parallel_rows(height, [&](int y) {
    const size_t y0 = size_t(std::max(0, y - radius)), y1 = size_t(std::min(height, y + radius + 1));
    for (int x = 0; x < width; ++x) {
      const size_t p = size_t(y) * size_t(width) + size_t(x);
      const size_t x0 = size_t(std::max(0, x - radius)), x1 = size_t(std::min(width, x + radius + 1));
      const uint32_t in_window = counts[y1 * stride + x1] - counts[y0 * stride + x1] - counts[y1 * stride + x0] +
                                 counts[y0 * stride + x0];
      if (in_window == 0)
        out[p] = {depth[p] > 0.0f ? surface_motion[p] : glm::vec2(0.0f), false};
      else
        out[p] = splat_shadow_motion_pixel(shadow, surface_motion, depth, width, height, size, x, y);
    }
  });
  return out;
}

}  // namespace rtdr
