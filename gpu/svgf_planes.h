// The SVGF ports' planes on the GPU (layout: filters/svgf/planes_shared.h): buffers of whole records, and the
// packing of the golden code's planes into them and back. Packing copies values, except into fp16 illumination
// records (RGBA16F), which hold half_record_value of each colour component and of the standard deviation;
// unpacking gives back exactly what they hold, the variance as that standard deviation squared. An illumination
// buffer holds both streams, two records per pixel; its functions take the stream (kDirectStream or
// kIndirectStream).
#pragma once

#include "filters/image.h"
#include "filters/svgf/planes_shared.h"
#include "filters/surface_planes.h"
#include "gpu/compute.h"

#include <memory>

namespace rtdr {

// A buffer of width x height texels of `format`, viewable as a texel buffer.
std::unique_ptr<GpuBuffer> plane_buffer(VulkanContext& context, int width, int height, TexelFormat format);

// The format of the context's illumination records: RGBA32F, or RGBA16F for IlluminationRecords::Fp16.
TexelFormat illumination_format(const VulkanContext& context);
// A buffer of width x height pixels' illumination records in that format, two per pixel: the direct and the
// indirect stream's side by side.
std::unique_ptr<GpuBuffer> illumination_buffer(VulkanContext& context, int width, int height);
// The colour value an fp16 illumination record holds for v: v saturated at +-kHalfMax (core/shader_shared.h),
// rounded to the nearest half, ties to even; and the variance it holds for `variance` (>= 0): the square of
// half_record_value(sqrt(variance)). What an fp16 port reads where the golden pass reads v.
float half_record_value(float v);
float half_record_variance(float variance);

// Surface records (n.x, n.y, n.z, z), z = kNoSurfaceDepth where s has no surface.
void pack_surface(const SurfacePlanes& s, GpuBuffer& out);
// Colour records (r, g, b, 0) of floats. Throws rtdr::Error for an RGBA16F buffer.
void pack_rgb(const RgbPlane& rgb, GpuBuffer& out);
// Stream `stream`'s illumination records in an illumination buffer, in its format (illumination_format):
// (r, g, b, variance), or the fp16 records (r, g, b, sqrt(variance)); variance 0 where `variance` is null. The other
// stream's records are left as they are.
void pack_illumination(int stream, const RgbPlane& rgb, const FloatPlane* variance, GpuBuffer& out);
// Moments records (mu1, mu2, n, 0).
void pack_moments(const FloatPlane& moment1, const FloatPlane& moment2, const FloatPlane& length, GpuBuffer& out);
void pack_vec2(const Vec2Plane& plane, GpuBuffer& out);  // RG32F
void pack_ids(const UIntPlane& plane, GpuBuffer& out);   // R32UI, the same 32 bits

// Channel `channel` of a buffer of `components`-float records, as a width x height plane.
FloatPlane unpack_channel(const GpuBuffer& in, int width, int height, int components, int channel);
// Channels 0-2 of a buffer of 4-float records.
RgbPlane unpack_rgb(const GpuBuffer& in, int width, int height);
// Stream `stream`'s colours and variances in an illumination buffer, either format.
RgbPlane unpack_illumination(const GpuBuffer& in, int width, int height, int stream);
FloatPlane unpack_variance(const GpuBuffer& in, int width, int height, int stream);

}  // namespace rtdr
