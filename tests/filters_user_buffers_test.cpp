// Tests of filters/user_buffers.cpp: strided user buffers read into planes by hand (an RGBA buffer with a padded
// row pitch), every malformed view refused with one line, and a whole SVGF run on a frame rebuilt from one
// interleaved buffer equal, bit for bit, to the run on the frame rtdr render made.
#include "filters/user_buffers.h"

#include "core/error.h"
#include "filters/method.h"
#include "scenes/gltf_loader.h"
#include "trace/render_frame.h"

#include <catch2/catch.hpp>

#include <cstdint>
#include <cstring>

using namespace rtdr;

TEST_CASE("user buffers: an RGBA buffer with a padded row pitch, read in place as RGB, RG, R and A planes") {
  // 3 x 2 pixels of RGBA floats, each row padded by 2 floats: pixel (x, y) holds (10y + x, 100 + .., 200 + .., 300 + ..).
  const int w = 3, h = 2, row_floats = 4 * w + 2;
  std::vector<float> buffer(size_t(row_floats * h), -1.0f);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x)
      for (int c = 0; c < 4; ++c) buffer[size_t(y * row_floats + 4 * x + c)] = float(100 * c + 10 * y + x);
  BufferView view{buffer.data(), w, h, 3, 16, 4 * row_floats};
  const RgbPlane rgb = rgb_plane(view);
  REQUIRE(rgb.width == w);
  CHECK(rgb.at(2, 1) == glm::vec3(12.0f, 112.0f, 212.0f));
  CHECK(rgb.at(0, 0) == glm::vec3(0.0f, 100.0f, 200.0f));
  view.channels = 2;
  CHECK(vec2_plane(view).at(1, 1) == glm::vec2(11.0f, 111.0f));
  view.channels = 1;
  CHECK(float_plane(view).at(2, 0) == 2.0f);
  view.data = buffer.data() + 3;  // the alpha channel
  CHECK(float_plane(view).at(1, 1) == 311.0f);

  // uint32 ids, packed (strides 0: the defaults).
  const std::vector<uint32_t> ids = {7, 8, 9, 10, 11, 0xFFFFFFFFu};
  const UIntPlane id = uint_plane(BufferView{ids.data(), 3, 2, 1, 0, 0});
  CHECK(id.at(2, 1) == 0xFFFFFFFFu);
  CHECK(id.at(0, 1) == 10u);
}

TEST_CASE("user buffers: null, empty, too few channels, overlapping pixels or rows, another size: one line each") {
  const std::vector<float> buffer(64, 0.0f);
  const auto refused = [](const BufferView& v, const std::string& part) {
    INFO(part);
    CHECK_THROWS_WITH(rgb_plane(v), Catch::Contains(part));
  };
  refused({nullptr, 2, 2, 3, 0, 0}, "null");
  refused({buffer.data(), 0, 2, 3, 0, 0}, "size 0x2 is empty");
  refused({buffer.data(), 2, 2, 4, 0, 0}, "needs 3 channels per pixel, the view has 4");
  refused({buffer.data(), 2, 2, 3, 8, 0}, "pixel_stride 8 bytes is less than a pixel's 3 values (12 bytes)");
  refused({buffer.data(), 2, 2, 3, 16, 24}, "row_stride 24 bytes is less than a row of 2 pixels (32 bytes)");
  Frame frame;
  add_float_channels(frame, {"depth.Z"}, {buffer.data(), 4, 2, 1, 0, 0});
  CHECK(frame.width() == 4);
  CHECK_THROWS_WITH(add_float_channels(frame, {"normal.X", "normal.Y", "normal.Z"}, {buffer.data(), 2, 2, 3, 0, 0}),
                    "add_float_channels 'normal.X': the view is 2x2, the frame 4x2");
}

TEST_CASE("user buffers: svgf on a frame rebuilt from one interleaved buffer equals svgf on the rendered frame") {
  const Scene scene = load_scene("cornell");
  const std::unique_ptr<Method> reference = make_method("svgf"), rebuilt = make_method("svgf");
  const InputChannels channels = reference->inputs();
  const int w = 24, h = 16, stride = int(channels.floats.size()) + 1;  // every float channel of a pixel, and 1 pad
  for (int f = 0; f < 2; ++f) {
    const Frame frame = render_frame(scene, f, w, h, RenderSettings{});
    // The engine's buffer: for each pixel, its channels side by side (as one big interleaved G-buffer).
    std::vector<float> interleaved(size_t(w * h * stride), 0.0f);
    for (size_t c = 0; c < channels.floats.size(); ++c) {
      const FloatPlane& plane = frame.float_channel(channels.floats[c]);
      for (size_t i = 0; i < plane.data.size(); ++i) interleaved[i * size_t(stride) + c] = plane.data[i];
    }
    Frame from_views;
    for (size_t c = 0; c < channels.floats.size(); ++c)
      add_float_channels(from_views, {channels.floats[c]},
                         {interleaved.data() + c, w, h, 1, std::ptrdiff_t(4 * stride), 0});
    const UIntPlane& mesh = frame.uint_channel("id.mesh");
    add_uint_channel(from_views, "id.mesh", {mesh.data.data(), w, h, 1, 0, 0});
    const Frame a = reference->filter(frame), b = rebuilt->filter(from_views);
    INFO("frame " << f);
    CHECK(a.float_channel("color.R").data == b.float_channel("color.R").data);
    CHECK(a.float_channel("color.G").data == b.float_channel("color.G").data);
    CHECK(a.float_channel("color.B").data == b.float_channel("color.B").data);
  }
}

