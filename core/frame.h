// Image planes and frames of named layers: the in-memory twin of one multi-layer EXR file.
//
// A Plane is one channel of width x height values, row-major, y down (row 0 is the top row, as in EXR).
// A Frame is a set of planes named "layer.channel" (`normal.X`, `motion.Y`, `id.instance`); every name a
// pass reads or writes is listed in docs/buffers.md. Float channels hold colours, vectors and depths;
// uint channels hold ids exactly (kInvalidId marks "no surface").
#pragma once

#include "core/frame_shared.h"

#include <glm/glm.hpp>

#include <cstdint>
#include <map>
#include <string>
#include <vector>

namespace rtdr {

// The largest frame index any command takes (--frames 0-999999, frame_999999.exr). With it, no loop over a
// user's frame range can overflow an int, and a mistyped range fails at once instead of filling a disk.
inline constexpr int kMaxFrameIndex = 999'999;

// The id stored where a pixel sees no surface (same value as Embree's RTC_INVALID_GEOMETRY_ID).
inline constexpr uint32_t kInvalidId = RTDR_INVALID_ID;  // core/frame_shared.h

template <class T>
struct Plane {
  int width = 0;
  int height = 0;
  std::vector<T> data;

  Plane() = default;
  Plane(int w, int h, T fill = T{}) : width(w), height(h), data(size_t(w) * size_t(h), fill) {}

  size_t index(int x, int y) const { return size_t(y) * size_t(width) + size_t(x); }
  T& at(int x, int y) { return data[index(x, y)]; }
  const T& at(int x, int y) const { return data[index(x, y)]; }
};

using FloatPlane = Plane<float>;
using UIntPlane = Plane<uint32_t>;

class Frame {
 public:
  Frame() = default;
  Frame(int width, int height) : width_(width), height_(height) {}

  int width() const { return width_; }
  int height() const { return height_; }

  // Adds (or replaces) a channel, filled with `fill`, and returns it for writing.
  FloatPlane& add_float(const std::string& name, float fill = 0.0f);
  UIntPlane& add_uint(const std::string& name, uint32_t fill = 0);

  bool has(const std::string& name) const;
  // Throw rtdr::Error("... has no channel 'name' ...") when the channel is missing or of the other type.
  const FloatPlane& float_channel(const std::string& name) const;
  const UIntPlane& uint_channel(const std::string& name) const;
  FloatPlane& float_channel(const std::string& name);
  UIntPlane& uint_channel(const std::string& name);

  // A vector layer is a group of float channels with one suffix each: set_vec3("normal", v) writes
  // normal.X, normal.Y, normal.Z; set_rgb("albedo", c) writes albedo.R, albedo.G, albedo.B.
  void set_vec2(const std::string& layer, const std::vector<glm::vec2>& values);
  void set_vec3(const std::string& layer, const std::vector<glm::vec3>& values);
  void set_rgb(const std::string& layer, const std::vector<glm::vec3>& values);
  std::vector<glm::vec2> get_vec2(const std::string& layer) const;
  std::vector<glm::vec3> get_vec3(const std::string& layer) const;
  std::vector<glm::vec3> get_rgb(const std::string& layer) const;

  const std::map<std::string, FloatPlane>& float_channels() const { return floats_; }
  const std::map<std::string, UIntPlane>& uint_channels() const { return uints_; }

  // Where the frame came from (a file path), used to make error messages name the file.
  std::string source;
  // Text attributes of the frame, written to and read from the EXR header as string attributes: how it was
  // made ("rtdr.scene", "rtdr.gradient.stratum_size", ...), so that a later pass can check what it reads.
  std::map<std::string, std::string> attributes;

 private:
  std::vector<glm::vec3> get_group3(const std::string& layer, const char* const suffixes[3]) const;
  void set_group3(const std::string& layer, const char* const suffixes[3], const std::vector<glm::vec3>& v);

  int width_ = 0;
  int height_ = 0;
  std::map<std::string, FloatPlane> floats_;
  std::map<std::string, UIntPlane> uints_;
};

// A checksum of the frame's pixels: its size, then every channel's name, type and values, in name order (FNV-1a over
// 32-bit values, core/hash.h), as 16 hex digits. The renderer stamps it into a frame's header as rtdr.checksum
// (trace/render_key.h), so a stored frame that changed in any value, channel or size since it was rendered can be
// told from the frame the renderer made. Attributes and the source path are not part of it.
std::string frame_checksum(const Frame& frame);

}  // namespace rtdr
