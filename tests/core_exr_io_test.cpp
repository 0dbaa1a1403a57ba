// Tests for core/exr_io: bit-exact round trips, HALF input, one-line errors naming the file, atomic writes,
// and the finite / same-size checks.
//
// Two files are built by hand, byte by byte, from "The OpenEXR File Layout" (F. Kainz, ILM): this checks
// our reader against the format itself rather than against the library that also wrote the file.
#include "core/error.h"
#include "core/exr_io.h"

#include <catch2/catch.hpp>

#include <unistd.h>

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <functional>
#include <limits>

namespace fs = std::filesystem;
using rtdr::Frame;
using rtdr::kInvalidId;

namespace {

// A fresh folder per test case, removed afterwards.
struct TempDir {
  fs::path path;
  TempDir() {
    static int count = 0;
    path = fs::temp_directory_path() /
           ("rtdr_exr_io_test_" + std::to_string(::getpid()) + "_" + std::to_string(count++));
    fs::remove_all(path);
    fs::create_directories(path);
  }
  ~TempDir() { fs::remove_all(path); }
  std::string file(const std::string& name) const { return (path / name).string(); }
};

// The rtdr::Error message that `fn` throws; fails the test when it throws nothing or something else.
std::string error_of(const std::function<void()>& fn) {
  try {
    fn();
  } catch (const rtdr::Error& e) {
    return e.what();
  }
  FAIL("expected an rtdr::Error");
  return "";
}

// A user-facing error is one line that names the file.
void check_one_line_naming(const std::string& message, const std::string& path) {
  INFO("message: " << message);
  CHECK(message.find('\n') == std::string::npos);
  CHECK(message.find('\r') == std::string::npos);
  CHECK(message.find(path) != std::string::npos);
}

// A frame whose every sample differs, with the awkward float values a lossy path would change.
Frame make_test_frame(int width, int height) {
  Frame frame(width, height);
  rtdr::FloatPlane& red = frame.add_float("color.R");
  rtdr::FloatPlane& depth = frame.add_float("depth.Z");
  rtdr::UIntPlane& instance = frame.add_uint("id.instance");
  for (int y = 0; y < height; ++y) {
    for (int x = 0; x < width; ++x) {
      red.at(x, y) = 0.1f * float(x) - 0.37f * float(y) + 1e-3f;  // not representable as half
      depth.at(x, y) = std::ldexp(1.0f + float(x * 31 + y), y * 7 - 20);
      instance.at(x, y) = uint32_t(x * 1000003 + y * 7919);
    }
  }
  // The awkward depths go along the first row, as many as fit: a 1x1 frame has room for the first only.
  const float awkward[] = {std::numeric_limits<float>::denorm_min(), -0.0f, std::numeric_limits<float>::max()};
  for (int x = 0; x < std::min(width, 3); ++x) depth.at(x, 0) = awkward[x];
  instance.at(0, 0) = kInvalidId;                       // "no surface"
  instance.at(width - 1, height - 1) = 0xFFFFFFFEu;     // largest valid id
  return frame;
}

// Every channel present in both frames with the same bits.
void check_bit_exact(const Frame& a, const Frame& b) {
  REQUIRE(a.width() == b.width());
  REQUIRE(a.height() == b.height());
  REQUIRE(a.float_channels().size() == b.float_channels().size());
  REQUIRE(a.uint_channels().size() == b.uint_channels().size());
  for (const auto& [name, plane] : a.float_channels()) {
    const rtdr::FloatPlane& other = b.float_channel(name);
    for (size_t i = 0; i < plane.data.size(); ++i) {
      INFO(name << " sample " << i);
      CHECK(std::bit_cast<uint32_t>(plane.data[i]) == std::bit_cast<uint32_t>(other.data[i]));
    }
  }
  for (const auto& [name, plane] : a.uint_channels()) CHECK(plane.data == b.uint_channel(name).data);
}

// ---- A hand-made uncompressed scanline EXR ----------------------------------------------------------
// Layout: magic 76 2f 31 01, version 2 (single-part scanline), header attributes (name\0 type\0 size
// value), a 0 byte ending the header, a line offset table (one uint64 file position per scanline block),
// then the blocks. Uncompressed blocks hold one scanline: int y, int byte count, then per channel in
// alphabetical order all samples of that row. Everything is little-endian.
struct ExrBytes {
  std::vector<uint8_t> bytes;
  template <class T>
  void put(T value) {  // little-endian, which is also this machine's order (x86-64)
    const auto* p = reinterpret_cast<const uint8_t*>(&value);
    bytes.insert(bytes.end(), p, p + sizeof(T));
  }
  void put_name(const std::string& s) {
    bytes.insert(bytes.end(), s.begin(), s.end());
    bytes.push_back(0);
  }
  void attribute(const std::string& name, const std::string& type, int32_t size) {
    put_name(name);
    put_name(type);
    put(size);
  }
};

struct HandChannel {
  std::string name;
  int32_t pixel_type;  // 0 UINT, 1 HALF, 2 FLOAT
  std::vector<uint32_t> samples;  // raw bits, row-major; HALF uses the low 16 bits
};

std::vector<uint8_t> hand_made_exr(int x_min, int y_min, int width, int height,
                                   const std::vector<HandChannel>& channels /* alphabetical */) {
  ExrBytes f;
  f.put(uint32_t(20000630));  // magic number, bytes 76 2f 31 01
  f.put(uint32_t(2));         // version 2, no flags
  int32_t chlist_size = 1;    // the terminating 0
  for (const HandChannel& c : channels) chlist_size += int32_t(c.name.size()) + 1 + 16;
  f.attribute("channels", "chlist", chlist_size);
  for (const HandChannel& c : channels) {
    f.put_name(c.name);
    f.put(c.pixel_type);
    f.put(uint32_t(0));  // pLinear, then 3 reserved bytes
    f.put(int32_t(1));   // xSampling
    f.put(int32_t(1));   // ySampling
  }
  f.bytes.push_back(0);
  f.attribute("compression", "compression", 1);
  f.bytes.push_back(0);  // NO_COMPRESSION
  for (const char* window : {"dataWindow", "displayWindow"}) {
    f.attribute(window, "box2i", 16);
    f.put(int32_t(x_min));
    f.put(int32_t(y_min));
    f.put(int32_t(x_min + width - 1));
    f.put(int32_t(y_min + height - 1));
  }
  f.attribute("lineOrder", "lineOrder", 1);
  f.bytes.push_back(0);  // INCREASING_Y
  f.attribute("pixelAspectRatio", "float", 4);
  f.put(1.0f);
  f.attribute("screenWindowCenter", "v2f", 8);
  f.put(0.0f);
  f.put(0.0f);
  f.attribute("screenWindowWidth", "float", 4);
  f.put(1.0f);
  f.bytes.push_back(0);  // end of header

  int32_t row_bytes = 0;
  for (const HandChannel& c : channels) row_bytes += width * (c.pixel_type == 1 ? 2 : 4);
  const size_t table_start = f.bytes.size();
  for (int y = 0; y < height; ++y)  // offset of block y: after the table, blocks of 8 + row_bytes
    f.put(uint64_t(table_start + 8 * size_t(height) + size_t(y) * (8 + size_t(row_bytes))));
  for (int y = 0; y < height; ++y) {
    f.put(int32_t(y_min + y));
    f.put(row_bytes);
    for (const HandChannel& c : channels)
      for (int x = 0; x < width; ++x) {
        const uint32_t bits = c.samples[size_t(y) * size_t(width) + size_t(x)];
        if (c.pixel_type == 1) f.put(uint16_t(bits));
        else f.put(bits);
      }
  }
  return f.bytes;
}

void write_bytes(const std::string& path, const std::vector<uint8_t>& bytes) {
  std::ofstream out(path, std::ios::binary);
  out.write(reinterpret_cast<const char*>(bytes.data()), std::streamsize(bytes.size()));
}

}  // namespace

