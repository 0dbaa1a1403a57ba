// Multi-layer OpenEXR files <-> Frames (OpenEXR 3.1's Imf::OutputFile / Imf::InputFile). See exr_io.h.
//
// Both directions describe the image to OpenEXR the same way: a Header lists the channels and their pixel
// types, and a FrameBuffer gives, per channel, a Slice: where its first pixel lives in memory and how far
// apart neighbouring pixels (x stride) and rows (y stride) are. Our planes are tightly packed rows, so the
// strides are sizeof(value) and width * sizeof(value).
#include "core/exr_io.h"

#include "core/atomic_file.h"
#include "core/error.h"

#include <OpenEXR/ImfChannelList.h>
#include <OpenEXR/ImfFrameBuffer.h>
#include <OpenEXR/ImfHeader.h>
#include <OpenEXR/ImfInputFile.h>
#include <OpenEXR/ImfOutputFile.h>
#include <OpenEXR/ImfStdIO.h>
#include <OpenEXR/ImfStringAttribute.h>
#include <OpenEXR/ImfTestFile.h>

#include <algorithm>
#include <cassert>
#include <cctype>
#include <cerrno>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <map>

namespace rtdr {
namespace {

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

std::string source_of(const Frame& frame) { return frame.source.empty() ? std::string("frame") : frame.source; }

// The Slice of one tightly packed plane. OpenEXR takes a `char*` for both reading and writing; when
// writing it only reads through it, so the const_cast is safe.
template <class T>
Imf::Slice slice_of(Imf::PixelType type, const Plane<T>& plane) {
  char* base = reinterpret_cast<char*>(const_cast<T*>(plane.data.data()));
  return Imf::Slice(type, base, sizeof(T), sizeof(T) * size_t(plane.width));
}

// Declares one channel in the header and points the frame buffer at its plane.
template <class T>
void add_channel(Imf::Header& header, Imf::FrameBuffer& buffer, const std::string& name, Imf::PixelType type,
                 const Plane<T>& plane) {
  header.channels().insert(name, Imf::Channel(type));
  buffer.insert(name, slice_of(type, plane));
}

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
// values of dataWindow (box2i) and tiles (tiledesc), empty when the part has none.
struct PartShape {
  std::string window, tiles;
};

// A little-endian 32-bit integer at byte `at` of an attribute value.
uint32_t le32(const std::string& value, size_t at) {
  uint32_t v = 0;
  for (size_t i = 0; i < 4; ++i) v |= uint32_t(uint8_t(value[at + i])) << (8 * i);
  return v;
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
// The walk also checks each part's tile size against its data window (require_tiles_fit).
void require_consistent_header(const std::string& path, bool multi_part) {
  std::error_code ec;
  const auto file_size = std::streamoff(std::filesystem::file_size(path, ec));
  std::ifstream in(path, std::ios::binary);
  if (ec || !in.seekg(8)) return;
  bool part_ended = false;  // the last attribute list ended; in a multi-part file another may follow
  PartShape part;
  for (std::string name, type; std::getline(in, name, '\0');) {
    if (name.empty()) {
      require_tiles_fit(path, part);
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
  }
}

// Everything read_exr checks before OpenEXR opens the file: it exists, it is a flat (not deep) OpenEXR
// file, and every header attribute declares the size OpenEXR reads for it.
void require_readable_exr(const std::string& path) {
  std::error_code ec;
  if (!std::filesystem::is_regular_file(path, ec)) throw Error("cannot read EXR file '" + path + "': no such file");
  bool tiled = false, deep = false, multi_part = false;
  if (!Imf::isOpenExrFile(path.c_str(), tiled, deep, multi_part))
    throw Error("cannot read EXR file '" + path + "': not an OpenEXR file");
  if (deep) throw Error("cannot read EXR file '" + path + "': deep images are not supported");
  require_consistent_header(path, multi_part);
}

// An uncompressed file stores every pixel as it is, so it cannot be smaller than its pixels. OpenEXR 3.1 does
// not check: a chunk shorter than its scanline leaves the rest of its buffer as it was, and a 1160-byte file
// was read as a 4194306x2 frame of 20 channels, 1 GB of whatever that memory held, in 7 s (found by
// fuzz/exr_reader_fuzz). Compressed chunks are checked by their decompressors.
void require_uncompressed_pixels_in_file(const std::string& path, const Imf::Header& header) {
  if (header.compression() != Imf::NO_COMPRESSION) return;
  const Imath::Box2i window = header.dataWindow();
  uint64_t row_bytes = 0;  // one row of every channel: at most 2^31 * 4 * channels, no overflow
  for (auto channel = header.channels().begin(); channel != header.channels().end(); ++channel)
    row_bytes += uint64_t(window.max.x - window.min.x + 1) * (channel.channel().type == Imf::HALF ? 2 : 4);
  const uint64_t rows = uint64_t(window.max.y - window.min.y + 1);
  std::error_code ec;
  const uint64_t file_size = std::filesystem::file_size(path, ec);
  if (!ec && row_bytes > 0 && rows > file_size / row_bytes)
    throw Error("cannot read EXR file '" + path + "': it is uncompressed but its " + std::to_string(file_size) +
                " bytes cannot hold its " + std::to_string(rows) + " rows of " + std::to_string(row_bytes) +
                " bytes (truncated or damaged)");
}

// Reads the pixels of an opened file into a new Frame. Throws rtdr::Error for layouts we do not support;
// OpenEXR's own exceptions pass through to read_exr.
Frame read_pixels(const std::string& path, Imf::InputFile& file) {
  const Imath::Box2i window = file.header().dataWindow();
  // Pixel (0, 0) of a Frame is the top-left of the data window, so a window elsewhere would silently
  // shift the image against every other buffer of the frame.
  if (window.min.x != 0 || window.min.y != 0)
    throw Error("cannot read EXR file '" + path + "': its data window starts at (" + std::to_string(window.min.x) +
                ", " + std::to_string(window.min.y) + "), expected (0, 0)");
  // A file whose writer was interrupted has chunks missing; OpenEXR would fill them without complaint.
  if (!file.isComplete()) throw Error("cannot read EXR file '" + path + "': the file is incomplete (truncated?)");
  require_uncompressed_pixels_in_file(path, file.header());

  Frame frame(window.max.x + 1, window.max.y + 1);
  frame.source = path;
  for (auto a = file.header().begin(); a != file.header().end(); ++a)
    if (const auto* text = dynamic_cast<const Imf::StringAttribute*>(&a.attribute());
        text && std::string(a.name()).rfind("rtdr.", 0) == 0)
      frame.attributes[a.name()] = text->value();
  Imf::FrameBuffer buffer;
  for (auto channel = file.header().channels().begin(); channel != file.header().channels().end(); ++channel) {
    const std::string name = channel.name();
    if (channel.channel().xSampling != 1 || channel.channel().ySampling != 1)
      throw Error("cannot read EXR file '" + path + "': channel '" + name + "' is subsampled (not supported)");
    switch (channel.channel().type) {
      case Imf::UINT:
        buffer.insert(name, slice_of(Imf::UINT, frame.add_uint(name)));
        break;
      case Imf::FLOAT:
      case Imf::HALF:  // a FLOAT slice makes OpenEXR convert each half to float while reading
        buffer.insert(name, slice_of(Imf::FLOAT, frame.add_float(name)));
        break;
      default:
        throw Error("cannot read EXR file '" + path + "': channel '" + name + "' has an unknown pixel type");
    }
  }
  file.setFrameBuffer(buffer);
  file.readPixels(window.min.y, window.max.y);
  return frame;
}

}  // namespace

void write_exr(const std::string& path, const Frame& frame) {
  if (frame.width() <= 0 || frame.height() <= 0)
    throw Error("cannot write EXR file '" + path + "': the frame is empty (" + std::to_string(frame.width()) + "x" +
                std::to_string(frame.height()) + ")");

  // The header: size (data window = display window = [0, w-1] x [0, h-1]), ZIP compression (lossless,
  // zlib over blocks of 16 scanlines), and one channel per plane.
  Imf::Header header(frame.width(), frame.height());
  header.compression() = Imf::ZIP_COMPRESSION;
  for (const auto& [name, value] : frame.attributes) header.insert(name, Imf::StringAttribute(value));
  Imf::FrameBuffer buffer;
  for (const auto& [name, plane] : frame.float_channels()) {
    assert(plane.width == frame.width() && plane.height == frame.height());
    add_channel(header, buffer, name, Imf::FLOAT, plane);
  }
  for (const auto& [name, plane] : frame.uint_channels()) {
    assert(plane.width == frame.width() && plane.height == frame.height());
    add_channel(header, buffer, name, Imf::UINT, plane);
  }

  write_file_atomically(path, [&](const std::string& temporary) {
    // OpenEXR writes through its own stream class; StdOFStream wraps a std::ofstream we own, so that
    // after ~OutputFile has written the table of scanline offsets (it cannot report errors) we can
    // still see whether every byte reached the file.
    std::ofstream stream(temporary, std::ios::binary | std::ios::trunc);
    if (!stream) throw Error("cannot create '" + temporary + "' (" + std::strerror(errno) + ")");
    try {
      Imf::StdOFStream exr_stream(stream, temporary.c_str());
      Imf::OutputFile file(exr_stream, header);
      file.setFrameBuffer(buffer);
      file.writePixels(frame.height());
    } catch (const std::exception& e) {  // Iex::BaseExc derives from std::exception
      throw Error(one_line(e.what()));
    }
    stream.close();  // flushes the last bytes: a full disk shows up here
    if (!stream) throw Error("the data could not be written completely (disk full?)");
  });
}

Frame read_exr(const std::string& path) {
  require_readable_exr(path);
  try {
    Imf::InputFile file(path.c_str());
    return read_pixels(path, file);
  } catch (const Error&) {
    throw;
  } catch (const std::exception& e) {  // Iex::BaseExc derives from std::exception
    throw Error("cannot read EXR file '" + path + "': " + one_line(e.what()));
  }
}

void require_finite(const Frame& frame, const std::vector<std::string>& channels) {
  for (const std::string& name : channels) {
    if (frame.uint_channels().count(name)) continue;     // integers cannot be NaN or infinite
    const FloatPlane& plane = frame.float_channel(name);  // throws when the channel is missing
    for (int y = 0; y < plane.height; ++y) {
      for (int x = 0; x < plane.width; ++x) {
        const float value = plane.at(x, y);
        if (std::isfinite(value)) continue;
        const std::string kind = std::isnan(value) ? "NaN" : (value > 0.0f ? "+Inf" : "-Inf");
        throw Error(source_of(frame) + ": channel '" + name + "' holds " + kind + " at pixel (" +
                    std::to_string(x) + ", " + std::to_string(y) + ")");
      }
    }
  }
}

void require_same_size(const Frame& a, const Frame& b) {
  if (a.width() == b.width() && a.height() == b.height()) return;
  auto size = [](const Frame& f) { return std::to_string(f.width()) + "x" + std::to_string(f.height()); };
  throw Error(source_of(a) + " is " + size(a) + " but " + source_of(b) + " is " + size(b) +
              "; the frames must have the same size");
}

}  // namespace rtdr
