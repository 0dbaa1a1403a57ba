// TRMV's splat of shadow motion vectors [TRMV21 Sec. 4.1]. Window, weights and fallback: filters/trmv/splat.h.
#include "filters/trmv/splat.h"

#include "core/error.h"
#include "core/parallel.h"

#include <algorithm>
#include <cstdint>
#include <string>
#include <vector>

namespace rtdr {

bool trmv_splat_same_surface(const TrmvSplatPlanes& in, int px, int py, int qx, int qy) {
  // The same instance: one slat of the fence is not the next, though they share a mesh.
  if (in.instance.at(qx, qy) != in.instance.at(px, py)) return false;
  // Normals within kTrmvSplatNormalCosine: not round a fold of the same instance (symmetric in p and q).
  return glm::dot(in.normal.at(px, py), in.normal.at(qx, qy)) >= kTrmvSplatNormalCosine;
}

TrmvSplatPixel trmv_splat_pixel(const TrmvSplatPlanes& in, int size, int x, int y, Probe* probe) {
  note_group(probe, "splat");
  note(probe, "window side", float(size), "[TRMV21 Sec. 4.1] the shadow filter's fixed size");
  if (in.instance.at(x, y) == kInvalidId) return {};  // no surface: (0, 0)
  const int radius = size / 2;
  const bool carries = in.carried.width != 0;
  glm::vec2 sum(0.0f);
  float sum_carried = 0.0f;
  int count = 0;  // splats landed: every weight is 1 (a box)
  for (int qy = std::max(0, y - radius); qy <= std::min(in.shadow.height - 1, y + radius); ++qy) {
    for (int qx = std::max(0, x - radius); qx <= std::min(in.shadow.width - 1, x + radius); ++qx) {
      if (in.valid.at(qx, qy) == 0) continue;  // only in-shadow pixels with an Eq. 3 vector splat
      if (!trmv_splat_same_surface(in, x, y, qx, qy)) continue;  // only onto their own receiving surface
      sum += in.shadow.at(qx, qy);
      if (carries) sum_carried += in.carried.at(qx, qy);
      ++count;
    }
  }
  note(probe, "splats landed", float(count), "[TRMV21 Sec. 4.1] same instance, normals within 25.8 degrees");
  // "weight averaged into the center of each filter" [TRMV21 Sec. 4.1]; nothing landed: the surface motion.
  if (count == 0) return {in.surface_motion.at(x, y), false, 0.0f};
  const TrmvSplatPixel out{sum / float(count), true, sum_carried / float(count)};
  note(probe, "m^V, splatted", out.motion, "[TRMV21 Sec. 4.1] mean of the landed m^V");
  if (carries) note(probe, "carried, splatted", out.carried, "[TRMV21 Sec. 4.1] 'other associated properties'");
  return out;
}

namespace {

// valid_before[(y + 1) (width + 1) + x + 1] = the number of valid vectors in rows 0..y, columns 0..x: a summed-area
// table, from which the count of any window is four look-ups.
std::vector<uint32_t> valid_counts(const UIntPlane& valid) {
  const size_t stride = size_t(valid.width) + 1;
  std::vector<uint32_t> table(stride * (size_t(valid.height) + 1), 0u);
  for (int y = 0; y < valid.height; ++y) {
    uint32_t row = 0;
    for (int x = 0; x < valid.width; ++x) {
      row += valid.at(x, y) != 0 ? 1u : 0u;
      table[(size_t(y) + 1) * stride + size_t(x) + 1] = table[size_t(y) * stride + size_t(x) + 1] + row;
    }
  }
  return table;
}

}  // namespace

void check_trmv_splat_inputs(const TrmvSplatPlanes& in, int size) {
  const int w = in.shadow.width, h = in.shadow.height;
  if (!has_size(in.valid, w, h) || !has_size(in.surface_motion, w, h) || !has_size(in.instance, w, h) ||
      !has_size(in.normal, w, h) || !empty_or_size(in.carried, w, h))
    throw Error("trmv splat: the shadow motion, validity, surface motion, instance, normal and carried planes are "
                "not all " + std::to_string(w) + "x" + std::to_string(h));
  if (size < 1 || size % 2 == 0)
    throw Error("trmv splat: the window's side must be odd and at least 1, not " + std::to_string(size));
}

TrmvSplatOutput trmv_splat_pass(const TrmvSplatPlanes& in, int size) {
  check_trmv_splat_inputs(in, size);
  const int w = in.shadow.width, h = in.shadow.height;
  // Speed only, the same result: a pixel whose window holds no valid vector at all keeps its surface motion (or
  // (0, 0) without a surface) without visiting the window's size^2 pixels, which most pixels far from any shadow
  // would do for nothing (tests/trmv_splat_test.cpp compares both).
  const std::vector<uint32_t> counts = valid_counts(in.valid);
  const size_t stride = size_t(w) + 1;
  const int radius = size / 2;
  TrmvSplatOutput out{Vec2Plane(w, h), UIntPlane(w, h), FloatPlane(w, h)};
  parallel_rows(h, [&](int y) {
    const size_t y0 = size_t(std::max(0, y - radius)), y1 = size_t(std::min(h, y + radius + 1));
    for (int x = 0; x < w; ++x) {
      const size_t x0 = size_t(std::max(0, x - radius)), x1 = size_t(std::min(w, x + radius + 1));
      const uint32_t in_window = counts[y1 * stride + x1] - counts[y0 * stride + x1] - counts[y1 * stride + x0] +
                                 counts[y0 * stride + x0];
      TrmvSplatPixel p;
      if (in_window == 0)
        p.motion = in.instance.at(x, y) != kInvalidId ? in.surface_motion.at(x, y) : glm::vec2(0.0f);
      else
        p = trmv_splat_pixel(in, size, x, y);
      out.motion.at(x, y) = p.motion;
      out.landed.at(x, y) = p.landed ? 1u : 0u;
      out.carried.at(x, y) = p.carried;
    }
  });
  return out;
}

}  // namespace rtdr
