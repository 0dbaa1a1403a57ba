// A-SVGF, the method [ASVGF18 Sec. 3.4, 3.5, 4, 5]: SVGF (filters/svgf/svgf.h) whose temporal accumulation takes,
// per pixel, a weight made from the frame's temporal gradient samples (trace/gradients.h). Per illumination stream:
//
//   gradient (gradient_image.h)             delta, Delta, l^(0), Var per stratum          [Eq. 3, 13, Sec. 3.4]
//   gradient_atrous x gradient_levels       the joint-bilateral reconstruction           [Eq. 7-12]
//     (gradient_atrous.h)
//   adaptive_alpha (adaptive_alpha.h)       lambda, then alpha_i and alpha_mu_i per pixel [Eq. 14, 15, Sec. 3.5]
//   -> SVGF's temporal pass reads alpha_i, alpha_mu_i and lambda (TemporalAdaptive, filters/svgf/temporal.h)
//   -> SVGF's variance, the 3x3 box a-trous [Sec. 4], remodulation, tone mapping, TAA.
//
// This file is where A-SVGF is put together: its defaults (the paper's alpha = 0.1 and 3x3 box), the inputs it
// adds, the passes it adds, and AsvgfStream, which runs them on one stream for SvgfFilter (filters/svgf/svgf.cpp)
// and logs each in the method's pass log (filters/pass_log.h), from which the dump and `rtdr probe` read them. Its
// Vulkan twin is gpu/asvgf_vulkan.h. The alpha of `--alpha` goes: the flag, or asvgf_defaults() below ->
// AsvgfStream::filter -> adaptive_alpha_pass (Eq. 15) -> alpha_i, which the temporal pass uses as it is.
#pragma once

#include "filters/asvgf/adaptive_alpha.h"
#include "filters/asvgf/asvgf_params.h"
#include "filters/asvgf/gradient_atrous.h"
#include "filters/asvgf/gradient_image.h"
#include "filters/method.h"
#include "filters/pass_log.h"
#include "filters/passes.h"
#include "filters/svgf/svgf_params.h"
#include "filters/svgf/temporal.h"
#include "filters/surface_planes.h"

#include <deque>
#include <functional>
#include <string>
#include <vector>

namespace rtdr {

// A-SVGF's choices where its paper departs from SVGF's tables, for the methods asvgf and a-eaw:
//   alpha = alpha_moments = 0.1  [ASVGF18 Sec. 5]: "alpha = 0.1" (SVGF: 0.2); the paper has one alpha
//   kernel_size = 3             [ASVGF18 Sec. 4]: "a simple 3x3 box filter" for the a-trous
void asvgf_defaults(MethodParams& params);
// (`--help` shows them beside each flag's table default: app/options.cpp.)

// The channels A-SVGF reads beyond SVGF's: the gradient samples (trace/gradients.h).
void add_gradient_inputs(InputChannels& channels);

// The passes A-SVGF runs on each stream before SVGF's temporal pass, in order (filters/passes.h), with the
// reconstruction's gradient_levels iterations.
std::vector<PassUse> asvgf_passes(const AsvgfParams& asvgf);

// One frame's gradient samples, shared by its streams: the stratum size they were made with (the render's header,
// rtdr.gradient.stratum_size) and gradient.source. Throws rtdr::Error naming `method` for a frame without them,
// and naming the frame for a stratum with more than one sample.
struct GradientSamples {
  int stratum_size = 0;
  UIntPlane source;
  static GradientSamples from_frame(const Frame& frame, const std::string& method);
};

// Runs `run`, timed as pass `name` (Method::time_pass).
using PassTimer = std::function<void(const std::string& name, const std::function<void()>& run)>;

// A-SVGF's passes on one illumination stream, and what each made this frame (which the pass log points at).
class AsvgfStream {
 public:
  // The stream's gradient image from its 1-spp colour `noisy` and gradient.prev_<stream> (`prev_luminance`), its
  // reconstruction, then lambda, alpha_i and alpha_mu_i; each pass timed by `time` and logged in `log` as stream
  // `name`, with its layers and its golden per-pixel function. The log points at this stream's planes and at
  // `noisy`, `samples` and `surface`: they must stay where they are until the log's next frame (SvgfFilter's
  // members do).
  void filter(const RgbPlane& noisy, FloatPlane prev_luminance, const GradientSamples& samples,
              const SurfacePlanes& surface, const SvgfParams& svgf, const AsvgfParams& asvgf, const std::string& name,
              const PassTimer& time, PassLog& log);
  // What SVGF's temporal pass reads of this frame: alpha_i, alpha_mu_i and lambda per pixel, and the history rule.
  TemporalAdaptive temporal(const AsvgfParams& asvgf) const;

 private:
  FloatPlane prev_luminance_;          // gradient.prev_<stream>: the previous frame's luminance at each source j
  GradientImage gradient_;             // the gradient image
  // Each reconstruction iteration's output: a deque, whose elements stay where they are as iterations are added,
  // for the pass log points at them (filters/pass_log.h).
  std::deque<GradientValues> levels_;
  AdaptiveAlpha adaptive_;             // lambda, lambda_max, alpha_i, alpha_mu_i
  const GradientValues& reconstructed() const { return levels_.empty() ? gradient_.values : levels_.back(); }
};

// What the gradient and adaptive_alpha passes read of the tables.
GradientForm gradient_form(const AsvgfParams& asvgf);
AdaptiveAlphaParams adaptive_alpha_params(const SvgfParams& svgf, const AsvgfParams& asvgf);

}  // namespace rtdr
