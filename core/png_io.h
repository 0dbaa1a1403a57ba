// 8-bit RGB PNG previews, written by hand with zlib: the smallest valid PNG (W3C PNG Specification,
// Second Edition, 2003): the signature, an IHDR chunk, one IDAT chunk, an IEND chunk.
//
// Previews are for looking at, not for measuring; measurements read the EXR files (core/exr_io.h).
// Colour conversion for previews (linear -> sRGB bytes) is in core/color.h.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

namespace rtdr {

// Writes `rgb` (width * height * 3 bytes: R, G, B per pixel, rows top to bottom) as a PNG at `path`,
// atomically (core/atomic_file.h). Throws a one-line rtdr::Error naming the file on failure.
void write_png(const std::string& path, int width, int height, const std::vector<uint8_t>& rgb);

// The bytes of that PNG file, for tests and for callers that keep the image in memory.
std::vector<uint8_t> encode_png(int width, int height, const std::vector<uint8_t>& rgb);

}  // namespace rtdr
