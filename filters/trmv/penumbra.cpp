// The penumbra-sized shadow filter's std [TRMV21 Sec. 4.1, 5, after LLK*19]. The equations and the choices:
// filters/trmv/penumbra.h.
#include "filters/trmv/penumbra.h"

#include "core/error.h"
#include "core/parallel.h"
#include "filters/trmv/splat_shared.h"  // kTrmvSplatNormalCosine: the same receiving surface

#include <algorithm>
#include <cmath>
#include <string>

namespace rtdr {

TrmvPenumbraInputs TrmvPenumbraInputs::from_frame(const Frame& frame) {
  return {xyz_plane(frame, "path.light"), frame.uint_channel("path.light.instance"), xyz_plane(frame, "path.blocker"),
          frame.uint_channel("path.blocker.instance"), xyz_plane(frame, "position"), frame.uint_channel("id.instance"),
          xyz_plane(frame, "normal")};
}

std::map<uint32_t, float> trmv_light_diameters(const RgbPlane& light, const UIntPlane& light_id) {
  // Per light instance: the count, the sum of l and the sum of |l|^2, in double and in pixel order.
  struct Moments {
    double n = 0.0, sum_sq = 0.0;
    glm::dvec3 sum{0.0};
  };
  std::map<uint32_t, Moments> moments;
  for (size_t i = 0; i < light_id.data.size(); ++i) {
    if (light_id.data[i] == kInvalidId) continue;
    Moments& m = moments[light_id.data[i]];
    const glm::dvec3 l(light.data[i]);
    m.n += 1.0, m.sum += l, m.sum_sq += glm::dot(l, l);
  }
  std::map<uint32_t, float> diameters;
  for (const auto& [id, m] : moments) {
    const glm::dvec3 c = m.sum / m.n;
    // E|l - c|^2 = E|l|^2 - |c|^2 (rounding may leave it just below 0).
    const double spread = std::max(0.0, m.sum_sq / m.n - glm::dot(c, c));
    // D = 2 R, R the radius of the disk with the same second moment: E|l - c|^2 = R^2 / 2 (penumbra.h).
    diameters[id] = float(2.0 * std::sqrt(2.0 * spread));
  }
  return diameters;
}

float trmv_penumbra_width(float diameter, glm::vec3 light, glm::vec3 blocker, glm::vec3 receiver) {
  const float d_b = glm::length(blocker - light), d_r = glm::length(receiver - light);
  if (!(d_b > 0.0f) || !(d_r > d_b)) return 0.0f;
  // W = D (d_r - d_b) / d_b: similar triangles through the blocker's edge [LLK*19, TRMV21 Sec. 4.1].
  return diameter * (d_r - d_b) / d_b;
}

float trmv_metres_per_pixel(const TrmvPenumbraInputs& in, glm::ivec2 axis, int x, int y) {
  // A neighbour on the pixel's own surface: the same instance, normals within the splat's 25.8 degrees.
  const auto on_surface = [&](glm::ivec2 q) {
    return inside(in.position, q.x, q.y) && in.instance.at(q.x, q.y) == in.instance.at(x, y) &&
           glm::dot(in.normal.at(q.x, q.y), in.normal.at(x, y)) >= kTrmvSplatNormalCosine;
  };
  const glm::ivec2 p(x, y), ahead = p + axis, behind = p - axis;
  const bool has_ahead = on_surface(ahead), has_behind = on_surface(behind);
  const auto at = [&](glm::ivec2 q) { return in.position.at(q.x, q.y); };
  // The central difference where both neighbours are on the surface, else the one-sided one, else unknown.
  if (has_ahead && has_behind) return 0.5f * glm::length(at(ahead) - at(behind));
  if (has_ahead) return glm::length(at(ahead) - at(p));
  if (has_behind) return glm::length(at(p) - at(behind));
  return 0.0f;
}

float trmv_penumbra_sigma(float width, float metres, float sigma_floor, float sigma_cap) {
  if (!(metres > 0.0f)) return sigma_floor;  // no metric: the least filter
  // sigma = W_px / 6: the penumbra's width spans +-3 std, as 31 pixels span the fixed filter's std 5 (penumbra.h).
  return std::clamp(width / (6.0f * metres), sigma_floor, std::max(sigma_floor, sigma_cap));
}

void trmv_penumbra_pixel(const TrmvPenumbraInputs& in, const std::map<uint32_t, float>& diameters, int x, int y,
                         float& width, glm::vec2& metres, Probe* probe) {
  width = 0.0f;
  metres = glm::vec2(0.0f);
  note_group(probe, "penumbra");
  if (in.instance.at(x, y) == kInvalidId) return;  // no surface
  metres = {trmv_metres_per_pixel(in, {1, 0}, x, y), trmv_metres_per_pixel(in, {0, 1}, x, y)};
  note(probe, "(m_x, m_y)", metres, "metres per pixel on the receiver");
  const uint32_t light = in.light_id.at(x, y);
  if (light == kInvalidId || in.blocker_id.at(x, y) == kInvalidId) return;  // lit, or no light sampled
  const auto d = diameters.find(light);
  const float diameter = d == diameters.end() ? 0.0f : d->second;
  note(probe, "D", diameter, "[LLK*19] the light's diameter, from its samples' second moment");
  width = trmv_penumbra_width(diameter, in.light.at(x, y), in.blocker.at(x, y), in.position.at(x, y));
  note(probe, "W", width, "[LLK*19] D (d_r - d_b) / d_b, metres");
}

void check_trmv_penumbra_sizes(const TrmvPenumbraInputs& in) {
  const int w = in.position.width, h = in.position.height;
  if (!has_size(in.light, w, h) || !has_size(in.light_id, w, h) || !has_size(in.blocker, w, h) ||
      !has_size(in.blocker_id, w, h) || !has_size(in.instance, w, h) || !has_size(in.normal, w, h))
    throw Error("trmv penumbra: path.light, path.blocker, id.instance and the normal are not all " +
                std::to_string(w) + "x" + std::to_string(h) + " like the position");
}

TrmvPenumbraOutput trmv_penumbra_pass(const TrmvPenumbraInputs& in) {
  check_trmv_penumbra_sizes(in);
  const int w = in.position.width, h = in.position.height;
  const std::map<uint32_t, float> diameters = trmv_light_diameters(in.light, in.light_id);
  TrmvPenumbraOutput out{FloatPlane(w, h), Vec2Plane(w, h)};
  parallel_rows(h, [&](int y) {
    for (int x = 0; x < w; ++x) trmv_penumbra_pixel(in, diameters, x, y, out.width.at(x, y), out.metres.at(x, y));
  });
  return out;
}

void trmv_penumbra_sigmas(const FloatPlane& splatted_width, const Vec2Plane& metres, float sigma_floor,
                          float sigma_cap, FloatPlane& sigma_x, FloatPlane& sigma_y) {
  const int w = splatted_width.width, h = splatted_width.height;
  if (!has_size(metres, w, h)) throw Error("trmv penumbra: the metres plane is not the width plane's size");
  sigma_x = FloatPlane(w, h);
  sigma_y = FloatPlane(w, h);
  for (size_t i = 0; i < splatted_width.data.size(); ++i) {
    sigma_x.data[i] = trmv_penumbra_sigma(splatted_width.data[i], metres.data[i].x, sigma_floor, sigma_cap);
    sigma_y.data[i] = trmv_penumbra_sigma(splatted_width.data[i], metres.data[i].y, sigma_floor, sigma_cap);
  }
}

}  // namespace rtdr
