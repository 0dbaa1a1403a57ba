// TRMV, the whole filter, on a Vulkan device: the Method behind `rtdr filter --backend vulkan --method trmv`. The
// same passes as TrmvFilter (filters/trmv/trmv.h), the ported ones dispatches of filters/trmv/*.comp, with every
// plane and history on the device:
//   visibility V:  the spatial filter (two 1-D dispatches) -> the falloff (alpha^V, with the splatted shadow motion)
//                  [TRMV21 Eq. 4] -> the temporal blend and clamp [TRMV21 Eq. 2, Sec. 5] -> the clean-up
//                  [TRMV21 Eq. 7-8] (one dispatch and two 1-D ones)
//   diffuse:       (the a-trous, on the host) -> the temporal blend along the dual motion, whose disoccluded pixels
//                  take the history re-shaded from the cones -> the clean-up
//   glossy:        (the lobe filter, on the host) -> the temporal blend along the glossy motion -> the clean-up
// What stays on the host, as the golden code, its result uploaded (each timed as its pass, host wall time):
//   - the penumbra's width and the splat of the shadow motion (filters/trmv/penumbra.h, splat.h; "trmv_splat"). The
//     splat has a port (gpu/trmv_splat_gpu.h, tested on its own) that this batch does not use yet;
//   - the diffuse light's a-trous (filters/trmv/atrous.h; "trmv_atrous") and the glossy light's lobe filter
//     (filters/trmv/reflection.h; "trmv_reflection"): no ports yet;
//   - the cone re-shading [TRMV21 Sec. 4.3, Eq. 9-11] (filters/trmv/reshade.h): it integrates each pixel's path
//     sample and filters each cone; its result is the temporal pass's re-shaded history ("trmv_reshade");
//   - the remodulation (trmv_remodulate: direct.shading x V + diffuse + glossy, times the albedo, plus emission) and
//     the tone mapping, on the three cleaned components read back ("modulate", "tonemap"). They are SVGF's passes,
//     a few ms at 1080p; TRMV has no TAA.
// The motion vectors are the frame's layers (motion.shadow, motion.dual, motion.glossy): the render side made
// them; their own ports are gpu/motion_*_gpu.h.
//
// pass_times(): each port's device time (timestamps) summed over its dispatches and components, the host passes
// above, and "transfer": packing the inputs and unpacking the outputs.
//
// filter(in, dump) with a dump gives TrmvFilter's dump layers (filters/passes.h), read from the device's planes
// after the frame's batch (each component has its own planes). Passes are not probed: that stays with the golden
// TrmvFilter (--backend cpu). Buffers are made for the first frame's size; a later frame of another size throws.
#pragma once

#include "filters/surface_planes.h"
#include "filters/trmv/cones.h"
#include "filters/trmv/footprint.h"
#include "filters/trmv/penumbra.h"
#include "filters/trmv/reshade.h"
#include "filters/trmv/splat.h"
#include "gpu/svgf_shaders.h"
#include "gpu/vulkan_method.h"

#include <memory>
#include <string>
#include <vector>

namespace rtdr {

class TrmvVulkan : public VulkanMethod {
 public:
  TrmvVulkan(VulkanContext& context, const MethodParams& params);
  ~TrmvVulkan() override;
  std::string name() const override { return "trmv"; }
  Frame filter(const Frame& in, Frame* dump) override;
  void reset() override;
  Probe probe(const std::string& pass, int x, int y, const std::string& stream, int level) const override;
  std::vector<std::string> probe_passes() const override { return {}; }
  InputChannels inputs() const override;
  std::vector<std::string> dump_channels() const override;

 private:
  struct Buffers;  // every device plane, made for one frame size
  // Records the visibility's spatial filter and the three components' temporal blends and clean-ups into batch_;
  // `alpha_v` is the visibility's alpha plane, or null; `per_axis_sigma`: the penumbra filter's std per pixel.
  void record_components(const GpuBuffer* alpha_v, bool per_axis_sigma);
  // The passes that run on the host (above), their results packed into `b`; returns the re-shaded history.
  RgbPlane host_passes(const Frame& in, Buffers& b, const SurfacePlanes& surface, const TrmvWindows& win);
  void dump(const Frame& in, Frame& out, const RgbPlane& tonemapped) const;

  VulkanContext& context_;
  MethodParams params_;
  SvgfShaders shaders_;
  std::unique_ptr<Buffers> buffers_;
  ConeLayout cone_layout_;       // the re-shading's cones (cones.h)
  TrmvConeHistory cones_;        // this frame's cones: next frame's history
  TrmvConeHistory seen_cones_;   // those the re-shading read this frame
  // This frame's host passes that the dump shows: the splat, the penumbra and its std per axis (shadow_filter = 1).
  struct HostPasses {
    TrmvSplatOutput splat;
    TrmvPenumbraOutput penumbra;
    FloatPlane sigma_x, sigma_y;
  } host_;
  int frames_ = 0;               // frames since the last reset: 0 means no history
};

}  // namespace rtdr
