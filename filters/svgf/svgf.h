// SVGF, the whole pipeline [SVGF17 Sec. 3 and 4], as a Method (filters/method.h). Per frame, for each of
// the demodulated direct and indirect illumination separately:
//   temporal accumulation (temporal.h) -> variance estimate (variance.h) -> a-trous levels (atrous.h),
//   the level `history_level` becoming next frame's colour history;
// then remodulation and recombination (modulate.h), tone mapping (tonemap.h) and TAA (filters/taa/taa.h).
// With `ema_after_spatial` (a-eaw) a temporal EMA follows the spatial filter instead of preceding it.
// With `adaptive` (A-SVGF [ASVGF18 Sec. 4]) each stream first runs A-SVGF's passes (filters/asvgf/asvgf.h, which
// puts them together), whose per-pixel alpha_i the temporal accumulation uses in place of the constant alpha.
// The same class runs the baselines of filters/baselines/ by switching stages off or swapping the spatial
// filter, so every method shares the exact same passes (README.md in this folder lists them).
#pragma once

#include "filters/asvgf/asvgf.h"
#include "filters/baselines/eaw.h"
#include "filters/method.h"
#include "filters/passes.h"
#include "filters/svgf/atrous.h"
#include "filters/svgf/svgf_params.h"
#include "filters/surface_planes.h"
#include "filters/svgf/temporal.h"
#include "filters/svgf/tonemap.h"
#include "filters/taa/taa.h"

#include <deque>
#include <optional>

namespace rtdr {

enum class SpatialFilter { None, Atrous, Eaw };

struct SvgfOptions {
  std::string name = "svgf";
  bool temporal = true;                        // temporal accumulation of colour and moments
  SpatialFilter spatial = SpatialFilter::Atrous;
  bool taa = true;                             // temporal antialiasing after tone mapping
  bool adaptive = false;                       // A-SVGF's adaptive alpha from gradient samples [ASVGF18 Sec. 3.5]
  // A temporal EMA of the spatial filter's output, after it (A-RAE's arrangement [ASVGF18 Sec. 4, Fig. 6]), with
  // the adaptive alpha when `adaptive`.
  bool ema_after_spatial = false;
  SvgfParams svgf;
  AsvgfParams asvgf;
  EawParams eaw;
  TonemapParams tonemap;
  TaaParams taa_params;
};

// The illumination streams a filter with `params` runs, by their names in the dump's layers (filters/passes.h):
// "direct" and "indirect" filtered apart [SVGF17 Sec. 3], or with streams = 1 "combined", their sum filtered as one
// stream, with one gradient [ASVGF18 Sec. 4: "we do not separate direct and indirect illumination"].
std::vector<std::string> svgf_streams(const SvgfParams& params);

// streams = 1: the frame's direct + indirect illumination, and with `adaptive` (A-SVGF) gradient.prev_direct +
// gradient.prev_indirect, the previous luminance of the sum. The Vulkan pipeline filters the same (gpu/svgf_vulkan.h).
struct OneStream {
  RgbPlane illumination;
  FloatPlane prev_luminance;
};
OneStream one_stream(const Frame& in, bool adaptive);

// The channels a filter with `options` reads from each input frame: the G-buffer (SurfacePlanes::from_frame),
// albedo, emission, both illumination streams, and `position` for the EAW spatial filter. The Vulkan ports read
// the same (gpu/svgf_vulkan.h).
InputChannels svgf_input_channels(const SvgfOptions& options);
// The passes a filter with `options` runs, in order (declared in filters/passes.h), and every channel its
// dump holds: each pass's dump layers for each stream (svgf_streams) and every level it runs.
std::vector<PassUse> svgf_passes(const SvgfOptions& options);
std::vector<std::string> svgf_dump_channels(const SvgfOptions& options);

class SvgfFilter : public Method {
 public:
  explicit SvgfFilter(const SvgfOptions& options);
  std::string name() const override { return options_.name; }
  Frame filter(const Frame& in, Frame* dump) override;
  void reset() override;
  std::unique_ptr<Method> clone() const override { return std::make_unique<SvgfFilter>(*this); }
  std::vector<std::string> probe_passes() const override;
  InputChannels inputs() const override { return svgf_input_channels(options_); }
  std::vector<std::string> dump_channels() const override { return svgf_dump_channels(options_); }

 private:
  // What one illumination stream carries from frame to frame, and what each of its passes saw last frame.
  struct Stream {
    TemporalHistory history;          // colour history, moments, history length, previous G-buffer
    RgbPlane noisy;                   // this frame's input
    AsvgfStream asvgf;                // A-SVGF's passes and what they made (filters/asvgf/asvgf.h)
    TemporalHistory ema_history, seen_ema_history;  // ema_after_spatial: the EMA's history, and what it read
    TemporalOutput ema;               // and its output
    bool ema_enabled = false;
    TemporalHistory seen_history;     // the history the temporal pass read this frame
    TemporalOutput temporal;          // its output
    FloatPlane variance;              // the variance estimate
    // Each a-trous level's output (prefiltered variance included), or each EAW level's output. Deques, whose
    // elements stay where they are as levels are added: the pass log points at them (filters/pass_log.h).
    std::deque<AtrousOutput> levels;
    std::deque<RgbPlane> eaw_levels;
    // The input of level i is the output of level i - 1; level 0 reads the temporal output.
    const RgbPlane& level_input_color(int level) const;
    const FloatPlane& level_input_variance(int level) const;
    const RgbPlane& spatial_result() const;  // the last level's output (the temporal output without levels)
    const RgbPlane& filtered() const;        // the stream's result: the EMA's output, else spatial_result()
  };

  // Runs one stream's passes and logs them; `name` is the stream, "direct", "indirect" or "combined", for the
  // layer names. `prev_luminance` is its gradient.prev_<stream> with A-SVGF (else empty).
  const RgbPlane& filter_stream(Stream& s, RgbPlane noisy, FloatPlane prev_luminance, const std::string& name);
  // What the temporal pass of stream `s` reads of A-SVGF (null without it).
  std::optional<TemporalAdaptive> temporal_adaptive(const Stream& s) const;

  SvgfOptions options_;
  Stream direct_, indirect_;
  SurfacePlanes surface_, prev_surface_;
  GradientSamples gradient_samples_;  // A-SVGF: this frame's gradient samples
  RgbPlane albedo_, emission_, position_;
  RgbPlane no_light_;                 // streams = 1: the empty second stream that modulate adds (all 0)
  const RgbPlane* filtered_[2] = {};  // what modulate read this frame: the direct (or combined) and indirect results
  RgbPlane color_, tonemapped_, taa_history_, seen_taa_history_, display_;
};

}  // namespace rtdr
