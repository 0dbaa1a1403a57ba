// Packing planes into the SVGF ports' GPU layout and back. See svgf_planes.h.
#include "gpu/svgf_planes.h"

#include "core/error.h"
#include "filters/svgf/planes_shared.h"

#include <bit>
#include <string>

namespace rtdr {

namespace {

// The buffer holds exactly `pixels` records of `floats` floats.
void check_fits(const GpuBuffer& buffer, size_t pixels, size_t floats, const char* what) {
  if (buffer.floats() != pixels * floats && !(pixels == 0 && buffer.floats() == 1))
    throw Error(std::string(what) + ": a buffer of " + std::to_string(buffer.floats()) + " floats cannot hold " +
                std::to_string(pixels) + " records of " + std::to_string(floats));
}

}  // namespace

std::unique_ptr<GpuBuffer> plane_buffer(VulkanContext& context, int width, int height, TexelFormat format) {
  // An empty plane still gets one texel: a binding needs a buffer, and the shaders never read it.
  const size_t pixels = std::max<size_t>(1, size_t(width) * size_t(height));
  return std::make_unique<GpuBuffer>(context, pixels * texel_floats(format), format);
}

void pack_surface(const SurfacePlanes& s, GpuBuffer& out) {
  const size_t pixels = s.depth.data.size();
  check_fits(out, pixels, 4, "pack_surface");
  float* d = out.data();
  for (size_t i = 0; i < pixels; ++i) {
    const glm::vec3 n = s.normal.data[i];
    d[4 * i] = n.x;
    d[4 * i + 1] = n.y;
    d[4 * i + 2] = n.z;
    d[4 * i + 3] = s.mesh.data[i] != kInvalidId ? s.depth.data[i] : kNoSurfaceDepth;
  }
}

void pack_rgbw(const RgbPlane& rgb, const FloatPlane* w, GpuBuffer& out) {
  const size_t pixels = rgb.data.size();
  check_fits(out, pixels, 4, "pack_rgbw");
  float* d = out.data();
  for (size_t i = 0; i < pixels; ++i) {
    d[4 * i] = rgb.data[i].r;
    d[4 * i + 1] = rgb.data[i].g;
    d[4 * i + 2] = rgb.data[i].b;
    d[4 * i + 3] = w ? w->data[i] : 0.0f;
  }
}

void pack_moments(const FloatPlane& moment1, const FloatPlane& moment2, const FloatPlane& length, GpuBuffer& out) {
  const size_t pixels = moment1.data.size();
  check_fits(out, pixels, 4, "pack_moments");
  float* d = out.data();
  for (size_t i = 0; i < pixels; ++i) {
    d[4 * i] = moment1.data[i];
    d[4 * i + 1] = moment2.data[i];
    d[4 * i + 2] = length.data[i];
    d[4 * i + 3] = 0.0f;
  }
}

void pack_vec2(const Vec2Plane& plane, GpuBuffer& out) {
  const size_t pixels = plane.data.size();
  check_fits(out, pixels, 2, "pack_vec2");
  float* d = out.data();
  for (size_t i = 0; i < pixels; ++i) {
    d[2 * i] = plane.data[i].x;
    d[2 * i + 1] = plane.data[i].y;
  }
}

void pack_ids(const UIntPlane& plane, GpuBuffer& out) {
  const size_t pixels = plane.data.size();
  check_fits(out, pixels, 1, "pack_ids");
  float* d = out.data();
  for (size_t i = 0; i < pixels; ++i) d[i] = std::bit_cast<float>(uint32_t(plane.data[i]));
}

FloatPlane unpack_channel(const GpuBuffer& in, int width, int height, int components, int channel) {
  FloatPlane plane(width, height);
  check_fits(in, plane.data.size(), size_t(components), "unpack_channel");
  const float* d = in.data();
  for (size_t i = 0; i < plane.data.size(); ++i) plane.data[i] = d[size_t(components) * i + size_t(channel)];
  return plane;
}

RgbPlane unpack_rgb(const GpuBuffer& in, int width, int height) {
  RgbPlane plane(width, height);
  check_fits(in, plane.data.size(), 4, "unpack_rgb");
  const float* d = in.data();
  for (size_t i = 0; i < plane.data.size(); ++i) plane.data[i] = glm::vec3(d[4 * i], d[4 * i + 1], d[4 * i + 2]);
  return plane;
}

}  // namespace rtdr
