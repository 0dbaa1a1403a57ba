// Packing planes into the SVGF ports' GPU layout and back. See svgf_planes.h.
#include "gpu/svgf_planes.h"

#include "core/error.h"
#include "filters/svgf/planes_shared.h"

#include <Imath/half.h>

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstring>
#include <string>

namespace rtdr {

namespace {

bool is_half(const GpuBuffer& buffer) { return buffer.format() == TexelFormat::RGBA16F; }

// The buffer holds exactly `records` records of `values` values: floats, or halves in an RGBA16F buffer (two to a
// 32-bit word). An empty plane fits the one texel plane_buffer gives it.
void check_fits(const GpuBuffer& buffer, size_t records, size_t values, const char* what) {
  const size_t words = is_half(buffer) ? records * values / 2 : records * values;
  const bool empty_fits = records == 0 && buffer.floats() == texel_floats(buffer.format());
  if ((is_half(buffer) && values != 4) || (buffer.floats() != words && !empty_fits))
    throw Error(std::string(what) + ": a buffer of " + std::to_string(buffer.floats()) + " words cannot hold " +
                std::to_string(records) + " records of " + std::to_string(values) + (is_half(buffer) ? " halves" : ""));
}

// Where stream `stream`'s record sits in a pixel's illumination pair (planes_shared.h): pixel i's is record
// 2i + stream_offset.
size_t stream_offset(int stream, const char* what) {
  if (stream != kDirectStream && stream != kIndirectStream)
    throw Error(std::string(what) + ": stream must be kDirectStream (0) or kIndirectStream (1), got " +
                std::to_string(stream));
  return size_t(stream);
}

// The half an fp16 record stores for v: v saturated at +-kHalfMax, as RTDR_OUTPUT_RGBA16F_PAIR does, then rounded to
// the nearest half, ties to even (Imath).
Imath::half to_half(float v) { return Imath::half(std::clamp(v, -kHalfMax, kHalfMax)); }
uint16_t half_bits(float v) { return to_half(v).bits(); }

// The four values (a, b, c, d) as one RGBA16F texel, in packHalf2x16's layout: two 32-bit words, each holding its
// first value in the low 16 bits.
void store_halves(float* texel, float a, float b, float c, float d) {
  const uint32_t words[2] = {uint32_t(half_bits(a)) | uint32_t(half_bits(b)) << 16,
                             uint32_t(half_bits(c)) | uint32_t(half_bits(d)) << 16};
  std::memcpy(texel, words, sizeof(words));
}

// The four values (a, b, c, d) as one RGBA32F texel.
void store_floats(float* texel, float a, float b, float c, float d) {
  texel[0] = a;
  texel[1] = b;
  texel[2] = c;
  texel[3] = d;
}

// Value `value` of record i in a buffer of records of `values` values, widened to float where it is a half.
float record_value(const GpuBuffer& buffer, size_t values, size_t i, size_t value) {
  if (!is_half(buffer)) return buffer.data()[values * i + value];
  uint32_t word;
  std::memcpy(&word, buffer.data() + (values * i + value) / 2, sizeof(word));
  return float(Imath::half(Imath::half::FromBits, uint16_t(value % 2 ? word >> 16 : word & 0xFFFFu)));
}

// Values 0-2 of record i in a buffer of 4-value records.
glm::vec3 record_rgb(const GpuBuffer& buffer, size_t i) {
  return glm::vec3(record_value(buffer, 4, i, 0), record_value(buffer, 4, i, 1), record_value(buffer, 4, i, 2));
}

}  // namespace

float half_record_value(float v) { return float(to_half(v)); }

float half_record_variance(float variance) {
  const float sigma = half_record_value(std::sqrt(variance));
  return sigma * sigma;
}

TexelFormat illumination_format(const VulkanContext& context) {
  return context.illumination_records() == IlluminationRecords::Fp16 ? TexelFormat::RGBA16F : TexelFormat::RGBA32F;
}

std::unique_ptr<GpuBuffer> illumination_buffer(VulkanContext& context, int width, int height) {
  // Two records per pixel, side by side: a plane of records twice as wide.
  return plane_buffer(context, 2 * width, height, illumination_format(context));
}

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

void pack_rgb(const RgbPlane& rgb, GpuBuffer& out) {
  const size_t pixels = rgb.data.size();
  if (is_half(out)) throw Error("pack_rgb: colour records are never halves (pack_illumination packs those)");
  check_fits(out, pixels, 4, "pack_rgb");
  for (size_t i = 0; i < pixels; ++i) store_floats(out.data() + 4 * i, rgb.data[i].r, rgb.data[i].g, rgb.data[i].b, 0);
}

void pack_illumination(int stream, const RgbPlane& rgb, const FloatPlane* variance, GpuBuffer& out) {
  const size_t offset = stream_offset(stream, "pack_illumination"), pixels = rgb.data.size();
  check_fits(out, 2 * pixels, 4, "pack_illumination");
  for (size_t i = 0; i < pixels; ++i) {
    const size_t record = 2 * i + offset;
    const glm::vec3 c = rgb.data[i];
    const float v = variance ? variance->data[i] : 0.0f;
    if (is_half(out))
      store_halves(out.data() + 2 * record, c.r, c.g, c.b, std::sqrt(v));  // the standard deviation (planes_shared.h)
    else
      store_floats(out.data() + 4 * record, c.r, c.g, c.b, v);
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
  for (size_t i = 0; i < plane.data.size(); ++i) plane.data[i] = record_value(in, components, i, size_t(channel));
  return plane;
}

RgbPlane unpack_rgb(const GpuBuffer& in, int width, int height) {
  RgbPlane plane(width, height);
  check_fits(in, plane.data.size(), 4, "unpack_rgb");
  for (size_t i = 0; i < plane.data.size(); ++i) plane.data[i] = record_rgb(in, i);
  return plane;
}

RgbPlane unpack_illumination(const GpuBuffer& in, int width, int height, int stream) {
  const size_t offset = stream_offset(stream, "unpack_illumination");
  RgbPlane plane(width, height);
  check_fits(in, 2 * plane.data.size(), 4, "unpack_illumination");
  for (size_t i = 0; i < plane.data.size(); ++i) plane.data[i] = record_rgb(in, 2 * i + offset);
  return plane;
}

FloatPlane unpack_variance(const GpuBuffer& in, int width, int height, int stream) {
  const size_t offset = stream_offset(stream, "unpack_variance");
  FloatPlane plane(width, height);
  check_fits(in, 2 * plane.data.size(), 4, "unpack_variance");
  for (size_t i = 0; i < plane.data.size(); ++i) {
    const float v = record_value(in, 4, 2 * i + offset, 3);
    plane.data[i] = is_half(in) ? v * v : v;  // a half record holds the standard deviation (planes_shared.h)
  }
  return plane;
}

}  // namespace rtdr