TEST_CASE("user buffers: strides whose products overflow are refused, not wrapped (2^62, PTRDIFF_MAX, y * row)") {
  const std::vector<float> buffer(64, 1.0f);
  const auto refused = [](const BufferView& v, const std::string& part) {
    INFO(part << ": pixel_stride " << v.pixel_stride << ", row_stride " << v.row_stride << ", " << v.width << "x"
              << v.height);
    CHECK_THROWS_WITH(float_plane(v), Catch::Contains(part));
  };
  constexpr std::ptrdiff_t max = PTRDIFF_MAX;
  // 2^62 * 4 wraps to 0 in 64 bits: the default row would be 0 bytes, "no overlap", and x * pixel_stride anywhere.
  refused({buffer.data(), 4, 1, 1, std::ptrdiff_t(1) << 62, 0}, "pixel_stride 4611686018427387904 times width 4");
  refused({buffer.data(), 2, 1, 1, max, 0}, "pixel_stride 9223372036854775807 times width 2");
  refused({buffer.data(), 1, 4, 1, 4, std::ptrdiff_t(1) << 62}, "row_stride 4611686018427387904 times 3 rows");
  refused({buffer.data(), 1, 2, 1, 4, max}, "row_stride 9223372036854775807 times 1 rows, plus a row");
  refused({buffer.data(), 2, 3, 1, max / 4, max / 2}, "PTRDIFF_MAX");
  // Addresses that wrap: a span of 16 bytes from 8 bytes below the top of the address space.
  const void* top = reinterpret_cast<const void*>(UINTPTR_MAX - 7);
  refused({top, 4, 1, 1, 0, 0}, "wrap around the address space");
  // At the limit but not past it: one pixel, whatever its strides, reads the first value only.
  CHECK(float_plane({buffer.data(), 1, 1, 1, max, max}).at(0, 0) == 1.0f);
  CHECK(float_plane({buffer.data(), 1, 1, 1, max, 0}).at(0, 0) == 1.0f);
}

TEST_CASE("user buffers: zero strides mean packed, and negative and short strides and sizes are refused") {
  std::vector<float> buffer(12);
  for (size_t i = 0; i < buffer.size(); ++i) buffer[i] = float(i);
  const RgbPlane packed = rgb_plane({buffer.data(), 2, 2, 3, 0, 0});  // 12 bytes a pixel, 24 a row
  CHECK(packed.at(1, 1) == glm::vec3(9.0f, 10.0f, 11.0f));
  const auto refused = [&](const BufferView& v, const std::string& part) {
    INFO(part);
    CHECK_THROWS_WITH(rgb_plane(v), Catch::Contains(part));
  };
  refused({buffer.data(), 2, 2, 3, -12, 0}, "pixel_stride -12 bytes is less than a pixel's 3 values (12 bytes)");
  refused({buffer.data(), 2, 2, 3, 12, -24}, "row_stride -24 bytes is less than a row of 2 pixels (24 bytes)");
  refused({buffer.data(), 2, 2, 3, PTRDIFF_MIN, 0}, "is less than a pixel's");
  refused({buffer.data(), -2, 2, 3, 0, 0}, "size -2x2 is empty");
  refused({buffer.data(), 2, INT32_MIN, 3, 0, 0}, "is empty");
}

TEST_CASE("user buffers: misaligned strides and data read every value exactly (no aligned load is assumed)") {
  // Pixels of 13 bytes (3 floats and a byte of padding), rows of 41 bytes, from the buffer's byte 1: no float is
  // 4-byte aligned. Pixel (x, y) holds (100 y + 10 x + c) in channel c.
  const int w = 3, h = 2;
  const std::ptrdiff_t pixel = 13, row = 41;
  std::vector<unsigned char> bytes(size_t(1 + row * h), 0xAB);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x)
      for (int c = 0; c < 3; ++c) {
        const float v = float(100 * y + 10 * x + c);
        std::memcpy(bytes.data() + 1 + y * row + x * pixel + 4 * c, &v, 4);
      }
  const RgbPlane rgb = rgb_plane({bytes.data() + 1, w, h, 3, pixel, row});
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) CHECK(rgb.at(x, y) == glm::vec3(100 * y + 10 * x, 100 * y + 10 * x + 1, 100 * y + 10 * x + 2));
}