TEST_CASE("write_exr then read_exr is bit-exact for float and uint channels") {
  TempDir dir;
  for (auto [w, h] : {std::pair{7, 5}, std::pair{1, 1}, std::pair{33, 17}}) {
    const std::string path = dir.file("frame_" + std::to_string(w) + "x" + std::to_string(h) + ".exr");
    const Frame written = make_test_frame(w, h);
    rtdr::write_exr(path, written);
    const Frame read = rtdr::read_exr(path);
    check_bit_exact(written, read);
    CHECK(read.source == path);
  }
}

TEST_CASE("write_exr then read_exr keeps the frame's rtdr.* attributes") {
  TempDir dir;
  Frame frame = make_test_frame(4, 3);
  frame.attributes = {{"rtdr.scene", "pillars"}, {"rtdr.gradient.stratum_size", "3"}, {"rtdr.empty", ""}};
  rtdr::write_exr(dir.file("a.exr"), frame);
  const Frame back = rtdr::read_exr(dir.file("a.exr"));
  CHECK(back.attributes == frame.attributes);
  check_bit_exact(frame, back);
  // Only string attributes named rtdr.* are read: OpenEXR's own header attributes are not the frame's.
  CHECK(back.attributes.count("compression") == 0);
}

TEST_CASE("write_exr keeps NaN and infinity bits (it stores, it does not judge)") {
  TempDir dir;
  Frame frame(3, 2);
  rtdr::FloatPlane& v = frame.add_float("v.X");
  v.at(0, 0) = std::numeric_limits<float>::quiet_NaN();
  v.at(1, 0) = std::numeric_limits<float>::infinity();
  v.at(2, 0) = -std::numeric_limits<float>::infinity();
  rtdr::write_exr(dir.file("special.exr"), frame);
  check_bit_exact(frame, rtdr::read_exr(dir.file("special.exr")));
}

