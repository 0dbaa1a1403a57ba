// Tests for core/png_io: the PNG we write is decoded back here independently, with nothing but zlib and
// the chunk layout of the PNG specification (W3C, Second Edition): signature, chunks with valid CRC-32s,
// IHDR fields, and IDAT inflating to rows of filter byte 0 followed by exactly our pixels. No Python, no
// image library.
#include "core/error.h"
#include "core/png_io.h"

#include <catch2/catch.hpp>

#include <unistd.h>
#include <zlib.h>

#include <filesystem>
#include <fstream>
#include <iterator>

namespace fs = std::filesystem;

namespace {

uint32_t read_u32_big_endian(const std::vector<uint8_t>& bytes, size_t at) {
  return uint32_t(bytes[at]) << 24 | uint32_t(bytes[at + 1]) << 16 | uint32_t(bytes[at + 2]) << 8 |
         uint32_t(bytes[at + 3]);
}

struct Chunk {
  std::string type;
  std::vector<uint8_t> data;
};

// Splits a PNG into its chunks, checking the signature and every chunk's CRC on the way.
std::vector<Chunk> parse_png(const std::vector<uint8_t>& png) {
  const std::vector<uint8_t> signature = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1A, '\n'};
  REQUIRE(png.size() >= signature.size());
  REQUIRE(std::equal(signature.begin(), signature.end(), png.begin()));
  std::vector<Chunk> chunks;
  size_t at = signature.size();
  while (at < png.size()) {
    REQUIRE(at + 12 <= png.size());  // length, type and CRC are 12 bytes
    const uint32_t length = read_u32_big_endian(png, at);
    REQUIRE(at + 12 + length <= png.size());
    const uint8_t* type_and_data = png.data() + at + 4;
    const uLong crc = crc32(crc32(0L, Z_NULL, 0), type_and_data, uInt(4 + length));
    INFO("chunk at byte " << at);
    CHECK(read_u32_big_endian(png, at + 8 + length) == uint32_t(crc));
    chunks.push_back({std::string(type_and_data, type_and_data + 4),
                      std::vector<uint8_t>(type_and_data + 4, type_and_data + 4 + length)});
    at += 12 + length;
  }
  return chunks;
}

// Decodes our PNG back to RGB bytes, checking every header field along the way.
std::vector<uint8_t> decode_png(const std::vector<uint8_t>& png, int width, int height) {
  const std::vector<Chunk> chunks = parse_png(png);
  REQUIRE(chunks.size() >= 3);
  CHECK(chunks.front().type == "IHDR");
  CHECK(chunks.back().type == "IEND");
  CHECK(chunks.back().data.empty());

  const std::vector<uint8_t>& ihdr = chunks.front().data;
  REQUIRE(ihdr.size() == 13);
  CHECK(read_u32_big_endian(ihdr, 0) == uint32_t(width));
  CHECK(read_u32_big_endian(ihdr, 4) == uint32_t(height));
  CHECK(ihdr[8] == 8);   // bit depth
  CHECK(ihdr[9] == 2);   // colour type: truecolour RGB
  CHECK(ihdr[10] == 0);  // compression: zlib
  CHECK(ihdr[11] == 0);  // filter method 0
  CHECK(ihdr[12] == 0);  // no interlace

  std::vector<uint8_t> compressed;  // IDAT chunks concatenate into one zlib stream
  for (const Chunk& c : chunks)
    if (c.type == "IDAT") compressed.insert(compressed.end(), c.data.begin(), c.data.end());
  const size_t row_bytes = 1 + 3 * size_t(width);  // the filter byte, then R, G, B per pixel
  std::vector<uint8_t> rows(row_bytes * size_t(height) + 1);  // one spare byte detects a too-long stream
  uLongf rows_size = uLongf(rows.size());
  REQUIRE(uncompress(rows.data(), &rows_size, compressed.data(), uLong(compressed.size())) == Z_OK);
  REQUIRE(rows_size == row_bytes * size_t(height));

  std::vector<uint8_t> rgb;
  for (int y = 0; y < height; ++y) {
    const auto row = rows.begin() + std::ptrdiff_t(size_t(y) * row_bytes);
    CHECK(*row == 0);  // filter type None
    rgb.insert(rgb.end(), row + 1, row + std::ptrdiff_t(row_bytes));
  }
  return rgb;
}

// A test image where every byte differs from its neighbours and all 256 values occur.
std::vector<uint8_t> test_image(int width, int height) {
  std::vector<uint8_t> rgb(size_t(width) * size_t(height) * 3);
  for (size_t i = 0; i < rgb.size(); ++i) rgb[i] = uint8_t((i * 37 + i / 3) & 0xFF);
  return rgb;
}

std::vector<uint8_t> read_file(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

}  // namespace

TEST_CASE("encode_png decodes back to the same pixels") {
  for (auto [w, h] : {std::pair{1, 1}, std::pair{7, 5}, std::pair{64, 3}, std::pair{3, 64}}) {
    INFO(w << "x" << h);
    const std::vector<uint8_t> rgb = test_image(w, h);
    CHECK(decode_png(rtdr::encode_png(w, h, rgb), w, h) == rgb);
  }
}

TEST_CASE("write_png writes exactly the encoded bytes, atomically") {
  const fs::path dir = fs::temp_directory_path() / ("rtdr_png_io_test_" + std::to_string(::getpid()));
  fs::remove_all(dir);
  fs::create_directories(dir);
  const std::string path = (dir / "preview.png").string();
  const std::vector<uint8_t> rgb = test_image(13, 9);

  rtdr::write_png(path, 13, 9, rgb);
  CHECK(read_file(path) == rtdr::encode_png(13, 9, rgb));
  CHECK(decode_png(read_file(path), 13, 9) == rgb);
  CHECK(std::distance(fs::directory_iterator(dir), fs::directory_iterator()) == 1);  // no temporary left

  const std::string unwritable = (dir / "no_such_folder" / "preview.png").string();
  try {
    rtdr::write_png(unwritable, 13, 9, rgb);
    FAIL("expected an rtdr::Error");
  } catch (const rtdr::Error& e) {
    const std::string message = e.what();
    CHECK(message.find(unwritable) != std::string::npos);
    CHECK(message.find('\n') == std::string::npos);
  }
  CHECK_FALSE(fs::exists(unwritable));
  fs::remove_all(dir);
}

TEST_CASE("encode_png rejects an empty image") {
  CHECK_THROWS_AS(rtdr::encode_png(0, 4, {}), rtdr::Error);
}
