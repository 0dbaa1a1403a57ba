// Multi-layer OpenEXR files <-> Frames (OpenEXR 3.1's Imf::OutputFile / Imf::InputFile). See exr_io.h.
//
// Both directions describe the image to OpenEXR the same way: a Header lists the channels and their pixel
// types, and a FrameBuffer gives, per channel, a Slice: where its first pixel lives in memory and how far
// apart neighbouring pixels (x stride) and rows (y stride) are. Our planes are tightly packed rows, so the
// strides are sizeof(value) and width * sizeof(value).
#include "core/exr_io.h"

#include "core/atomic_file.h"
#include "core/error.h"
#include "core/exr_checks.h"
#include "core/memory_budget.h"
#include "core/regular_file.h"

#include <OpenEXR/ImfChannelList.h>
#include <OpenEXR/ImfFrameBuffer.h>
#include <OpenEXR/ImfHeader.h>
#include <OpenEXR/ImfInputFile.h>
#include <OpenEXR/ImfOutputFile.h>
#include <OpenEXR/ImfStdIO.h>
#include <OpenEXR/ImfStringAttribute.h>
#include <OpenEXR/ImfTestFile.h>
#include <OpenEXR/IexBaseExc.h>

#include <cassert>
#include <cerrno>
#include <cmath>
#include <cstring>
#include <fstream>

namespace rtdr {
namespace {

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

// OpenEXR's input stream over the std::istream of a RegularFile (core/regular_file.h): OpenEXR reads the very file
// that was checked to be regular, through its buffer. Like OpenEXR's own StdIFStream, a short read throws.
class CheckedInputStream : public Imf::IStream {
 public:
  CheckedInputStream(std::istream& in, const std::string& path) : Imf::IStream(path.c_str()), in_(in) {}
  bool read(char c[], int n) override {
    if (!in_.read(c, n))
      throw Iex::InputExc("early end of file: read " + std::to_string(in_.gcount()) + " of " + std::to_string(n) +
                          " bytes");
    return true;
  }
  uint64_t tellg() override { return uint64_t(in_.tellg()); }
  void seekg(uint64_t pos) override {
    in_.clear();
    if (!in_.seekg(std::streamoff(pos))) throw Iex::InputExc("cannot seek to byte " + std::to_string(pos));
  }
  void clear() override { in_.clear(); }

 private:
  std::istream& in_;
};

// Everything read_exr checks before OpenEXR opens the file: it is a flat (not deep) OpenEXR file, every header
// attribute declares the size OpenEXR reads for it, and its pixels fit in the file and in memory
// (core/exr_checks.h).
void require_readable_exr(const std::string& path, RegularFile& file, CheckedInputStream& stream) {
  bool tiled = false, deep = false, multi_part = false;
  if (!Imf::isOpenExrFile(stream, tiled, deep, multi_part))
    throw Error("cannot read EXR file '" + path + "': not an OpenEXR file");
  if (deep) throw Error("cannot read EXR file '" + path + "': deep images are not supported");
  require_consistent_header(path, file.stream(), file.size(), multi_part, memory_budget());
  stream.seekg(0);
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
  RegularFile file(path, "cannot read EXR file '" + path + "'");  // a FIFO or a folder is refused at once
  try {
    CheckedInputStream stream(file.stream(), path);
    require_readable_exr(path, file, stream);
    Imf::InputFile exr(stream);
    return read_pixels(path, exr);
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