TEST_CASE("write_exr replaces an existing file and leaves no temporary behind") {
  TempDir dir;
  const std::string path = dir.file("frame.exr");
  rtdr::write_exr(path, make_test_frame(4, 4));
  rtdr::write_exr(path, make_test_frame(7, 5));
  CHECK(rtdr::read_exr(path).width() == 7);
  CHECK(std::distance(fs::directory_iterator(dir.path), fs::directory_iterator()) == 1);
}

TEST_CASE("read_exr reads HALF, FLOAT and UINT channels of a hand-made file") {
  TempDir dir;
  // Half bit patterns (IEEE 754 binary16) with exact float values: 1, 0.5, -2, 65504 (largest half),
  // 2^-24 (smallest subnormal half), 0.
  const std::vector<uint32_t> halves = {0x3C00, 0x3800, 0xC000, 0x7BFF, 0x0001, 0x0000};
  const std::vector<float> halves_as_float = {1.0f, 0.5f, -2.0f, 65504.0f, std::ldexp(1.0f, -24), 0.0f};
  std::vector<uint32_t> floats, uints = {7, kInvalidId, 0, 1, 2, 3};
  for (float v : {0.1f, -3.5f, 1e-30f, 2.0f, 3.0f, 4.0f}) floats.push_back(std::bit_cast<uint32_t>(v));
  const std::string path = dir.file("hand.exr");
  write_bytes(path, hand_made_exr(0, 0, 3, 2, {{"a.half", 1, halves}, {"b.float", 2, floats}, {"c.uint", 0, uints}}));

  const Frame frame = rtdr::read_exr(path);
  REQUIRE(frame.width() == 3);
  REQUIRE(frame.height() == 2);
  CHECK(frame.float_channel("a.half").data == halves_as_float);
  for (size_t i = 0; i < floats.size(); ++i)
    CHECK(std::bit_cast<uint32_t>(frame.float_channel("b.float").data[i]) == floats[i]);
  CHECK(frame.uint_channel("c.uint").data == uints);
}

TEST_CASE("read_exr rejects a data window that does not start at (0, 0)") {
  TempDir dir;
  const std::string path = dir.file("offset.exr");
  write_bytes(path, hand_made_exr(1, 0, 2, 2, {{"Y", 2, {0, 0, 0, 0}}}));
  const std::string message = error_of([&] { rtdr::read_exr(path); });
  check_one_line_naming(message, path);
  CHECK(message.find("data window") != std::string::npos);
}

TEST_CASE("read_exr: unreadable files give one-line errors naming the file") {
  TempDir dir;

  SECTION("missing file") {
    const std::string path = dir.file("missing.exr");
    check_one_line_naming(error_of([&] { rtdr::read_exr(path); }), path);
  }
  SECTION("a text file named .exr") {
    const std::string path = dir.file("text.exr");
    std::ofstream(path) << "this is not an image\nsecond line\n";
    check_one_line_naming(error_of([&] { rtdr::read_exr(path); }), path);
  }
  SECTION("truncated files, cut in the pixels and in the header") {
    const std::string whole = dir.file("whole.exr");
    rtdr::write_exr(whole, make_test_frame(64, 48));
    const auto size = fs::file_size(whole);
    for (auto keep : {size - 1, size / 2, uintmax_t(100), uintmax_t(20), uintmax_t(6)}) {
      const std::string path = dir.file("cut_" + std::to_string(keep) + ".exr");
      fs::copy_file(whole, path);
      fs::resize_file(path, keep);
      check_one_line_naming(error_of([&] { rtdr::read_exr(path); }), path);
    }
  }
}

