// The render side's motion ports' shared host code (gpu/motion_shadow_gpu.cpp, gpu/motion_dual_gpu.cpp,
// gpu/motion_glossy_gpu.cpp): a pass's pipeline and its timed dispatch, the upload of a std430 array of records,
// the records of each instance's T^{-1} and of the two Views, and the readback of (motion, flag) records.
//
// MotionPort
//   in:  the shader's stem (motion/<stem>.comp: motion_<stem>), its texel and storage bindings, its push bytes
//   out: a pipeline with the SVGF ports' workgroup shape on this device (filters/svgf/planes_shared.h) as
//        specialization constants 0 and 1; run() dispatches it over a frame and writes its device time
#pragma once

#include "gpu/compute.h"
#include "gpu/svgf_planes.h"
#include "gpu/vulkan_context.h"
#include "motion/shadow_shared.h"
#include "raster/gbuffer_frame.h"

#include <glm/glm.hpp>

#include <algorithm>
#include <cstdint>
#include <cstring>
#include <memory>
#include <string>
#include <vector>

namespace rtdr {

// One pass's pipeline and its dispatch over a width x height frame, timed.
class MotionPort {
 public:
  MotionPort(VulkanContext& context, const char* stem, uint32_t texel, uint32_t storage, uint32_t push_bytes);

  // Runs the pass once over width x height pixels and waits; *ms receives its device time
  // (see ComputeBatch::total_time).
  void run(VulkanContext& context, const std::vector<const GpuBuffer*>& buffers, const void* push, int width,
           int height, double* ms) const;

 private:
  uint32_t group_width_, group_height_;
  std::string stem_;
  ComputePipeline pipeline_;
};

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

// T^{-1} per instance, computed once on the host by the golden instance_to_previous (motion/shadow.h), as
// records (motion/shadow_shared.h): each the mat4's columns, then the mat3's with w = 0.
std::vector<ShadowInstanceMotion> to_previous_records(const FrameGeometry& geometry);

// The geometry's two Views, this frame's then the previous one's, as ViewRecords (raster/view_shared.h), uploaded.
std::unique_ptr<GpuBuffer> view_buffer(VulkanContext& context, const FrameGeometry& geometry);

// A pass's output, (motion.x, motion.y, flag 0 or 1, 0) records, as the golden pass's results
// (ShadowMotion, SplatMotion, DualMotion: a vec2, then a bool).
template <class Result>
std::vector<Result> unpack_records(const GpuBuffer& records, int width, int height) {
  const FloatPlane x = unpack_channel(records, width, height, 4, 0), y = unpack_channel(records, width, height, 4, 1),
                   flag = unpack_channel(records, width, height, 4, 2);
  std::vector<Result> out(x.data.size());
  for (size_t i = 0; i < out.size(); ++i) out[i] = {glm::vec2(x.data[i], y.data[i]), flag.data[i] != 0.0f};
  return out;
}

}  // namespace rtdr
