// Your engine's buffers as RTDR's planes and frames, to call a golden pass, or a whole method, from your own code
// (README.md, "Use it from your own project"; examples/shader_port_check/).
//
// A BufferView describes a buffer you own: row-major, row 0 at the top (as docs/buffers.md's frames), with any
// strides, so an interleaved RGBA texture read back with a padded row pitch is read in place. The functions copy
// the values they read into RTDR's planes, which own their values (std::vector); the view's buffer is not kept.
// A buffer already in RTDR's layout needs no copy at all: move it into a plane,
//   rtdr::FloatPlane depth;  depth.width = w;  depth.height = h;  depth.data = std::move(my_depth);
//
// Plumbing, not a pass: it implements no equation of the papers, and the planes it makes hold the values unchanged.
//
// Errors (a null buffer, a size below 1, strides that make pixels or rows overlap, strides whose span does not fit
// in a ptrdiff_t or wraps the address space, a channel count the plane cannot hold) throw rtdr::Error with a
// one-line message, as the rtdr command prints them. Every size is computed with overflow checks (a pixel_stride
// of 2^62 times a width of 4 would wrap to 0); RTDR cannot know how large your buffer is, only that the view's
// arithmetic is exact, so the view must describe memory you own.
#pragma once

#include "core/frame.h"
#include "filters/image.h"

#include <cstddef>
#include <string>
#include <vector>

namespace rtdr {

struct BufferView {
  const void* data = nullptr;       // the first value of pixel (0, 0)
  int width = 0, height = 0;
  int channels = 1;                 // values read per pixel, the first `channels` of each pixel
  std::ptrdiff_t pixel_stride = 0;  // bytes from a pixel to the next in its row; 0: `channels` values, packed
  std::ptrdiff_t row_stride = 0;    // bytes from a row to the next; 0: `width` pixels, packed
};

// The plane of a view of 32-bit floats (uint32 for uint_plane): channels must be 1, 2 and 3 respectively for
// float_plane and uint_plane, vec2_plane, rgb_plane (more channels per pixel are fine with a pixel_stride: an
// RGBA buffer read as rgb_plane with channels = 3 and pixel_stride = 16).
FloatPlane float_plane(const BufferView& view);
Vec2Plane vec2_plane(const BufferView& view);
RgbPlane rgb_plane(const BufferView& view);
UIntPlane uint_plane(const BufferView& view);

// Adds to `frame` one float channel per name, from the view's channels in order: add_float_channels(frame,
// {"normal.X", "normal.Y", "normal.Z"}, normals). The frame takes the view's size when it has none yet, and must
// have it otherwise. A whole method then runs on the frame: make_method("svgf")->filter(frame) (filters/method.h;
// the channels each method reads: docs/buffers.md, "Feeding your engine's frames").
void add_float_channels(Frame& frame, const std::vector<std::string>& names, const BufferView& view);
// The same for one uint channel (id.mesh, gradient.source), from a view of uint32 with channels = 1.
void add_uint_channel(Frame& frame, const std::string& name, const BufferView& view);

}  // namespace rtdr
