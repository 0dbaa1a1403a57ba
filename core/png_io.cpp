// A PNG writer in a few dozen lines, following the W3C PNG Specification (Second Edition, 2003).
//
// A PNG file is an 8-byte signature followed by chunks. Every chunk is
//   length (4 bytes, big-endian, counts the data only) | type (4 ASCII letters) | data | CRC-32 (4 bytes),
// where the CRC covers the type and the data (PNG spec Sec. 5.3) and is the same CRC-32 that zlib's
// crc32() computes (PNG spec Annex D). We write three chunks:
//   IHDR: the image size and pixel format (Sec. 11.2.2),
//   IDAT: the pixels, each row prefixed with a filter-type byte, compressed as one zlib stream (Sec. 10),
//   IEND: the end marker, with no data (Sec. 11.2.5).
#include "core/png_io.h"

#include "core/atomic_file.h"
#include "core/error.h"

#include <zlib.h>

#include <cerrno>
#include <cstring>
#include <fstream>
#include <stdexcept>

namespace rtdr {
namespace {

// PNG stores every multi-byte integer big-endian ("network byte order", PNG spec Sec. 7.1).
void append_u32_big_endian(std::vector<uint8_t>& out, uint32_t value) {
  out.push_back(uint8_t(value >> 24));
  out.push_back(uint8_t(value >> 16));
  out.push_back(uint8_t(value >> 8));
  out.push_back(uint8_t(value));
}

// Appends one chunk: length, type, data, then the CRC-32 of type and data.
void append_chunk(std::vector<uint8_t>& out, const char type[4], const std::vector<uint8_t>& data) {
  append_u32_big_endian(out, uint32_t(data.size()));
  const size_t type_start = out.size();
  out.insert(out.end(), type, type + 4);
  out.insert(out.end(), data.begin(), data.end());
  // crc32(0, nullptr, 0) is zlib's initial CRC value; then feed the type and data bytes.
  const uLong crc = crc32(crc32(0L, Z_NULL, 0), out.data() + type_start, uInt(4 + data.size()));
  append_u32_big_endian(out, uint32_t(crc));
}

// The IHDR data: width, height, bit depth 8, colour type 2 (truecolour: R, G, B per pixel),
// compression method 0 (zlib), filter method 0 (adaptive, five filter types), interlace 0 (none).
std::vector<uint8_t> header_data(int width, int height) {
  std::vector<uint8_t> data;
  append_u32_big_endian(data, uint32_t(width));
  append_u32_big_endian(data, uint32_t(height));
  data.insert(data.end(), {8, 2, 0, 0, 0});
  return data;
}

// The IDAT data: the "filtered" rows, each a filter-type byte followed by its 3 * width bytes, then the
// whole sequence compressed into one zlib stream. Filter type 0 ("None", PNG spec Sec. 9.2) leaves the
// bytes as they are: the simplest choice, at the cost of a somewhat larger file.
std::vector<uint8_t> pixel_data(int width, int height, const std::vector<uint8_t>& rgb) {
  const size_t row_bytes = 3 * size_t(width);
  std::vector<uint8_t> filtered;
  filtered.reserve(size_t(height) * (1 + row_bytes));
  for (int y = 0; y < height; ++y) {
    filtered.push_back(0);  // filter type 0: None
    const auto row = rgb.begin() + std::ptrdiff_t(size_t(y) * row_bytes);
    filtered.insert(filtered.end(), row, row + std::ptrdiff_t(row_bytes));
  }
  // compressBound() is zlib's worst-case size of the compressed stream; compress2 shrinks `size`.
  uLongf size = compressBound(uLong(filtered.size()));
  std::vector<uint8_t> compressed(size);
  if (compress2(compressed.data(), &size, filtered.data(), uLong(filtered.size()), Z_DEFAULT_COMPRESSION) != Z_OK)
    throw Error("zlib could not compress the PNG pixels");
  compressed.resize(size);
  return compressed;
}

}  // namespace

std::vector<uint8_t> encode_png(int width, int height, const std::vector<uint8_t>& rgb) {
  // PNG spec Sec. 11.2.2: width and height are in [1, 2^31 - 1].
  if (width <= 0 || height <= 0)
    throw Error("cannot encode a " + std::to_string(width) + "x" + std::to_string(height) + " PNG (empty image)");
  // A wrong buffer size is a caller's bug, but reading past its end would be worse than stopping.
  if (rgb.size() != 3 * size_t(width) * size_t(height))
    throw std::invalid_argument("encode_png: rgb holds " + std::to_string(rgb.size()) + " bytes, expected 3 * " +
                                std::to_string(width) + " * " + std::to_string(height));
  // The signature (PNG spec Sec. 5.2): \x89 P N G \r \n \x1a \n.
  std::vector<uint8_t> png = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1A, '\n'};
  append_chunk(png, "IHDR", header_data(width, height));
  append_chunk(png, "IDAT", pixel_data(width, height, rgb));
  append_chunk(png, "IEND", {});
  return png;
}

void write_png(const std::string& path, int width, int height, const std::vector<uint8_t>& rgb) {
  const std::vector<uint8_t> png = encode_png(width, height, rgb);
  write_file_atomically(path, [&](const std::string& temporary) {
    std::ofstream stream(temporary, std::ios::binary | std::ios::trunc);
    if (!stream) throw Error("cannot create '" + temporary + "' (" + std::strerror(errno) + ")");
    stream.write(reinterpret_cast<const char*>(png.data()), std::streamsize(png.size()));
    stream.close();  // flushes the last bytes: a full disk shows up here
    if (!stream) throw Error("the data could not be written completely (disk full?)");
  });
}

}  // namespace rtdr
