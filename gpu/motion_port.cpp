// The render side's motion ports' shared host code. See motion_port.h.
#include "gpu/motion_port.h"

#include "gpu/svgf_shaders.h"
#include "motion/shadow.h"
#include "raster/view_shared.h"

namespace rtdr {

MotionPort::MotionPort(VulkanContext& context, const char* stem, uint32_t texel, uint32_t storage,
                       uint32_t push_bytes)
    : group_width_(context.cpu_device() ? kSvgfCpuGroupSizeX : kSvgfGroupSizeX),
      group_height_(context.cpu_device() ? kSvgfCpuGroupSizeY : kSvgfGroupSizeY),
      stem_(stem),
      pipeline_(context, load_port(context, stem), port_bindings(context, texel, storage), push_bytes,
                {int32_t(group_width_), int32_t(group_height_)}) {
  static_assert(kSvgfGroupSizeXConstant == 0 && kSvgfGroupSizeYConstant == 1, "constant_id 0, 1 in order");
}

void MotionPort::run(VulkanContext& context, const std::vector<const GpuBuffer*>& buffers, const void* push,
                     int width, int height, double* ms) const {
  ComputeBatch batch(context, 1);
  batch.dispatch(pipeline_, buffers, push, group_count(uint32_t(width), group_width_),
                 group_count(uint32_t(height), group_height_), stem_);
  batch.run();
  batch.total_time(ms);
}

std::vector<ShadowInstanceMotion> to_previous_records(const FrameGeometry& g) {
  std::vector<ShadowInstanceMotion> records;
  for (const InstanceMotion& m : instance_to_previous(g.pose, g.prev_pose)) {
    ShadowInstanceMotion r{};
    for (int c = 0; c < 4; ++c) r.to_previous[c] = m.to_previous[c];
    for (int c = 0; c < 3; ++c) r.normal_to_previous[c] = glm::vec4(m.normal_to_previous[c], 0.0f);
    records.push_back(r);
  }
  return records;
}

std::unique_ptr<GpuBuffer> view_buffer(VulkanContext& context, const FrameGeometry& g) {
  return record_buffer(context, std::vector<ViewRecord>{view_record(g.view), view_record(g.prev_view)});
}

}  // namespace rtdr
