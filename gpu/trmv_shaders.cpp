// TRMV's own compute pipelines and their dispatches. See trmv_shaders.h.
#include "gpu/trmv_shaders.h"

#include "filters/svgf/planes_shared.h"
#include "gpu/svgf_shaders.h"  // port_bindings, load_port: the SVGF ports' conventions, which these follow

namespace rtdr {

namespace {

static_assert(kTrmvSplatTexelBindings + kTrmvSplatStorageBindings <= kStorageInputBindings &&
                  kTrmvSplatTexelBindings <= kTexelInputBindings,
              "TRMV's splat port fits the bindings VulkanContext chose its input kind for");

}  // namespace

TrmvShaders::TrmvShaders(VulkanContext& context)
    : group_width_(context.cpu_device() ? kSvgfCpuGroupSizeX : kSvgfGroupSizeX),
      group_height_(context.cpu_device() ? kSvgfCpuGroupSizeY : kSvgfGroupSizeY),
      splat_(context, load_port(context, "trmv_splat"),
             port_bindings(context, kTrmvSplatTexelBindings, kTrmvSplatStorageBindings), sizeof(TrmvSplatPush),
             {int32_t(group_width_), int32_t(group_height_)}) {}

uint32_t TrmvShaders::groups_x(uint32_t width) const { return (width + group_width_ - 1) / group_width_; }
uint32_t TrmvShaders::groups_y(uint32_t height) const { return (height + group_height_ - 1) / group_height_; }

void TrmvShaders::splat(ComputeBatch& batch, const TrmvSplatGpuPlanes& in, const GpuBuffer& out,
                        const TrmvSplatPush& push) const {
  batch.dispatch(splat_, {in.shadow, in.surface_motion, in.instance, in.normal, &out}, &push, groups_x(push.width),
                 groups_y(push.height), "trmv_splat");
}

}  // namespace rtdr
