#include "core/frame.h"

#include "core/error.h"
#include "core/hash.h"

#include <utility>

namespace rtdr {
namespace {

const char* const kXYZ[3] = {"X", "Y", "Z"};
const char* const kRGB[3] = {"R", "G", "B"};

std::string where(const Frame& f) { return f.source.empty() ? std::string("frame") : f.source; }

// A vector layer must have one value per pixel of the frame it goes into.
void require_pixel_count(const Frame& f, const std::string& layer, size_t count) {
  if (count != size_t(f.width()) * size_t(f.height()))
    throw Error("layer '" + layer + "' has " + std::to_string(count) + " values for a " + std::to_string(f.width()) +
                "x" + std::to_string(f.height()) + " " + where(f));
}

}  // namespace

FloatPlane& Frame::add_float(const std::string& name, float fill) {
  uints_.erase(name);
  return floats_[name] = FloatPlane(width_, height_, fill);
}

UIntPlane& Frame::add_uint(const std::string& name, uint32_t fill) {
  floats_.erase(name);
  return uints_[name] = UIntPlane(width_, height_, fill);
}

bool Frame::has(const std::string& name) const { return floats_.count(name) || uints_.count(name); }

const FloatPlane& Frame::float_channel(const std::string& name) const {
  auto it = floats_.find(name);
  if (it == floats_.end() && uints_.count(name))
    throw Error(where(*this) + " stores channel '" + name + "' as uint; it must be float (see docs/buffers.md)");
  if (it == floats_.end())
    throw Error(where(*this) + " has no float channel '" + name + "' (see docs/buffers.md)");
  return it->second;
}

const UIntPlane& Frame::uint_channel(const std::string& name) const {
  auto it = uints_.find(name);
  if (it == uints_.end() && floats_.count(name))
    throw Error(where(*this) + " stores channel '" + name + "' as float; it must be uint (see docs/buffers.md)");
  if (it == uints_.end())
    throw Error(where(*this) + " has no uint channel '" + name + "' (see docs/buffers.md)");
  return it->second;
}

FloatPlane& Frame::float_channel(const std::string& name) {
  return const_cast<FloatPlane&>(std::as_const(*this).float_channel(name));
}

UIntPlane& Frame::uint_channel(const std::string& name) {
  return const_cast<UIntPlane&>(std::as_const(*this).uint_channel(name));
}

void Frame::set_vec2(const std::string& layer, const std::vector<glm::vec2>& values) {
  require_pixel_count(*this, layer, values.size());
  FloatPlane& x = add_float(layer + ".X");
  FloatPlane& y = add_float(layer + ".Y");
  for (size_t i = 0; i < values.size(); ++i) {
    x.data[i] = values[i].x;
    y.data[i] = values[i].y;
  }
}

std::vector<glm::vec2> Frame::get_vec2(const std::string& layer) const {
  const FloatPlane& x = float_channel(layer + ".X");
  const FloatPlane& y = float_channel(layer + ".Y");
  std::vector<glm::vec2> out(x.data.size());
  for (size_t i = 0; i < out.size(); ++i) out[i] = {x.data[i], y.data[i]};
  return out;
}

void Frame::set_group3(const std::string& layer, const char* const suffixes[3], const std::vector<glm::vec3>& v) {
  require_pixel_count(*this, layer, v.size());
  for (int c = 0; c < 3; ++c) {
    FloatPlane& p = add_float(layer + "." + suffixes[c]);
    for (size_t i = 0; i < v.size(); ++i) p.data[i] = v[i][c];
  }
}

std::vector<glm::vec3> Frame::get_group3(const std::string& layer, const char* const suffixes[3]) const {
  std::vector<glm::vec3> out(size_t(width_) * size_t(height_));
  for (int c = 0; c < 3; ++c) {
    const FloatPlane& p = float_channel(layer + "." + suffixes[c]);
    for (size_t i = 0; i < out.size(); ++i) out[i][c] = p.data[i];
  }
  return out;
}

void Frame::set_vec3(const std::string& layer, const std::vector<glm::vec3>& v) { set_group3(layer, kXYZ, v); }
void Frame::set_rgb(const std::string& layer, const std::vector<glm::vec3>& v) { set_group3(layer, kRGB, v); }
std::vector<glm::vec3> Frame::get_vec3(const std::string& layer) const { return get_group3(layer, kXYZ); }
std::vector<glm::vec3> Frame::get_rgb(const std::string& layer) const { return get_group3(layer, kRGB); }

std::string frame_checksum(const Frame& frame) {
  Fnv1a64 h;
  const uint32_t size[2] = {uint32_t(frame.width()), uint32_t(frame.height())};
  h.words(size, 2);
  for (const auto& [name, plane] : frame.float_channels())
    h.text("float").text(name).floats(plane.data.data(), plane.data.size());
  for (const auto& [name, plane] : frame.uint_channels())
    h.text("uint").text(name).words(plane.data.data(), plane.data.size());
  return h.hex();
}

}  // namespace rtdr
