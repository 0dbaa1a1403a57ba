// Strided user buffers into planes and frames. See user_buffers.h.
#include "filters/user_buffers.h"

#include "core/error.h"

#include <cstdint>
#include <cstring>
#include <optional>

namespace rtdr {
namespace {

// The view's strides with their defaults filled in, after checking that pixels and rows do not overlap and that
// every byte the view spans has an offset from `data` that a ptrdiff_t holds (so the address arithmetic of
// value_at cannot wrap): every product is computed with an overflow check, since a stride of 2^62 times a width of
// 4 wraps to 0, which would pass the overlap check and read anywhere.
struct Strides {
  std::ptrdiff_t pixel, row;
};

// a * b, or nothing when the product does not fit in a ptrdiff_t.
std::optional<std::ptrdiff_t> product(std::ptrdiff_t a, std::ptrdiff_t b) {
  std::ptrdiff_t p = 0;
  if (__builtin_mul_overflow(a, b, &p)) return std::nullopt;
  return p;
}

Strides checked_strides(const BufferView& v, int want_channels, const char* what) {
  const std::string name = std::string(what) + ": ";
  if (!v.data) throw Error(name + "the buffer is null");
  if (v.width < 1 || v.height < 1)
    throw Error(name + "size " + std::to_string(v.width) + "x" + std::to_string(v.height) + " is empty");
  if (v.channels != want_channels)
    throw Error(name + "needs " + std::to_string(want_channels) + " channels per pixel, the view has " +
                std::to_string(v.channels));
  const std::ptrdiff_t value = 4;  // float and uint32 alike
  const std::ptrdiff_t pixel_values = value * v.channels;  // channels is 1 to 3 here, or a list's size
  const std::ptrdiff_t pixel = v.pixel_stride ? v.pixel_stride : pixel_values;
  if (pixel < pixel_values)
    throw Error(name + "pixel_stride " + std::to_string(pixel) + " bytes is less than a pixel's " +
                std::to_string(v.channels) + " values (" + std::to_string(pixel_values) + " bytes)");
  const std::string too_far = name + "the view spans more than PTRDIFF_MAX bytes: ";
  const std::optional<std::ptrdiff_t> row_bytes = product(pixel, v.width);
  if (!row_bytes)
    throw Error(too_far + "pixel_stride " + std::to_string(pixel) + " times width " + std::to_string(v.width));
  const std::ptrdiff_t row = v.row_stride ? v.row_stride : *row_bytes;
  if (row < *row_bytes)
    throw Error(name + "row_stride " + std::to_string(row) + " bytes is less than a row of " +
                std::to_string(v.width) + " pixels (" + std::to_string(*row_bytes) + " bytes)");
  // The last byte read: (height - 1) row + (width - 1) pixel + the pixel's values.
  const std::optional<std::ptrdiff_t> rows_before = product(row, v.height - 1);
  std::ptrdiff_t span = 0;
  if (!rows_before || __builtin_add_overflow(*rows_before, *row_bytes - pixel + pixel_values, &span))
    throw Error(too_far + "row_stride " + std::to_string(row) + " times " + std::to_string(v.height - 1) +
                " rows, plus a row");
  // And the addresses it spans: data + span must not wrap around the address space.
  std::uintptr_t end = 0;
  if (__builtin_add_overflow(reinterpret_cast<std::uintptr_t>(v.data), std::uintptr_t(span), &end))
    throw Error(name + "the view's " + std::to_string(span) + " bytes from its data pointer wrap around the address "
                "space");
  return {pixel, row};
}

// Value c of pixel (x, y); memcpy, since a byte stride need not keep floats aligned.
template <class T>
T value_at(const BufferView& v, const Strides& s, int x, int y, int c) {
  T out;
  std::memcpy(&out, static_cast<const unsigned char*>(v.data) + y * s.row + x * s.pixel + c * 4, sizeof out);
  return out;
}

// A plane of T from a view, pixel by pixel: read(view, strides, x, y) gives the pixel.
template <class T, class Read>
Plane<T> plane_from(const BufferView& v, int channels, const char* what, Read read) {
  const Strides s = checked_strides(v, channels, what);
  Plane<T> plane(v.width, v.height);
  for (int y = 0; y < v.height; ++y)
    for (int x = 0; x < v.width; ++x) plane.at(x, y) = read(s, x, y);
  return plane;
}

void take_size(Frame& frame, const BufferView& v, const std::string& what) {
  if (frame.width() == 0 && frame.height() == 0) {
    Frame sized(v.width, v.height);
    sized.source = frame.source;
    sized.attributes = frame.attributes;
    frame = std::move(sized);
  } else if (frame.width() != v.width || frame.height() != v.height) {
    throw Error(what + ": the view is " + std::to_string(v.width) + "x" + std::to_string(v.height) +
                ", the frame " + std::to_string(frame.width()) + "x" + std::to_string(frame.height()));
  }
}

}  // namespace

FloatPlane float_plane(const BufferView& v) {
  return plane_from<float>(v, 1, "float_plane", [&](const Strides& s, int x, int y) {
    return value_at<float>(v, s, x, y, 0);
  });
}

Vec2Plane vec2_plane(const BufferView& v) {
  return plane_from<glm::vec2>(v, 2, "vec2_plane", [&](const Strides& s, int x, int y) {
    return glm::vec2(value_at<float>(v, s, x, y, 0), value_at<float>(v, s, x, y, 1));
  });
}

RgbPlane rgb_plane(const BufferView& v) {
  return plane_from<glm::vec3>(v, 3, "rgb_plane", [&](const Strides& s, int x, int y) {
    return glm::vec3(value_at<float>(v, s, x, y, 0), value_at<float>(v, s, x, y, 1), value_at<float>(v, s, x, y, 2));
  });
}

UIntPlane uint_plane(const BufferView& v) {
  return plane_from<uint32_t>(v, 1, "uint_plane", [&](const Strides& s, int x, int y) {
    return value_at<uint32_t>(v, s, x, y, 0);
  });
}

void add_float_channels(Frame& frame, const std::vector<std::string>& names, const BufferView& v) {
  const std::string what = "add_float_channels '" + (names.empty() ? std::string() : names.front()) + "'";
  const Strides s = checked_strides(v, int(names.size()), what.c_str());
  take_size(frame, v, what);
  for (size_t c = 0; c < names.size(); ++c) {
    FloatPlane& plane = frame.add_float(names[c]);
    for (int y = 0; y < v.height; ++y)
      for (int x = 0; x < v.width; ++x) plane.at(x, y) = value_at<float>(v, s, x, y, int(c));
  }
}

void add_uint_channel(Frame& frame, const std::string& name, const BufferView& v) {
  const std::string what = "add_uint_channel '" + name + "'";
  checked_strides(v, 1, what.c_str());
  take_size(frame, v, what);
  frame.add_uint(name) = uint_plane(v);
}

}  // namespace rtdr