TEST_CASE("a failed write_exr throws and leaves nothing at the destination") {
  TempDir dir;
  SECTION("into a folder that does not exist") {
    const std::string path = dir.file("no/such/folder/frame.exr");
    check_one_line_naming(error_of([&] { rtdr::write_exr(path, make_test_frame(7, 5)); }), path);
    CHECK_FALSE(fs::exists(path));
  }
  SECTION("over a folder (the rename fails after the data was written)") {
    const std::string path = dir.file("a_folder.exr");
    fs::create_directory(path);
    check_one_line_naming(error_of([&] { rtdr::write_exr(path, make_test_frame(7, 5)); }), path);
    CHECK(fs::is_directory(path));
    // Only the folder itself: the temporary was removed.
    CHECK(std::distance(fs::directory_iterator(dir.path), fs::directory_iterator()) == 1);
  }
  SECTION("an empty frame") {
    const std::string path = dir.file("empty.exr");
    check_one_line_naming(error_of([&] { rtdr::write_exr(path, Frame(0, 0)); }), path);
    CHECK_FALSE(fs::exists(path));
  }
}

TEST_CASE("require_finite names the channel and the first non-finite pixel") {
  Frame frame = make_test_frame(7, 5);
  frame.source = "out/frame_0003.exr";
  REQUIRE_NOTHROW(rtdr::require_finite(frame, {"color.R", "depth.Z", "id.instance"}));

  frame.float_channel("depth.Z").at(4, 2) = std::numeric_limits<float>::quiet_NaN();
  frame.float_channel("depth.Z").at(6, 3) = std::numeric_limits<float>::infinity();  // later in row order
  std::string message = error_of([&] { rtdr::require_finite(frame, {"color.R", "depth.Z"}); });
  check_one_line_naming(message, frame.source);
  CHECK(message.find("depth.Z") != std::string::npos);
  CHECK(message.find("NaN") != std::string::npos);
  CHECK(message.find("(4, 2)") != std::string::npos);
  CHECK_NOTHROW(rtdr::require_finite(frame, {"color.R"}));  // only the listed channels are checked

  frame.float_channel("color.R").at(1, 0) = -std::numeric_limits<float>::infinity();
  message = error_of([&] { rtdr::require_finite(frame, {"color.R"}); });
  CHECK(message.find("color.R") != std::string::npos);
  CHECK(message.find("(1, 0)") != std::string::npos);
  CHECK(message.find("Inf") != std::string::npos);

  CHECK_THROWS_AS(rtdr::require_finite(frame, {"no.such"}), rtdr::Error);
}

TEST_CASE("require_same_size names both frames") {
  Frame a(7, 5), b(7, 5), c(5, 7);
  a.source = "a.exr";
  c.source = "c.exr";
  CHECK_NOTHROW(rtdr::require_same_size(a, b));
  const std::string message = error_of([&] { rtdr::require_same_size(a, c); });
  check_one_line_naming(message, "a.exr");
  check_one_line_naming(message, "c.exr");
  CHECK(message.find("7x5") != std::string::npos);
  CHECK(message.find("5x7") != std::string::npos);
}

TEST_CASE("read_exr rejects header attributes whose size is not what OpenEXR reads, before OpenEXR reads them") {
  // fuzz/exr_reader_fuzz found files whose header makes OpenEXR 3.1 allocate and clear about 2 GB (seconds)
  // before it notices that the file ends: a string declaring 1979711507 bytes, right after the version or
  // behind a chlist that declares more bytes than its channel list holds (OpenEXR reads the list up to its
  // end marker and takes the next bytes for the next attribute). Each header here is cut after the
  // attribute that is wrong.
  TempDir dir;
  auto check = [&](const std::string& name, const ExrBytes& f, const std::string& expected) {
    const std::string path = dir.file(name + ".exr");
    write_bytes(path, f.bytes);
    const std::string message = error_of([&] { rtdr::read_exr(path); });
    check_one_line_naming(message, path);
    INFO("message: " << message);
    CHECK(message.find(expected) != std::string::npos);
  };
  auto header = [] {
    ExrBytes f;
    f.put(uint32_t(20000630));  // magic number
    f.put(uint32_t(2));         // version 2, single-part scanline
    return f;
  };

  for (const int32_t size : {int32_t(0x76000013), int32_t(-1)}) {  // OpenEXR reads the size as a signed int
    ExrBytes f = header();
    f.attribute("capDate", "string", size);
    f.put_name("2026:11:23 23:55:18");
    check("string_" + std::to_string(size), f, "'capDate' declares " + std::to_string(size) + " bytes");
  }
  {
    ExrBytes f = header();
    f.attribute("channels", "chlist", 40);  // an empty list (1 byte), then the bytes of the next attribute
    f.bytes.push_back(0);
    f.attribute("capDate", "string", int32_t(0x76000013));
    f.bytes.resize(f.bytes.size() + 40);
    check("chlist", f, "'channels' of type 'chlist' declares 40 bytes but its value takes 1");
  }
  {
    ExrBytes f = header();
    f.attribute("dataWindow", "box2i", 17);  // a box2i is four ints, 16 bytes
    f.bytes.resize(f.bytes.size() + 40);
    check("box2i", f, "'dataWindow' of type 'box2i' declares 17 bytes but its value takes 16");
  }
}

