// A-SVGF, the method: its defaults, inputs and passes, and AsvgfStream. See asvgf.h.
#include "filters/asvgf/asvgf.h"

#include "core/error.h"
#include "filters/input_check.h"
#include "filters/svgf/prefilter.h"

namespace rtdr {

// Every logged layer is named by its declaration in filters/passes.h, listed in docs/buffers.md.
using namespace layers;

void asvgf_defaults(MethodParams& p) {
  p.svgf.alpha = 0.1f;          // [ASVGF18 Sec. 5]: "alpha = 0.1" (SVGF: 0.2)
  p.svgf.alpha_moments = 0.1f;  // the paper has one alpha
  p.svgf.kernel_size = 3;       // "a simple 3x3 box filter" for the a-trous [ASVGF18 Sec. 4]
}

void add_gradient_inputs(InputChannels& c) {
  c.floats.push_back("gradient.prev_direct");
  c.floats.push_back("gradient.prev_indirect");
  c.uints.push_back("gradient.source");
}

std::vector<PassUse> asvgf_passes(const AsvgfParams& asvgf) {
  return {{&find_pass("gradient")}, {&find_pass("gradient_atrous"), asvgf.gradient_levels}, {&find_pass("adaptive_alpha")}};
}

GradientSamples GradientSamples::from_frame(const Frame& frame, const std::string& method) {
  GradientSamples samples;
  samples.stratum_size = frame_stratum_size(frame, method);
  samples.source = frame.uint_channel("gradient.source");
  // At most one sample per stratum (filters/input_check.h, the rule rtdr check applies), named with the frame.
  if (const std::vector<std::string> crowded = gradient_strata_problems(samples.source, samples.stratum_size);
      !crowded.empty())
    throw Error((frame.source.empty() ? std::string("the input frame") : frame.source) + ": " + crowded.front());
  return samples;
}

GradientForm gradient_form(const AsvgfParams& asvgf) {
  return {asvgf.gradient_normalize == 1, asvgf.gradient_abs == 1, asvgf.gradient_exponent, asvgf.gradient_scale};
}

AdaptiveAlphaParams adaptive_alpha_params(const SvgfParams& svgf, const AsvgfParams& asvgf) {
  // Normalised before the reconstruction, delta^ / Delta^ is the mean ratio already: p and k were applied per sample.
  const bool after = asvgf.gradient_normalize == 0;
  return {svgf.alpha, svgf.alpha_moments, asvgf.alpha_max_radius, after ? asvgf.gradient_exponent : 1,
          after ? asvgf.gradient_scale : 1.0f};
}

void AsvgfStream::filter(const RgbPlane& noisy, FloatPlane prev_luminance, const GradientSamples& samples,
                         const SurfacePlanes& surface, const SvgfParams& svgf, const AsvgfParams& asvgf,
                         const std::string& name, const PassTimer& time, PassLog& log) {
  prev_luminance_ = std::move(prev_luminance);
  const int s = samples.stratum_size, w = noisy.width, h = noisy.height;
  // The per-stratum passes are probed at the stratum of pixel (x, y); their planes hold one value per stratum.
  // 1. The gradient image on the stratum grid [ASVGF18 Sec. 3.4, Eq. 3, Eq. 13].
  time("gradient",
       [&] { gradient_ = gradient_image(noisy, samples.source, prev_luminance_, surface, s, gradient_form(asvgf)); });
  log.add(find_pass("gradient"), name)
      .writes(kGradientDelta, gradient_.values.delta, s)
      .writes(kGradientNorm, gradient_.values.norm, s)
      .writes(kGradientLuminance, gradient_.values.luminance, s)
      .writes(kGradientVariance, gradient_.values.variance, s)
      .pixel([this, noisy = &noisy, source = &samples.source, surface = &surface, s, form = gradient_form(asvgf)](
                 int x, int y, Probe* probe) {
        gradient_stratum(*noisy, *source, prev_luminance_, *surface, s, x / s, y / s, form, probe);
      });
  // 2. Its reconstruction, iteration k reading iteration k - 1 [ASVGF18 Eq. 7-12].
  levels_.clear();
  for (int level = 0; level < asvgf.gradient_levels; ++level) {
    const GradientValues& in = reconstructed();
    time("gradient_atrous", [&] { levels_.push_back(gradient_atrous_level(in, gradient_, level, svgf)); });
    log.add(find_pass("gradient_atrous"), name, level)
        .writes(kGradientLevelDelta, levels_.back().delta, s)
        .writes(kGradientLevelNorm, levels_.back().norm, s)
        .writes(kGradientLevelLuminance, levels_.back().luminance, s)
        .writes(kGradientLevelVariance, levels_.back().variance, s)
        .pixel([this, in = &in, level, s, svgf](int x, int y, Probe* probe) {
          gradient_atrous_pixel(*in, prefilter_variance(in->variance), gradient_, level, svgf, x / s, y / s, probe);
        });
  }
  // 3. lambda, alpha_i and alpha_mu_i [ASVGF18 Eq. 14-15, Sec. 3.5].
  const AdaptiveAlphaParams alpha = adaptive_alpha_params(svgf, asvgf);
  time("adaptive_alpha", [&] { adaptive_ = adaptive_alpha_pass(reconstructed(), s, w, h, alpha); });
  log.add(find_pass("adaptive_alpha"), name)
      .writes(kLambda, adaptive_.lambda, s)
      .writes(kAlpha, adaptive_.alpha)
      .pixel([this, s, alpha](int x, int y, Probe* probe) {
        adaptive_alpha_pixel(reconstructed(), s, alpha, x, y, probe);
      });
}

TemporalAdaptive AsvgfStream::temporal(const AsvgfParams& asvgf) const {
  return TemporalAdaptive{&adaptive_.lambda_max, &adaptive_.alpha, &adaptive_.alpha_moments, asvgf.history_rule == 0};
}

}  // namespace rtdr
