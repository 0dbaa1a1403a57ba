// A-SVGF, the method: its defaults, inputs and passes, and AsvgfStream. See asvgf.h.
#include "filters/asvgf/asvgf.h"

#include "filters/svgf/prefilter.h"

namespace rtdr {

// Every dump layer is named by its declaration in filters/passes.h (dump_layer), listed in docs/buffers.md.
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

std::vector<const PassDecl*> asvgf_passes() {
  return {&find_pass("gradient"), &find_pass("gradient_atrous"), &find_pass("adaptive_alpha")};
}

GradientSamples GradientSamples::from_frame(const Frame& frame, const std::string& method) {
  GradientSamples samples;
  samples.stratum_size = frame_stratum_size(frame, method);
  samples.source = frame.uint_channel("gradient.source");
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
                         const SurfacePlanes& surface, const SvgfParams& svgf, const AsvgfParams& asvgf, Frame* dump,
                         const std::string& name, const PassTimer& time) {
  prev_luminance_ = std::move(prev_luminance);
  const int s = samples.stratum_size, w = noisy.width, h = noisy.height;
  // 1. The gradient image on the stratum grid [ASVGF18 Sec. 3.4, Eq. 3, Eq. 13].
  time("gradient",
       [&] { gradient_ = gradient_image(noisy, samples.source, prev_luminance_, surface, s, gradient_form(asvgf)); });
  const auto dump_strata = [&](const LayerDecl& layer, int level, const FloatPlane& strata) {
    if (dump) dump_layer(dump, layer, name, level, replicate_strata(strata, s, w, h));
  };
  dump_strata(kGradientDelta, -1, gradient_.values.delta);
  dump_strata(kGradientNorm, -1, gradient_.values.norm);
  dump_strata(kGradientLuminance, -1, gradient_.values.luminance);
  dump_strata(kGradientVariance, -1, gradient_.values.variance);
  // 2. Its reconstruction, iteration k reading iteration k - 1 [ASVGF18 Eq. 7-12].
  levels_.clear();
  for (int level = 0; level < asvgf.gradient_levels; ++level) {
    time("gradient_atrous", [&] { levels_.push_back(gradient_atrous_level(reconstructed(), gradient_, level, svgf)); });
    dump_strata(kGradientLevelDelta, level, levels_.back().delta);
    dump_strata(kGradientLevelNorm, level, levels_.back().norm);
    dump_strata(kGradientLevelLuminance, level, levels_.back().luminance);
    dump_strata(kGradientLevelVariance, level, levels_.back().variance);
  }
  // 3. lambda, alpha_i and alpha_mu_i [ASVGF18 Eq. 14-15, Sec. 3.5].
  time("adaptive_alpha",
       [&] { adaptive_ = adaptive_alpha_pass(reconstructed(), s, w, h, adaptive_alpha_params(svgf, asvgf)); });
  dump_strata(kLambda, -1, adaptive_.lambda);
  dump_layer(dump, kAlpha, name, -1, adaptive_.alpha);
}

TemporalAdaptive AsvgfStream::temporal(const AsvgfParams& asvgf) const {
  return TemporalAdaptive{&adaptive_.lambda_max, &adaptive_.alpha, &adaptive_.alpha_moments, asvgf.history_rule == 0};
}

Probe AsvgfStream::probe(const std::string& pass, int x, int y, int level, const RgbPlane& noisy,
                         const GradientSamples& samples, const SurfacePlanes& surface, const SvgfParams& svgf,
                         const AsvgfParams& asvgf) const {
  Probe probe;
  const int s = samples.stratum_size, sx = x / s, sy = y / s;
  if (pass == "gradient")
    gradient_stratum(noisy, samples.source, prev_luminance_, surface, s, sx, sy, gradient_form(asvgf), &probe);
  if (pass == "gradient_atrous") {
    const GradientValues& in = level == 0 ? gradient_.values : levels_[size_t(level - 1)];
    gradient_atrous_pixel(in, prefilter_variance(in.variance), gradient_, level, svgf, sx, sy, &probe);
  }
  if (pass == "adaptive_alpha")
    adaptive_alpha_pixel(reconstructed(), s, adaptive_alpha_params(svgf, asvgf), x, y, &probe);
  return probe;
}

}  // namespace rtdr
