// The Vulkan ports of TRMV's shadow motion vector and its splat. See motion_shadow_gpu.h; the shaders are
// motion/shadow.comp and motion/shadow_splat.comp.
#include "gpu/motion_shadow_gpu.h"

#include "core/error.h"
#include "filters/image.h"
#include "gpu/compute.h"
#include "gpu/svgf_planes.h"
#include "gpu/svgf_shaders.h"
#include "motion/shadow_shared.h"
#include "motion/shadow_splat_shared.h"
#include "raster/view_shared.h"

#include <algorithm>
#include <cstdint>
#include <cstring>
#include <memory>
#include <string>
#include <vector>

namespace rtdr {

namespace {

// Both passes' bindings fit the limits the context was chosen for (gpu/vulkan_context.h).
static_assert(kShadowMotionTexelBindings + kShadowMotionStorageBindings <= kStorageInputBindings &&
                  kShadowMotionTexelBindings <= kTexelInputBindings,
              "the shadow motion port's bindings fit every context");
static_assert(kShadowSplatTexelBindings + kShadowSplatStorageBindings <= kStorageInputBindings &&
                  kShadowSplatTexelBindings <= kTexelInputBindings,
              "the splat port's bindings fit every context");

// One pass's pipeline with the SVGF ports' workgroup shape on this device (filters/svgf/planes_shared.h), passed as
// specialization constants 0 and 1, and its dispatch over a width x height frame, timed.
class MotionPort {
 public:
  MotionPort(VulkanContext& context, const char* stem, uint32_t texel, uint32_t storage, uint32_t push_bytes)
      : group_width_(context.cpu_device() ? kSvgfCpuGroupSizeX : kSvgfGroupSizeX),
        group_height_(context.cpu_device() ? kSvgfCpuGroupSizeY : kSvgfGroupSizeY),
        stem_(stem),
        pipeline_(context, load_port(context, stem), port_bindings(context, texel, storage), push_bytes,
                  {int32_t(group_width_), int32_t(group_height_)}) {
    static_assert(kSvgfGroupSizeXConstant == 0 && kSvgfGroupSizeYConstant == 1, "constant_id 0, 1 in order");
  }

  // Runs the pass once over width x height pixels and waits; *ms receives its device time.
  void run(VulkanContext& context, const std::vector<const GpuBuffer*>& buffers, const void* push, int width,
           int height, double* ms) const {
    ComputeBatch batch(context, 1);
    batch.dispatch(pipeline_, buffers, push, group_count(uint32_t(width), group_width_),
                   group_count(uint32_t(height), group_height_), stem_);
    batch.run();
    batch.total_time(ms);
  }

 private:
  uint32_t group_width_, group_height_;
  std::string stem_;
  ComputePipeline pipeline_;
};

// An instance's T^{-1} as its record (motion/shadow_shared.h): the mat4's columns, then the mat3's with w = 0.
ShadowInstanceMotion instance_record(const InstanceMotion& m) {
  ShadowInstanceMotion r{};
  for (int c = 0; c < 4; ++c) r.to_previous[c] = m.to_previous[c];
  for (int c = 0; c < 3; ++c) r.normal_to_previous[c] = glm::vec4(m.normal_to_previous[c], 0.0f);
  return r;
}

// A buffer holding `records` (at least one record's room: a GpuBuffer is never empty), uploaded.
template <class Record>
std::unique_ptr<GpuBuffer> record_buffer(VulkanContext& context, const std::vector<Record>& records) {
  static_assert(sizeof(Record) % sizeof(float) == 0, "records of whole floats");
  constexpr size_t floats = sizeof(Record) / sizeof(float);
  auto buffer = std::make_unique<GpuBuffer>(context, floats * std::max<size_t>(records.size(), 1));
  std::vector<float> values(buffer->floats(), 0.0f);
  if (!records.empty()) std::memcpy(values.data(), records.data(), records.size() * sizeof(Record));
  buffer->upload(values);
  return buffer;
}

// A pass's output, (motion.x, motion.y, flag 0 or 1, 0) records, as the golden pass's results.
template <class Result>
std::vector<Result> unpack_records(const GpuBuffer& records, int width, int height) {
  const FloatPlane x = unpack_channel(records, width, height, 4, 0), y = unpack_channel(records, width, height, 4, 1),
                   flag = unpack_channel(records, width, height, 4, 2);
  std::vector<Result> out(x.data.size());
  for (size_t i = 0; i < out.size(); ++i) out[i] = {glm::vec2(x.data[i], y.data[i]), flag.data[i] != 0.0f};
  return out;
}

}  // namespace

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
  std::vector<ShadowInstanceMotion> instances;
  for (const InstanceMotion& m : instance_to_previous(g.pose, g.prev_pose)) instances.push_back(instance_record(m));
  const auto instance_buffer = record_buffer(context, instances);
  const auto views = record_buffer(context, std::vector<ViewRecord>{view_record(g.view), view_record(g.prev_view)});
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

std::vector<SplatMotion> splat_shadow_motion_vulkan(VulkanContext& context, const std::vector<ShadowMotion>& shadow,
                                                    const std::vector<glm::vec2>& surface_motion,
                                                    const std::vector<float>& depth, int width, int height, int size,
                                                    double* ms) {
  // splat_shadow_motion's checks, with its messages.
  const size_t pixels = size_t(width) * size_t(height);
  if (shadow.size() != pixels || surface_motion.size() != pixels || depth.size() != pixels)
    throw Error("splat_shadow_motion: planes of " + std::to_string(shadow.size()) + ", " +
                std::to_string(surface_motion.size()) + " and " + std::to_string(depth.size()) + " pixels for " +
                std::to_string(width) + "x" + std::to_string(height));
  if (size < 1 || size % 2 == 0)
    throw Error("splat_shadow_motion: the window's side must be odd and at least 1, not " + std::to_string(size));
  if (pixels == 0) return {};

  // (m^V, valid) and (surface motion, depth) as (x, y, z, 0) records.
  RgbPlane shadow_records(width, height), surface_records(width, height);
  for (size_t i = 0; i < pixels; ++i) {
    shadow_records.data[i] = glm::vec3(shadow[i].motion, shadow[i].valid ? 1.0f : 0.0f);
    surface_records.data[i] = glm::vec3(surface_motion[i], depth[i]);
  }
  const auto shadow_buffer = plane_buffer(context, width, height, TexelFormat::RGBA32F),
             surface_buffer = plane_buffer(context, width, height, TexelFormat::RGBA32F),
             result = plane_buffer(context, width, height, TexelFormat::RGBA32F);
  pack_rgb(shadow_records, *shadow_buffer);
  pack_rgb(surface_records, *surface_buffer);

  const MotionPort port(context, "motion_shadow_splat", kShadowSplatTexelBindings, kShadowSplatStorageBindings,
                        sizeof(ShadowSplatPush));
  const ShadowSplatPush push{.width = uint32_t(width), .height = uint32_t(height), .size = size, .unused = 0u};
  port.run(context, {shadow_buffer.get(), surface_buffer.get(), result.get()}, &push, width, height, ms);

  return unpack_records<SplatMotion>(*result, width, height);
}

}  // namespace rtdr
