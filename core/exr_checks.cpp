// What read_exr checks in a file before OpenEXR reads it. See exr_checks.h.
#include "core/exr_checks.h"

#include "core/error.h"

#include <algorithm>
#include <cctype>
#include <map>

namespace rtdr {

// OpenEXR's messages can span several lines; an rtdr::Error is one line. Folds every run of white space
// (newlines included) into one space and trims the ends.
std::string one_line(const std::string& message) {
  std::string out;
  bool pending_space = false;
  for (char c : message) {
    if (std::isspace(static_cast<unsigned char>(c))) {
      pending_space = !out.empty();
      continue;
    }
    if (pending_space) out += ' ';
    pending_space = false;
    out += c;
  }
  return out;
}


namespace {

// The bytes OpenEXR 3.1 reads for a value of a fixed-size attribute type, whatever size the file declares
// ("The OpenEXR File Layout", predefined attribute types); -1 for the other types.
int fixed_value_size(const std::string& type) {
  static const std::map<std::string, int> sizes = {
      {"box2f", 16},  {"box2i", 16},   {"chromaticities", 32}, {"compression", 1}, {"deepImageState", 1},
      {"double", 8},  {"envmap", 1},   {"float", 4},           {"int", 4},         {"keycode", 28},
      {"lineOrder", 1}, {"m33d", 72},  {"m33f", 36},           {"m44d", 128},      {"m44f", 64},
      {"rational", 8}, {"tiledesc", 9}, {"timecode", 8},       {"v2d", 16},        {"v2f", 8},
      {"v2i", 8},     {"v3d", 24},     {"v3f", 12},            {"v3i", 12}};
  const auto it = sizes.find(type);
  return it == sizes.end() ? -1 : it->second;
}

// The bytes OpenEXR 3.1 reads for a chlist value: channels (name\0, then 16 bytes) up to an empty name,
// whatever size the file declares; -1 when the list does not end inside `value`.
int64_t channel_list_size(const std::string& value) {
  size_t at = 0;
  while (at < value.size()) {
    const size_t name_end = value.find('\0', at);
    if (name_end == std::string::npos) return -1;
    if (name_end == at) return int64_t(at) + 1;  // the empty name that ends the list
    at = name_end + 1 + 16;
  }
  return -1;
}

// The attributes of one part's header that bound what OpenEXR allocates when it opens the part: the raw
// values of dataWindow (box2i), tiles (tiledesc), channels (chlist) and compression, empty when the part has
// none.
struct PartShape {
  std::string window, tiles, channels, compression;
};

// A little-endian 32-bit integer at byte `at` of an attribute value.
uint32_t le32(const std::string& value, size_t at) {
  uint32_t v = 0;
  for (size_t i = 0; i < 4; ++i) v |= uint32_t(uint8_t(value[at + i])) << (8 * i);
  return v;
}

// What the part declares about its pixels, read from the raw values as OpenEXR will read them (a chlist entry:
// name\0, then pixel type, pLinear and 3 reserved bytes, x and y sampling, 16 bytes). A subsampled channel
// counts no stored bytes: the bound must not refuse what a file can hold (read_exr refuses it later anyway).
// Empty (width 0) when the part lacks a value OpenEXR needs: OpenEXR then reports the damage.
ExrDeclared declared_of(const PartShape& part) {
  ExrDeclared d;
  if (part.window.size() != 16 || part.compression.size() != 1 || channel_list_size(part.channels) < 0) return d;
  for (size_t at = 0; at < part.channels.size() && part.channels[at] != '\0';) {
    at = part.channels.find('\0', at) + 1;
    const uint32_t type = le32(part.channels, at);
    const bool full = le32(part.channels, at + 8) == 1 && le32(part.channels, at + 12) == 1;
    d.stored_bytes_per_pixel += full ? (type == 1 ? 2 : 4) : 0;  // 1: HALF; 0 UINT and 2 FLOAT
    ++d.channels;
    at += 16;
  }
  d.width = int64_t(int32_t(le32(part.window, 8))) - int32_t(le32(part.window, 0)) + 1;
  d.height = int64_t(int32_t(le32(part.window, 12))) - int32_t(le32(part.window, 4)) + 1;
  d.compression = uint8_t(part.compression[0]);
  return d;
}

// OpenEXR 3.1 allocates a tile's worth of buffers for every thread when it opens a tiled file, before it
// reads a pixel: a 1 KB file whose tiles are declared 2^15 pixels wide made it allocate 2.2 GB
// (fuzz/exr_reader_fuzz found it). A tile wider or taller than the image serves no purpose, so we accept
// tiles up to the data window's size in each direction, or up to 256 pixels (writers use 64 to 256 tiles
// for small images too); what OpenEXR allocates for them is then of the order of the frame itself.
void require_tiles_fit(const std::string& path, const PartShape& part) {
  if (part.tiles.size() != 9 || part.window.size() != 16) return;  // scanline, or OpenEXR reports the damage
  const uint32_t tile_width = le32(part.tiles, 0), tile_height = le32(part.tiles, 4);
  // The window's sides in 64 bits: max - min + 1 of two int32s can exceed 2^31.
  const int64_t width = int64_t(int32_t(le32(part.window, 8))) - int32_t(le32(part.window, 0)) + 1;
  const int64_t height = int64_t(int32_t(le32(part.window, 12))) - int32_t(le32(part.window, 4)) + 1;
  constexpr int64_t kSmallTile = 256;
  if (tile_width <= std::max(width, kSmallTile) && tile_height <= std::max(height, kSmallTile)) return;
  throw Error("cannot read EXR file '" + path + "': its tiles (" + std::to_string(tile_width) + "x" +
              std::to_string(tile_height) + ") are larger than its " + std::to_string(width) + "x" +
              std::to_string(height) + " image (damaged?)");
}

}  // namespace

// OpenEXR 3.1 believes the size a header attribute declares: a 126-byte file whose header announces a 1.9 GB
// string makes it allocate and clear 1.9 GB before it finds the file too short (fuzz/exr_reader_fuzz found
// it). Only some types read the declared size, though: a chlist is read up to its end marker, a box2i is 16
// bytes whatever the size says, and OpenEXR goes on reading the next attribute from where the value ended.
// So before OpenEXR reads the header, every attribute must declare exactly the bytes OpenEXR reads for it,
// and they must be in the file; then our walk through the header and OpenEXR's agree on every size.
// The layout ("The OpenEXR File Layout"): magic number and version, 4 bytes each, then per part its
// attributes, each name\0 type\0 size (int32, little-endian) value[size], ended by an empty name; in a
// multi-part file an empty name also follows the last part's header. Other damage (a name without its \0
// or longer than the 255 characters OpenEXR allows) is left to OpenEXR, which reports it.
//
// The walk also checks each part's tile size against its data window (require_tiles_fit), and its pixels against
// the file's size and the memory budget (require_plausible_exr).
void require_consistent_header(const std::string& path, std::istream& in, uint64_t file_size_bytes, bool multi_part,
                               const MemoryBudget& budget) {
  const auto file_size = std::streamoff(file_size_bytes);
  in.clear();
  if (!in.seekg(8)) return;
  bool part_ended = false;  // the last attribute list ended; in a multi-part file another may follow
  PartShape part;
  for (std::string name, type; std::getline(in, name, '\0');) {
    if (name.empty()) {
      require_tiles_fit(path, part);
      const ExrDeclared declared = declared_of(part);
      if (declared.width > 0) require_plausible_exr(path, declared, file_size_bytes, budget);
      part = PartShape{};
      if (!multi_part || part_ended) return;  // the end of the (last) header
      part_ended = true;
      continue;
    }
    part_ended = false;
    unsigned char size_bytes[4];
    if (name.size() > 255 || !std::getline(in, type, '\0') || type.size() > 255 ||
        !in.read(reinterpret_cast<char*>(size_bytes), 4))
      return;
    const int32_t size = int32_t(uint32_t(size_bytes[0]) | uint32_t(size_bytes[1]) << 8 |
                                 uint32_t(size_bytes[2]) << 16 | uint32_t(size_bytes[3]) << 24);
    const std::string what = "cannot read EXR file '" + path + "': header attribute '" + one_line(name) + "' ";
    const std::streamoff left = file_size - in.tellg();
    if (size < 0 || size > left)
      throw Error(what + "declares " + std::to_string(size) + " bytes, but only " + std::to_string(left) +
                  " follow (truncated?)");

    // What OpenEXR will read: a fixed size, a channel list up to its end, whole floats, or the declared size.
    std::string value(size_t(size), '\0');
    if (!in.read(value.data(), size)) return;
    int64_t read = size;
    if (fixed_value_size(type) >= 0) read = fixed_value_size(type);
    if (type == "chlist") read = channel_list_size(value);
    if (type == "floatvector") read = size - size % 4;
    if (read != size)
      throw Error(what + "of type '" + one_line(type) + "' declares " + std::to_string(size) +
                  " bytes but its value takes " + (read < 0 ? "more" : std::to_string(read)));
    if (name == "dataWindow" && type == "box2i") part.window = value;
    if (name == "tiles" && type == "tiledesc") part.tiles = value;
    if (name == "channels" && type == "chlist") part.channels = value;
    if (name == "compression" && type == "compression") part.compression = value;
  }
}


// Each bound is what the decoder can emit for one byte it reads, at best, so a file holding more pixels than its
// size times the bound cannot be read whatever its chunks hold ("The OpenEXR File Layout"; OpenEXR 3.1's
// decoders):
// - none: 1, a pixel is stored as it is.
// - RLE: a run of at most 128 equal bytes costs 2 bytes (a count byte of at most 127, meaning count + 1, and
//   the byte): 64.
// - ZIPS, ZIP: zlib's deflate, whose longest match (258 bytes) costs at least 2 bits (1-bit length and distance
//   codes): 1032 (zlib's FAQ gives the same); the predictor and interleaving before it keep the size.
// - PXR24: deflate over floats cut to 24 bits, each 3 bytes decoding to 4: 1032 * 4 / 3 = 1376.
// - PIZ: a wavelet and a lookup table that keep the count of 16-bit values, then OpenEXR's Huffman code, whose
//   longest run (a run code of at least 1 bit and an 8-bit count) repeats the last value 255 times: 510 bytes
//   from 9 bits, 454.
// - B44, B44A: a 4x4 block of halfs (32 bytes) from at least 3 bytes (B44A's flat block), other types stored
//   as they are: 11.
// - DWAA, DWAB: a lossy DCT per 8x8 block; a flat block is one DC value (deflated, 1032) and one end-of-block
//   code (Huffman runs, 454), a few thousandths of a byte for 64 values of 4 bytes, about 4 * 10^4. We take
//   2^16, above it: a bound that must not refuse a real file.
uint64_t exr_max_expansion(int compression) {
  switch (compression) {
    case 0: return 1;
    case 1: return 64;
    case 2:
    case 3: return 1032;
    case 4: return 454;
    case 5: return 1376;
    case 6:
    case 7: return 11;
    case 8:
    case 9: return uint64_t(1) << 16;
    default: return 0;
  }
}

std::string exr_compression_name(int compression) {
  static const char* const names[] = {"no", "RLE", "ZIPS", "ZIP", "PIZ", "PXR24", "B44", "B44A", "DWAA", "DWAB"};
  return compression >= 0 && compression < 10 ? names[compression] : "unknown (" + std::to_string(compression) + ")";
}

void require_plausible_exr(const std::string& path, const ExrDeclared& image, uint64_t file_size,
                           const MemoryBudget& budget) {
  const std::string what = "cannot read EXR file '" + path + "': ";
  const uint64_t pixels = saturating_product(uint64_t(std::max<int64_t>(image.width, 0)),
                                             uint64_t(std::max<int64_t>(image.height, 0)));
  const uint64_t stored = saturating_product(pixels, image.stored_bytes_per_pixel);
  const std::string declared = "its " + std::to_string(image.width) + "x" + std::to_string(image.height) +
                               " pixels of " + std::to_string(image.channels) + (image.channels == 1 ? " channel" : " channels");
  const uint64_t expansion = exr_max_expansion(image.compression);
  if (expansion == 1 && stored > file_size)  // an uncompressed file holds every pixel as it is
    throw Error(what + "it is uncompressed, but its " + std::to_string(file_size) + " bytes cannot hold " +
                declared + " (" + std::to_string(stored) + " bytes): truncated or damaged");
  if (expansion > 1 && stored / expansion > file_size)
    throw Error(what + declared + " (" + format_bytes(stored) + ") cannot come from its " +
                std::to_string(file_size) + " bytes: " + exr_compression_name(image.compression) +
                " compression decodes at most " + std::to_string(expansion) +
                " bytes from each (core/exr_checks.cpp); truncated or damaged");
  // read_exr's planes: 4 bytes per value, a HALF widened to a float.
  require_within_budget(saturating_product(pixels, saturating_product(uint64_t(image.channels), 4)),
                        what + "reading " + declared, budget);
}

}  // namespace rtdr
