// The Vulkan port of TRMV's shadow motion vector. See motion_shadow_gpu.h; the shader is motion/shadow.comp.
#include "gpu/motion_shadow_gpu.h"

#include "core/error.h"
#include "filters/image.h"
#include "gpu/motion_port.h"
#include "gpu/svgf_planes.h"
#include "motion/shadow_shared.h"

#include <cstdint>
#include <string>
#include <vector>

namespace rtdr {

// The pass's bindings fit the limits the context was chosen for (gpu/vulkan_context.h).
static_assert(kShadowMotionTexelBindings + kShadowMotionStorageBindings <= kStorageInputBindings &&
                  kShadowMotionTexelBindings <= kTexelInputBindings,
              "the shadow motion port's bindings fit every context");

std::vector<ShadowMotion> shadow_motion_vulkan(VulkanContext& context, const FrameGeometry& g, const Frame& frame,
                                               double* ms) {
  const ShadowRayLayers check(frame);  // throws rtdr::Error naming a missing channel, as shadow_motion does
  const int w = g.vis.width, h = g.vis.height;
  if (frame.width() != w || frame.height() != h)
    throw Error("shadow_motion: a " + std::to_string(frame.width()) + "x" + std::to_string(frame.height()) +
                " frame for a " + std::to_string(w) + "x" + std::to_string(h) + " geometry");
  if (w == 0 || h == 0) return {};

  // The per-pixel planes of ShadowRayLayers, as (x, y, z, 0) records and R32UI ids.
  const auto light = plane_buffer(context, w, h, TexelFormat::RGBA32F),
             blocker = plane_buffer(context, w, h, TexelFormat::RGBA32F),
             position = plane_buffer(context, w, h, TexelFormat::RGBA32F),
             geonormal = plane_buffer(context, w, h, TexelFormat::RGBA32F),
             light_id = plane_buffer(context, w, h, TexelFormat::R32UI),
             blocker_id = plane_buffer(context, w, h, TexelFormat::R32UI),
             receiver_id = plane_buffer(context, w, h, TexelFormat::R32UI);
  pack_rgb(xyz_plane(frame, "path.light"), *light);
  pack_rgb(xyz_plane(frame, "path.blocker"), *blocker);
  pack_rgb(xyz_plane(frame, "position"), *position);
  pack_rgb(xyz_plane(frame, "geonormal"), *geonormal);
  pack_ids(frame.uint_channel("path.light.instance"), *light_id);
  pack_ids(frame.uint_channel("path.blocker.instance"), *blocker_id);
  pack_ids(frame.uint_channel("id.instance"), *receiver_id);
  // T^{-1} per instance, computed once on the host by the golden instance_to_previous; the two Views.
  const std::vector<ShadowInstanceMotion> instances = to_previous_records(g);
  const auto instance_buffer = record_buffer(context, instances);
  const auto views = view_buffer(context, g);
  // (m^V, valid, 0) per pixel.
  const auto result = plane_buffer(context, w, h, TexelFormat::RGBA32F);

  const MotionPort port(context, "motion_shadow", kShadowMotionTexelBindings, kShadowMotionStorageBindings,
                        sizeof(ShadowMotionPush));
  const ShadowMotionPush push{
      .width = uint32_t(w), .height = uint32_t(h), .instance_count = uint32_t(instances.size()), .unused = 0u};
  port.run(context,
           {light.get(), blocker.get(), position.get(), geonormal.get(), light_id.get(), blocker_id.get(),
            receiver_id.get(), instance_buffer.get(), views.get(), result.get()},
           &push, w, h, ms);

  return unpack_records<ShadowMotion>(*result, w, h);
}

}  // namespace rtdr
