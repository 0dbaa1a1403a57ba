// The SVGF ports' planes on the GPU (layout: filters/svgf/planes_shared.h): buffers of whole records, and the
// packing of the golden code's planes into them and back. Packing copies values, except into fp16 illumination
// records (RGBA16F), which hold half_record_value of each colour component and of the standard deviation;
// unpacking gives back exactly what they hold, the variance as that standard deviation squared.
#pragma once

#include "filters/image.h"
#include "filters/svgf/svgf_shared.h"
#include "gpu/compute.h"

#include <memory>

namespace rtdr {

// A buffer of width x height texels of `format`, viewable as a texel buffer.
std::unique_ptr<GpuBuffer> plane_buffer(VulkanContext& context, int width, int height, TexelFormat format);

// The format of the context's illumination records: RGBA32F, or RGBA16F for IlluminationRecords::Fp16.
TexelFormat illumination_format(const VulkanContext& context);
// A buffer of width x height illumination records in that format.
std::unique_ptr<GpuBuffer> illumination_buffer(VulkanContext& context, int width, int height);
// The colour value an fp16 illumination record holds for v: v saturated at +-kHalfMax (core/shader_shared.h),
// rounded to the nearest half, ties to even; and the variance it holds for `variance` (>= 0): the square of
// half_record_value(sqrt(variance)). What an fp16 port reads where the golden pass reads v.
float half_record_value(float v);
float half_record_variance(float variance);

// Surface records (n.x, n.y, n.z, z), z = kNoSurfaceDepth where s has no surface.
void pack_surface(const SurfacePlanes& s, GpuBuffer& out);
// Records (r, g, b, w) of floats: w from `w` where given, else 0. Colour records (and fp32 illumination records).
// Throws rtdr::Error for an RGBA16F buffer.
void pack_rgbw(const RgbPlane& rgb, const FloatPlane* w, GpuBuffer& out);
// Illumination records in the buffer's format (illumination_format): (r, g, b, variance) as pack_rgbw, or the
// fp16 records (r, g, b, sqrt(variance)); variance 0 where `variance` is null.
void pack_illumination(const RgbPlane& rgb, const FloatPlane* variance, GpuBuffer& out);
// Moments records (mu1, mu2, n, 0).
void pack_moments(const FloatPlane& moment1, const FloatPlane& moment2, const FloatPlane& length, GpuBuffer& out);
void pack_vec2(const Vec2Plane& plane, GpuBuffer& out);  // RG32F
void pack_ids(const UIntPlane& plane, GpuBuffer& out);   // R32UI, the same 32 bits

// Channel `channel` of a buffer of `components`-float records (or of RGBA16F records, components 4), as a
// width x height plane.
FloatPlane unpack_channel(const GpuBuffer& in, int width, int height, int components, int channel);
// The variances of a buffer of illumination records, either format.
FloatPlane unpack_variance(const GpuBuffer& in, int width, int height);
// Channels 0-2 of a buffer of 4-float (or RGBA16F) records.
RgbPlane unpack_rgb(const GpuBuffer& in, int width, int height);

}  // namespace rtdr
