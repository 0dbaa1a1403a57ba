// The SVGF ports' planes on the GPU (layout: filters/svgf/planes_shared.h): buffers of whole records, and the
// packing of the golden code's planes into them and back. Packing copies values; it never converts one.
#pragma once

#include "filters/image.h"
#include "filters/svgf/svgf_shared.h"
#include "gpu/compute.h"

#include <memory>

namespace rtdr {

// A buffer of width x height texels of `format`, viewable as a texel buffer.
std::unique_ptr<GpuBuffer> plane_buffer(VulkanContext& context, int width, int height, TexelFormat format);

// Surface records (n.x, n.y, n.z, z), z = kNoSurfaceDepth where s has no surface.
void pack_surface(const SurfacePlanes& s, GpuBuffer& out);
// Records (r, g, b, w): w from `w` where given, else 0. Illumination (w = variance) and colour records.
void pack_rgbw(const RgbPlane& rgb, const FloatPlane* w, GpuBuffer& out);
// Moments records (mu1, mu2, n, 0).
void pack_moments(const FloatPlane& moment1, const FloatPlane& moment2, const FloatPlane& length, GpuBuffer& out);
void pack_vec2(const Vec2Plane& plane, GpuBuffer& out);  // RG32F
void pack_ids(const UIntPlane& plane, GpuBuffer& out);   // R32UI, the same 32 bits

// Channel `channel` of a buffer of `components`-float records, as a width x height plane.
FloatPlane unpack_channel(const GpuBuffer& in, int width, int height, int components, int channel);
// Channels 0-2 of a buffer of 4-float records.
RgbPlane unpack_rgb(const GpuBuffer& in, int width, int height);

}  // namespace rtdr
