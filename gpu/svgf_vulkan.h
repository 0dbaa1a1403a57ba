// SVGF and A-SVGF, the whole pipeline, on a Vulkan device: the Method behind `rtdr filter --backend vulkan
// --method svgf|asvgf`. The same passes in the same order as SvgfFilter (filters/svgf/svgf.h) with method "svgf" or
// "asvgf" - for asvgf first, per stream, the gradient image, its reconstruction's iterations and lambda and alpha_i
// (gpu/asvgf_vulkan.h, filters/asvgf/*.comp) [ASVGF18 Sec. 3.4, 3.5]; then temporal accumulation (with asvgf's alpha_i per pixel),
// variance, the a-trous levels (the level `history_level` kept as next frame's colour history), remodulation, tone
// mapping and TAA - each one dispatch of the ports in filters/svgf/*.comp and filters/taa/taa.comp, both streams
// at once.
//
// Every history stays on the device between frames (colour history, moments, the previous G-buffer, the TAA
// history): per frame the host uploads the input frame's planes, runs one batch of dispatches (5 + atrous_levels,
// and 2 (2 + gradient_levels) more for asvgf) and two copies, and reads back the colour and the display colour. Buffers are made for the first frame's size; a
// later frame of another size throws, as SvgfFilter does.
//
// pass_times(): each pass's device time (timestamps), summed over its dispatches and streams, plus "transfer": the
// host's wall time to pack the inputs and unpack the outputs, and the device time of copying the outputs into
// host-cached memory first.
//
// filter(in, dump) with a dump (`rtdr filter --backend vulkan --dump-passes`, `rtdr compare`) gives the golden
// SvgfFilter's intermediate layers (docs/buffers.md, "Filter passes"), read back from the device: each plane is
// copied into host-cached memory right after the dispatch that writes it, since the levels' planes are reused
// within the frame. The copies run in the same batch, timed as "dump", and change no output. They hold what the
// device's records hold: with fp16 records, every illumination colour and variance as stored in halves. Passes are
// not probed: that stays with the golden SvgfFilter (--backend cpu).
#pragma once

#include "filters/svgf/svgf.h"
#include "gpu/asvgf_vulkan.h"
#include "gpu/svgf_shaders.h"
#include "gpu/vulkan_method.h"

#include <memory>

namespace rtdr {

class SvgfVulkan : public VulkanMethod {
 public:
  // `options` must be the "svgf" or "asvgf" configuration's stages (temporal, a-trous, TAA, with or without the
  // adaptive alpha); its parameters may be any.
  SvgfVulkan(VulkanContext& context, const SvgfOptions& options);
  ~SvgfVulkan() override;
  std::string name() const override { return options_.name; }
  Frame filter(const Frame& in, Frame* dump) override;
  void reset() override;
  Probe probe(const std::string& pass, int x, int y, const std::string& stream, int level) const override;
  std::vector<std::string> probe_passes() const override { return {}; }
  InputChannels inputs() const override { return svgf_input_channels(options_); }
  std::vector<std::string> dump_channels() const override { return svgf_dump_channels(options_); }

 private:
  struct Buffers;  // every device plane, made for one frame size
  class Dump;      // the copies behind filter()'s dump, and their readback buffers
  VulkanContext& context_;
  SvgfOptions options_;
  SvgfShaders shaders_;
  std::unique_ptr<Buffers> buffers_;
  std::unique_ptr<AsvgfVulkan> asvgf_;  // A-SVGF's passes (with options_.adaptive)
  std::unique_ptr<GpuBuffer> unread_weights_;  // what the temporal port binds without them
  std::unique_ptr<Dump> dump_;
  int frames_ = 0;  // frames since the last reset: 0 means no history
};

}  // namespace rtdr
