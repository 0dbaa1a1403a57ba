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
// and re-runs them under `rtdr probe`. Its Vulkan twin is gpu/asvgf_vulkan.h. The alpha of `--alpha` goes:
// the flag, or asvgf_defaults() below -> AsvgfStream::filter -> adaptive_alpha_pass (Eq. 15) -> alpha_i, which
// the temporal pass uses as it is.
#pragma once

#include "filters/asvgf/adaptive_alpha.h"
#include "filters/asvgf/asvgf_params.h"
#include "filters/asvgf/gradient_atrous.h"
#include "filters/asvgf/gradient_image.h"
#include "filters/method.h"
#include "filters/passes.h"
#include "filters/svgf/svgf_params.h"
#include "filters/svgf/temporal.h"
#include "filters/surface_planes.h"

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

// The passes A-SVGF runs on each stream before SVGF's temporal pass, in order (filters/passes.h).
std::vector<const PassDecl*> asvgf_passes();

// One frame's gradient samples, shared by its streams: the stratum size they were made with (the render's header,
// rtdr.gradient.stratum_size) and gradient.source. Throws rtdr::Error naming `method` for a frame without them.
struct GradientSamples {
  int stratum_size = 0;
  UIntPlane source;
  static GradientSamples from_frame(const Frame& frame, const std::string& method);
};

// Runs `run`, timed as pass `name` (Method::time_pass).
using PassTimer = std::function<void(const std::string& name, const std::function<void()>& run)>;

// A-SVGF's passes on one illumination stream, and what each made this frame (for the dump and the probe).
class AsvgfStream {
 public:
  // The stream's gradient image from its 1-spp colour `noisy` and gradient.prev_<stream> (`prev_luminance`), its
  // reconstruction, then lambda, alpha_i and alpha_mu_i. With `dump`, their layers as stream `name`.
  void filter(const RgbPlane& noisy, FloatPlane prev_luminance, const GradientSamples& samples,
              const SurfacePlanes& surface, const SvgfParams& svgf, const AsvgfParams& asvgf, Frame* dump,
              const std::string& name, const PassTimer& time);
  // What SVGF's temporal pass reads of this frame: alpha_i, alpha_mu_i and lambda per pixel, and the history rule.
  TemporalAdaptive temporal(const AsvgfParams& asvgf) const;
  // The reconstruction's iterations run this frame.
  int levels() const { return int(levels_.size()); }
  // Re-runs `pass` (one of asvgf_passes()) at pixel (x, y), iteration `level` for gradient_atrous, on exactly the
  // inputs it saw: `noisy`, `samples` and `surface` as given to filter().
  Probe probe(const std::string& pass, int x, int y, int level, const RgbPlane& noisy, const GradientSamples& samples,
              const SurfacePlanes& surface, const SvgfParams& svgf, const AsvgfParams& asvgf) const;

 private:
  FloatPlane prev_luminance_;          // gradient.prev_<stream>: the previous frame's luminance at each source j
  GradientImage gradient_;             // the gradient image
  std::vector<GradientValues> levels_;  // each reconstruction iteration's output
  AdaptiveAlpha adaptive_;             // lambda, lambda_max, alpha_i, alpha_mu_i
  const GradientValues& reconstructed() const { return levels_.empty() ? gradient_.values : levels_.back(); }
};

// What the gradient and adaptive_alpha passes read of the tables.
GradientForm gradient_form(const AsvgfParams& asvgf);
AdaptiveAlphaParams adaptive_alpha_params(const SvgfParams& svgf, const AsvgfParams& asvgf);

}  // namespace rtdr