TEST_CASE("read_exr rejects an uncompressed file too small for its pixels") {
  // fuzz/exr_reader_fuzz found a 1160-byte uncompressed file whose data window says 4194306x2: OpenEXR 3.1
  // read it without complaint, the rows it did not find filled with whatever its buffers held. Here a
  // hand-made 2x2 file whose data window is widened to 100000x2 after it was written.
  TempDir dir;
  std::vector<uint8_t> bytes = hand_made_exr(0, 0, 2, 2, {{"Y", 2, {1, 2, 3, 4}}});
  const std::string key = "dataWindow";
  const auto at = std::search(bytes.begin(), bytes.end(), key.begin(), key.end());
  REQUIRE(at != bytes.end());
  // name\0 "box2i"\0 size(4), then min.x, min.y, max.x: max.x is 28 bytes after the name starts.
  const int32_t max_x = 99999;
  std::memcpy(&*(at + std::ptrdiff_t(key.size() + 1 + 6 + 4 + 8)), &max_x, sizeof max_x);
  const std::string path = dir.file("wide.exr");
  write_bytes(path, bytes);
  const std::string message = error_of([&] { rtdr::read_exr(path); });
  check_one_line_naming(message, path);
  CHECK(message.find("uncompressed") != std::string::npos);
  CHECK(message.find("its 100000x2 pixels of 1 channel (800000 bytes)") != std::string::npos);
}

TEST_CASE("read_exr rejects tiles larger than the image, before OpenEXR allocates them") {
  // fuzz/exr_reader_fuzz found a 1 KB tiled file whose tiles were declared 2^15 pixels wide: opening it made
  // OpenEXR 3.1 allocate 2.2 GB of tile buffers. Here hand-made headers of an 8x8 tiled file; the check
  // runs on the header alone, so no pixels follow.
  TempDir dir;
  auto tiled_header = [](uint32_t tile_width, uint32_t tile_height) {
    ExrBytes f;
    f.put(uint32_t(20000630));      // magic number
    f.put(uint32_t(2 | 0x200));     // version 2, single-part tiled
    f.attribute("channels", "chlist", 2 + 16 + 1);
    f.put_name("Y");
    f.put(int32_t(2));    // FLOAT
    f.put(uint32_t(0));   // pLinear, reserved
    f.put(int32_t(1));    // xSampling
    f.put(int32_t(1));    // ySampling
    f.bytes.push_back(0);
    f.attribute("compression", "compression", 1);
    f.bytes.push_back(0);
    for (const char* window : {"dataWindow", "displayWindow"}) {
      f.attribute(window, "box2i", 16);
      for (int32_t v : {0, 0, 7, 7}) f.put(v);
    }
    f.attribute("tiles", "tiledesc", 9);
    f.put(tile_width);
    f.put(tile_height);
    f.bytes.push_back(0);  // ONE_LEVEL, ROUND_DOWN
    f.bytes.push_back(0);  // end of header
    return f.bytes;
  };
  auto message_for = [&](uint32_t tile_width, uint32_t tile_height) {
    const std::string path = dir.file(std::to_string(tile_width) + "x" + std::to_string(tile_height) + ".exr");
    write_bytes(path, tiled_header(tile_width, tile_height));
    const std::string message = error_of([&] { rtdr::read_exr(path); });
    check_one_line_naming(message, path);
    return message;
  };
  CHECK(message_for(32768, 32768).find("its tiles (32768x32768) are larger than its 8x8 image") !=
        std::string::npos);
  CHECK(message_for(257, 8).find("tiles (257x8) are larger") != std::string::npos);
  CHECK(message_for(8, 0x80000000u).find("tiles (8x2147483648) are larger") != std::string::npos);
  // Tiles up to 256 pixels are accepted for any image: the file is then refused for what it lacks (pixels).
  for (const uint32_t side : {1u, 8u, 64u, 256u}) {
    INFO("tile side " << side);
    CHECK(message_for(side, side).find("tiles (") == std::string::npos);
  }
}
