// The preview mosaic: tiles of width x height, 3 per row,
//   albedo (sRGB)          | shading normal (n/2 + 1/2)  | depth (near bright, far dark)
//   motion (see below)     | instance id (hashed hue)    | emission (clamped, sRGB)
//   direct (demodulated)   | indirect (demodulated)      | colour = emission + albedo * (direct + indirect)
// The third row appears when the frame has radiance layers; radiance tiles are tone mapped with Reinhard's
// c / (1 + c) per channel, then sRGB-encoded. Motion is shown as R = 1/2 + m.x / s, G = 1/2 + m.y / s,
// B = 1/2, with s = 2 * max |m| in the frame (at least 1 px), so a still pixel is grey.
#include "app/preview.h"

#include "core/color.h"
#include "core/png_io.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <functional>
#include <vector>

namespace rtdr {
namespace {

using PixelColor = std::function<glm::vec3(size_t)>;  // pixel index -> display colour in [0, 1], sRGB

glm::vec3 tone_map(const glm::vec3& c) { return srgb_encode(c / (glm::vec3(1.0f) + c)); }

// A fixed, well-spread colour for an id (golden-ratio hue walk); black for "no surface".
glm::vec3 id_color(uint32_t id) {
  if (id == kInvalidId) return glm::vec3(0.0f);
  const float h = std::fmod(0.61803398875f * float(id) + 0.1f, 1.0f) * 6.0f;
  const float f = h - std::floor(h);
  switch (int(h)) {
    case 0: return {1.0f, f, 0.2f};
    case 1: return {1.0f - f, 1.0f, 0.2f};
    case 2: return {0.2f, 1.0f, f};
    case 3: return {0.2f, 1.0f - f, 1.0f};
    case 4: return {f, 0.2f, 1.0f};
    default: return {1.0f, 0.2f, 1.0f - f};
  }
}

}  // namespace

void write_preview_png(const std::string& path, const Frame& frame) {
  const int w = frame.width(), h = frame.height();
  const auto albedo = frame.get_rgb("albedo");
  const auto normal = frame.get_vec3("normal");
  const auto emission = frame.get_rgb("emission");
  const auto motion = frame.get_vec2("motion");
  const FloatPlane& depth = frame.float_channel("depth.Z");
  const UIntPlane& instance = frame.uint_channel("id.instance");

  float max_depth = 0.0f, max_motion = 0.5f;
  for (size_t i = 0; i < depth.data.size(); ++i) {
    max_depth = std::max(max_depth, depth.data[i]);
    max_motion = std::max({max_motion, std::abs(motion[i].x), std::abs(motion[i].y)});
  }
  const float motion_scale = 2.0f * max_motion;

  std::vector<std::array<PixelColor, 3>> tiles = {
      {[&](size_t i) { return srgb_encode(albedo[i]); },
       [&](size_t i) { return instance.data[i] == kInvalidId ? glm::vec3(0.0f) : normal[i] * 0.5f + 0.5f; },
       [&](size_t i) { return glm::vec3(depth.data[i] > 0.0f ? 1.0f - 0.9f * depth.data[i] / max_depth : 0.0f); }},
      {[&](size_t i) { return glm::vec3(0.5f + motion[i] / motion_scale, 0.5f); },
       [&](size_t i) { return id_color(instance.data[i]); },
       [&](size_t i) { return srgb_encode(glm::min(emission[i], glm::vec3(1.0f))); }},
  };
  std::vector<glm::vec3> direct, indirect;
  if (frame.has("direct.R")) {
    direct = frame.get_rgb("direct");
    indirect = frame.get_rgb("indirect");
    tiles.push_back({[&](size_t i) { return tone_map(direct[i]); }, [&](size_t i) { return tone_map(indirect[i]); },
                     [&](size_t i) {
                       return tone_map(emission[i] + demodulation_factor(albedo[i]) * (direct[i] + indirect[i]));
                     }});
  }

  const int rows = int(tiles.size());
  const int mosaic_w = 3 * w, mosaic_h = rows * h;
  std::vector<uint8_t> rgb(size_t(mosaic_w) * size_t(mosaic_h) * 3);
  for (int ty = 0; ty < rows; ++ty)
    for (int tx = 0; tx < 3; ++tx)
      for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
          const glm::vec3 c = tiles[size_t(ty)][size_t(tx)](size_t(y) * size_t(w) + size_t(x));
          uint8_t* out = &rgb[(size_t(ty * h + y) * size_t(mosaic_w) + size_t(tx * w + x)) * 3];
          for (int k = 0; k < 3; ++k) out[k] = to_byte(c[k]);
        }
  write_png(path, mosaic_w, mosaic_h, rgb);
}

void write_display_png(const std::string& path, const RgbPlane& display) {
  std::vector<uint8_t> rgb(display.data.size() * 3);
  for (size_t i = 0; i < display.data.size(); ++i)
    for (int c = 0; c < 3; ++c) rgb[3 * i + size_t(c)] = to_byte(srgb_encode(display.data[i][c]));
  write_png(path, display.width, display.height, rgb);
}

}  // namespace rtdr
