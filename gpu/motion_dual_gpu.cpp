// The Vulkan port of TRMV's dual motion vector. See motion_dual_gpu.h; the shader is motion/dual.comp.
#include "gpu/motion_dual_gpu.h"

#include "core/error.h"
#include "core/parallel.h"
#include "gpu/motion_port.h"
#include "gpu/svgf_planes.h"
#include "motion/dual_shared.h"

#include <cstdint>
#include <cstring>
#include <string>

namespace rtdr {

namespace {

// glslc folds the shader's 1 - kForwardProjectionDepthTolerance in double and rounds it once to a float
// (motion/dual.comp: 0.99000001 in the SPIR-V); the golden pass rounds the float difference. The same float, so the
// depth test is the golden one.
static_assert(float(1.0 - double(kForwardProjectionDepthTolerance)) == 1.0f - kForwardProjectionDepthTolerance,
              "the shader's 1 - tolerance is the golden pass's float");

// Each visibility-buffer sample's object-space point (object_point, the golden helper), as (x, y, z, w) records
// in `out` (a plane_buffer of RGBA32F): w is the sample's depth (0 without a surface) where `with_depth`, else 0.
// A pixel without a surface gets (0, 0, 0, w); the shader reads its instance id first.
void pack_object_points(const Scene& scene, const VisibilityBuffer& vis, bool with_depth, GpuBuffer& out) {
  float* records = out.data();
  parallel_rows(vis.height, [&](int y) {
    for (int x = 0; x < vis.width; ++x) {
      const size_t i = vis.index(x, y);
      const SurfaceSample s = vis.sample(x, y);
      const glm::vec3 p = s.valid() ? object_point(scene, s) : glm::vec3(0.0f);
      const float w = with_depth ? vis.depth[i] : 0.0f;
      std::memcpy(records + 4 * i, &p[0], 3 * sizeof(float));
      records[4 * i + 3] = w;
    }
  });
}

// A visibility buffer's instance ids as R32UI texels.
void pack_instances(const VisibilityBuffer& vis, GpuBuffer& out) {
  std::memcpy(out.data(), vis.instance.data(), vis.instance.size() * sizeof(uint32_t));
}

// Each instance's instance_to_world at both poses, as columns.
std::vector<DualInstance> instance_records(const ScenePose& pose, const ScenePose& prev_pose) {
  std::vector<DualInstance> records(pose.instance_to_world.size());
  for (size_t k = 0; k < records.size(); ++k)
    for (int c = 0; c < 4; ++c) {
      records[k].to_world[c] = pose.instance_to_world[k][c];
      records[k].prev_to_world[c] = prev_pose.instance_to_world[k][c];
    }
  return records;
}

}  // namespace

std::vector<DualMotion> dual_motion_vulkan(VulkanContext& context, const Scene& scene, const FrameGeometry& g,
                                           const std::vector<glm::vec2>& surface_motion, double* ms) {
  const int w = g.vis.width, h = g.vis.height;
  const size_t pixels = size_t(w) * size_t(h);
  if (surface_motion.size() != pixels)  // dual_motion's check, with its message
    throw Error("dual_motion: " + std::to_string(surface_motion.size()) + " motion vectors for a " +
                std::to_string(w) + "x" + std::to_string(h) + " frame");
  if (pixels == 0) return {};
  if (g.prev_pose.instance_to_world.size() != g.pose.instance_to_world.size())
    throw Error("dual_motion: the two poses have different instance counts");

  // The host's part (motion_dual_gpu.h): the previous visibility buffer, and every sample's object point.
  const VisibilityBuffer prev_vis = previous_visibility(scene, g);
  const int pw = prev_vis.width, ph = prev_vis.height;
  const auto point = plane_buffer(context, w, h, TexelFormat::RGBA32F),
             instance = plane_buffer(context, w, h, TexelFormat::R32UI),
             motion = plane_buffer(context, w, h, TexelFormat::RG32F),
             prev_point_depth = plane_buffer(context, pw, ph, TexelFormat::RGBA32F),
             prev_instance = plane_buffer(context, pw, ph, TexelFormat::R32UI);
  pack_object_points(scene, g.vis, false, *point);
  pack_instances(g.vis, *instance);
  std::memcpy(motion->data(), surface_motion.data(), pixels * sizeof(glm::vec2));
  if (pw > 0 && ph > 0) {
    pack_object_points(scene, prev_vis, true, *prev_point_depth);
    pack_instances(prev_vis, *prev_instance);
  }
  const std::vector<DualInstance> instances = instance_records(g.pose, g.prev_pose);
  const auto instance_buffer = record_buffer(context, instances);
  const auto views = view_buffer(context, g);
  // (x^O - x_i, disoccluded, 0) per pixel.
  const auto result = plane_buffer(context, w, h, TexelFormat::RGBA32F);

  const MotionPort port(context, "motion_dual", kDualMotionTexelBindings, kDualMotionStorageBindings,
                        sizeof(DualMotionPush));
  const DualMotionPush push{.width = uint32_t(w),
                            .height = uint32_t(h),
                            .prev_width = uint32_t(pw),
                            .prev_height = uint32_t(ph),
                            .instance_count = uint32_t(instances.size()),
                            .unused = {0u, 0u, 0u}};
  port.run(context,
           {point.get(), instance.get(), motion.get(), prev_point_depth.get(), prev_instance.get(),
            instance_buffer.get(), views.get(), result.get()},
           &push, w, h, ms);

  return unpack_records<DualMotion>(*result, w, h);
}

}  // namespace rtdr
