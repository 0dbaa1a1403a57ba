// Tests of filters/user_buffers.cpp: strided user buffers read into planes by hand (an RGBA buffer with a padded
// row pitch), every malformed view refused with one line, and a whole SVGF run on a frame rebuilt from one
// interleaved buffer equal, bit for bit, to the run on the frame rtdr render made.
#include "filters/user_buffers.h"

#include "core/error.h"
#include "filters/method.h"
#include "scenes/gltf_loader.h"
#include "trace/render_frame.h"

#include <catch2/catch.hpp>

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
