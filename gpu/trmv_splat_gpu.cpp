// The Vulkan port of TRMV's splat. See trmv_splat_gpu.h; the shader is filters/trmv/splat.comp.
#include "gpu/trmv_splat_gpu.h"

#include "gpu/svgf_planes.h"
#include "gpu/svgf_shaders.h"
#include "gpu/trmv_shaders.h"

namespace rtdr {

void pack_trmv_splat(const TrmvSplatPlanes& in, GpuBuffer& shadow, GpuBuffer& surface_motion, GpuBuffer& normal) {
  const size_t pixels = in.shadow.data.size();
  float* s = shadow.data();
  float* m = surface_motion.data();
  for (size_t i = 0; i < pixels; ++i) {
    // (m^V, valid, carried) and (m, 0, 0).
    s[4 * i] = in.shadow.data[i].x, s[4 * i + 1] = in.shadow.data[i].y;
    s[4 * i + 2] = in.valid.data[i] != 0 ? 1.0f : 0.0f;
    s[4 * i + 3] = in.carried.width != 0 ? in.carried.data[i] : 0.0f;
    m[4 * i] = in.surface_motion.data[i].x, m[4 * i + 1] = in.surface_motion.data[i].y;
    m[4 * i + 2] = m[4 * i + 3] = 0.0f;
  }
  pack_rgb(in.normal, normal);
}

TrmvSplatOutput trmv_splat_vulkan(VulkanContext& context, const TrmvSplatPlanes& in, int size, double* ms) {
  check_trmv_splat_inputs(in, size);  // trmv_splat_pass's checks
  const int w = in.shadow.width, h = in.shadow.height;
  TrmvSplatOutput out{Vec2Plane(w, h), UIntPlane(w, h), FloatPlane(w, h)};
  if (out.motion.data.empty()) return out;

  const auto shadow = plane_buffer(context, w, h, TexelFormat::RGBA32F),
             surface_motion = plane_buffer(context, w, h, TexelFormat::RGBA32F),
             instance = plane_buffer(context, w, h, TexelFormat::R32UI),
             normal = plane_buffer(context, w, h, TexelFormat::RGBA32F),
             result = plane_buffer(context, w, h, TexelFormat::RGBA32F);
  pack_trmv_splat(in, *shadow, *surface_motion, *normal);
  pack_ids(in.instance, *instance);

  const TrmvSplatPush push{.width = uint32_t(w), .height = uint32_t(h), .size = size, .unused = 0u};
  run_pass<TrmvShaders>(
      context,
      [&](const TrmvShaders& shaders, ComputeBatch& batch) {
        shaders.splat(batch, {shadow.get(), surface_motion.get(), instance.get(), normal.get()}, *result, push);
      },
      ms);

  const FloatPlane x = unpack_channel(*result, w, h, 4, 0), y = unpack_channel(*result, w, h, 4, 1),
                   landed = unpack_channel(*result, w, h, 4, 2);
  out.carried = unpack_channel(*result, w, h, 4, 3);
  for (size_t i = 0; i < out.motion.data.size(); ++i) {
    out.motion.data[i] = {x.data[i], y.data[i]};
    out.landed.data[i] = landed.data[i] != 0.0f ? 1u : 0u;
  }
  return out;
}

}  // namespace rtdr
