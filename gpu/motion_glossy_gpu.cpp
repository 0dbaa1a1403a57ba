// The Vulkan port of TRMV's glossy motion vector. See motion_glossy_gpu.h; the shader is motion/glossy.comp.
#include "gpu/motion_glossy_gpu.h"

#include "core/error.h"
#include "filters/image.h"
#include "gpu/motion_port.h"
#include "gpu/svgf_planes.h"
#include "motion/glossy_shared.h"
#include "scenes/scene.h"

#include <cstdint>
#include <cstring>
#include <memory>
#include <numbers>
#include <string>

namespace rtdr {

static_assert(kGlossyPi == std::numbers::pi_v<float>, "the shader's pi is the golden pass's float");

std::vector<GlossyMotion> glossy_motion_vulkan(VulkanContext& context, const FrameGeometry& g, const Frame& frame,
                                               double* ms) {
  const GlossyRayLayers check(frame);  // throws rtdr::Error naming a missing channel, as glossy_motion does
  const int w = g.vis.width, h = g.vis.height;
  if (frame.width() != w || frame.height() != h)  // motion_per_pixel's check, with its message
    throw Error("glossy_motion: a " + std::to_string(frame.width()) + "x" + std::to_string(frame.height()) +
                " frame for a " + std::to_string(w) + "x" + std::to_string(h) + " geometry");
  if (w == 0 || h == 0) return {};

  // GlossyRayLayers' planes: (s_i, roughness), n(s_i) and h_i as (x, y, z, w) records, the ids and the seed.
  RgbPlane position = xyz_plane(frame, "position");
  const auto reflector = plane_buffer(context, w, h, TexelFormat::RGBA32F),
             normal = plane_buffer(context, w, h, TexelFormat::RGBA32F),
             hit = plane_buffer(context, w, h, TexelFormat::RGBA32F),
             reflector_id = plane_buffer(context, w, h, TexelFormat::R32UI),
             hit_id = plane_buffer(context, w, h, TexelFormat::R32UI),
             seed = plane_buffer(context, w, h, TexelFormat::R32UI);
  pack_rgb(position, *reflector);
  const FloatPlane& roughness = frame.float_channel("material.roughness");
  for (size_t i = 0; i < roughness.data.size(); ++i) reflector->data()[4 * i + 3] = roughness.data[i];
  pack_rgb(xyz_plane(frame, "geonormal"), *normal);
  pack_rgb(xyz_plane(frame, "path.secondary"), *hit);
  pack_ids(frame.uint_channel("id.instance"), *reflector_id);
  pack_ids(frame.uint_channel("path.secondary.instance"), *hit_id);
  pack_ids(frame.uint_channel("rng.seed"), *seed);
  // T^{-1} per instance, computed once on the host by the golden instance_to_previous; the two Views.
  const std::vector<ShadowInstanceMotion> instances = to_previous_records(g);
  const auto instance_buffer = record_buffer(context, instances);
  const auto views = view_buffer(context, g);
  // One GlossyMotionRecord per pixel.
  const auto result = std::make_unique<GpuBuffer>(context, size_t(w) * size_t(h) * (sizeof(GlossyMotionRecord) / 4));

  const MotionPort port(context, "motion_glossy", kGlossyMotionTexelBindings, kGlossyMotionStorageBindings,
                        sizeof(GlossyMotionPush));
  const GlossyMotionPush push{.eye = glm::vec4(g.view.eye, 0.0f),
                              .prev_eye = glm::vec4(g.prev_view.eye, 0.0f),
                              .width = uint32_t(w),
                              .height = uint32_t(h),
                              .instance_count = uint32_t(instances.size()),
                              .min_ggx_alpha = kMinGgxAlpha};
  port.run(context,
           {reflector.get(), normal.get(), hit.get(), reflector_id.get(), hit_id.get(), seed.get(),
            instance_buffer.get(), views.get(), result.get()},
           &push, w, h, ms);

  std::vector<GlossyMotionRecord> records(size_t(w) * size_t(h));
  std::memcpy(records.data(), result->data(), records.size() * sizeof(GlossyMotionRecord));
  std::vector<GlossyMotion> out(records.size());
  for (size_t i = 0; i < records.size(); ++i) {
    const GlossyMotionRecord& r = records[i];
    GlossyMotion& m = out[i];
    if (r.has_footprint != 0u) {  // the current footprint, as glossy_motion_pixel makes it
      m.footprint_axes = glm::mat2(r.b1, r.b2);
      m.footprint = m.footprint_axes * glm::transpose(m.footprint_axes);
      m.has_footprint = true;
    }
    if (r.valid == 0u) continue;  // (0, 0), not valid, as glossy_motion_pixel leaves it
    m.mu = r.mu, m.motion = r.motion, m.valid = true;
    m.axes = glm::mat2(r.a1, r.a2);
    m.Sigma = m.axes * glm::transpose(m.axes);  // a1 a1^T + a2 a2^T, as glossy_motion_pixel
  }
  return out;
}

}  // namespace rtdr
