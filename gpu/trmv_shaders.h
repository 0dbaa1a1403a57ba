// TRMV's own compute pipelines beyond those it shares with SVGF (gpu/svgf_shaders.h: its temporal blend, falloff,
// 1-D bilateral and clean-up weights), created once, and one function per pass that records its dispatch into a
// ComputeBatch. Every buffer is a plane in the layout of filters/svgf/planes_shared.h; each pass's bindings are
// listed in its filters/trmv/<stem>_shared.h. The shaders are filters/trmv/*.comp.
#pragma once

#include "filters/trmv/splat_shared.h"
#include "gpu/compute.h"

#include <cstdint>

namespace rtdr {

// What TRMV's splat reads (filters/trmv/splat_shared.h's bindings 0-3).
struct TrmvSplatGpuPlanes {
  const GpuBuffer* shadow;          // (m^V, valid, carried)
  const GpuBuffer* surface_motion;  // (m, 0, 0)
  const GpuBuffer* instance;        // id.instance
  const GpuBuffer* normal;          // (n, 0)
};

class TrmvShaders {
 public:
  explicit TrmvShaders(VulkanContext& context);

  // [TRMV21 Sec. 4.1]: the splat of the shadow motion over a window of push.size (filters/trmv/splat_shared.h),
  // -> (motion, landed, carried).
  void splat(ComputeBatch& batch, const TrmvSplatGpuPlanes& in, const GpuBuffer& out, const TrmvSplatPush& push) const;

 private:
  uint32_t groups_x(uint32_t width) const;
  uint32_t groups_y(uint32_t height) const;

  uint32_t group_width_, group_height_;  // the SVGF ports' workgroup shape on this device (planes_shared.h)
  ComputePipeline splat_;
};

// One of TrmvShaders' passes on its own (the per-pass ports of gpu/trmv_*_gpu.h) runs through
// run_pass<TrmvShaders> (gpu/svgf_shaders.h).

}  // namespace rtdr
