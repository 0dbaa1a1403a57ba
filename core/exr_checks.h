// What read_exr (core/exr_io.h) checks in a file before OpenEXR reads it: OpenEXR 3.1 believes what a header
// declares and allocates for it before it reads a pixel, so a small file can make it take gigabytes. Every check
// throws a one-line rtdr::Error "cannot read EXR file '<path>': ..." before anything is allocated for pixels.
//
// - Each header attribute declares exactly the bytes OpenEXR reads for it, and they are in the file
//   (require_consistent_header).
// - Tiles are at most the image's size, or 256 pixels, in each direction.
// - The pixels fit in the file: the bytes of the pixels it declares, as stored (HALF 2 bytes, FLOAT and UINT 4),
//   are at most its size times the most its compression can decode from one byte (exr_max_expansion): an
//   8,542-byte ZIP file cannot hold 16384 x 16384 x 3 floats (3 GiB; at least 3.1 MB of ZIP).
// - The planes they become (4 bytes per value) fit in the memory budget (core/memory_budget.h).
#pragma once

#include "core/memory_budget.h"

#include <cstdint>
#include <istream>
#include <string>

namespace rtdr {

// OpenEXR's messages can span several lines; an rtdr::Error is one line. Folds every run of white space
// (newlines included) into one space and trims the ends.
std::string one_line(const std::string& message);

// Walks the header of the file read by `in` (`file_size` bytes) as OpenEXR will, and checks each part's
// attributes, tiles and pixels (require_plausible_exr, against `budget`). See exr_checks.cpp for why each
// attribute's declared size matters.
void require_consistent_header(const std::string& path, std::istream& in, uint64_t file_size, bool multi_part,
                               const MemoryBudget& budget);

// The most bytes of pixels that one byte of a chunk compressed with EXR compression `compression` decodes to
// (the file format's numbers: 0 none, 1 RLE, 2 ZIPS, 3 ZIP, 4 PIZ, 5 PXR24, 6 B44, 7 B44A, 8 DWAA, 9 DWAB); 0 for
// a number OpenEXR does not know. Each bound is derived in exr_checks.cpp.
uint64_t exr_max_expansion(int compression);
// Its name, for messages: "ZIP".
std::string exr_compression_name(int compression);

// What a header declares about its pixels.
struct ExrDeclared {
  int64_t width = 0, height = 0;  // of the data window
  int channels = 0;
  uint64_t stored_bytes_per_pixel = 0;  // all channels, as stored: HALF 2, FLOAT and UINT 4
  int compression = 0;
};

// Throws unless the pixels fit in the file (of `file_size` bytes) and the planes read_exr makes for them (4 bytes
// per value) fit in `budget`.
void require_plausible_exr(const std::string& path, const ExrDeclared& image, uint64_t file_size,
                           const MemoryBudget& budget);

}  // namespace rtdr
