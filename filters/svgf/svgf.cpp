// The SVGF pipeline: passes in the paper's order, histories carried between frames, every intermediate
// buffer kept for dumps and probes. See svgf.h.
#include "filters/svgf/svgf.h"

#include "core/error.h"
#include "filters/input_check.h"
#include "filters/svgf/modulate.h"
#include "filters/svgf/prefilter.h"
#include "filters/svgf/variance.h"

#include <algorithm>

namespace rtdr {

// Every dump layer is named by its declaration in filters/passes.h (dump_layer), listed in docs/buffers.md.
using namespace layers;

SvgfFilter::SvgfFilter(const SvgfOptions& options) : options_(options) {
  validate(options_.svgf);
  validate(options_.asvgf);
  validate(options_.eaw);
  validate(options_.tonemap);
  validate(options_.taa_params);
}

void SvgfFilter::reset() {
  direct_ = Stream();
  indirect_ = Stream();
  prev_surface_ = SurfacePlanes();
  taa_history_ = RgbPlane();
}

const RgbPlane& SvgfFilter::Stream::level_input_color(int level) const {
  if (level == 0) return temporal.color;
  return eaw_levels.empty() ? levels[size_t(level - 1)].color : eaw_levels[size_t(level - 1)];
}

const FloatPlane& SvgfFilter::Stream::level_input_variance(int level) const {
  return level == 0 ? variance : levels[size_t(level - 1)].variance;
}

const RgbPlane& SvgfFilter::Stream::filtered() const { return ema_enabled ? ema.color : spatial_result(); }

const RgbPlane& SvgfFilter::Stream::spatial_result() const {
  if (!levels.empty()) return levels.back().color;
  if (!eaw_levels.empty()) return eaw_levels.back();
  return temporal.color;
}

void SvgfFilter::adaptive_alpha_stream(Stream& s, const std::string& name) {
  const SvgfParams& p = options_.svgf;
  const int s_size = stratum_size_, w = s.noisy.width, h = s.noisy.height;
  // A pixel's stratum, where the gradient passes' per-stratum golden functions are probed.
  const auto stratum = [s_size](int x, int y) { return glm::ivec2(x / s_size, y / s_size); };
  // 1. The gradient image on the stratum grid [ASVGF18 Sec. 3.4, Eq. 3, Eq. 13].
  time_pass("gradient", [&] { s.gradient = gradient_image(s.noisy, gradient_source_, s.prev_luminance, surface_, s_size); });
  log_pass("gradient", name)
      .writes(kGradientDelta, s.gradient.values.delta, s_size)
      .writes(kGradientNorm, s.gradient.values.norm, s_size)
      .writes(kGradientLuminance, s.gradient.values.luminance, s_size)
      .writes(kGradientVariance, s.gradient.values.variance, s_size)
      .pixel([this, &s, stratum](int x, int y, Probe* probe) {
        const glm::ivec2 q = stratum(x, y);
        gradient_stratum(s.noisy, gradient_source_, s.prev_luminance, surface_, stratum_size_, q.x, q.y, probe);
      });
  // 2. Its reconstruction, iteration k reading iteration k - 1 [ASVGF18 Eq. 7-12].
  s.gradient_levels.clear();
  for (int level = 0; level < options_.asvgf.gradient_levels; ++level) {
    const GradientValues& in = level == 0 ? s.gradient.values : s.gradient_levels.back();
    time_pass("gradient_atrous", [&] { s.gradient_levels.push_back(gradient_atrous_level(in, s.gradient, level, p)); });
    const GradientValues& out = s.gradient_levels.back();
    log_pass("gradient_atrous", name, level)
        .writes(kGradientLevelDelta, out.delta, s_size)
        .writes(kGradientLevelNorm, out.norm, s_size)
        .writes(kGradientLevelLuminance, out.luminance, s_size)
        .writes(kGradientLevelVariance, out.variance, s_size)
        .pixel([this, &s, in = &in, level, stratum](int x, int y, Probe* probe) {
          const glm::ivec2 q = stratum(x, y);
          gradient_atrous_pixel(*in, prefilter_variance(in->variance), s.gradient, level, options_.svgf, q.x, q.y,
                                probe);
        });
  }
  // 3. lambda and alpha_i [ASVGF18 Eq. 14-15, Sec. 3.5].
  const GradientValues& reconstructed = s.gradient_levels.empty() ? s.gradient.values : s.gradient_levels.back();
  time_pass("adaptive_alpha", [&] {
    s.adaptive = adaptive_alpha_pass(reconstructed, s_size, w, h, p.alpha, options_.asvgf.alpha_max_radius);
  });
  log_pass("adaptive_alpha", name)
      .writes(kLambda, s.adaptive.lambda, s_size)
      .writes(kAlpha, s.adaptive.alpha)
      .pixel([this, reconstructed = &reconstructed](int x, int y, Probe* probe) {
        adaptive_alpha_pixel(*reconstructed, stratum_size_, options_.svgf.alpha, options_.asvgf.alpha_max_radius, x, y,
                             probe);
      });
}

std::optional<TemporalAdaptive> SvgfFilter::temporal_adaptive(const Stream& s) const {
  if (!options_.adaptive) return std::nullopt;
  return TemporalAdaptive{&s.adaptive.lambda_max, options_.asvgf.history_rule == 0};
}

const RgbPlane& SvgfFilter::filter_stream(Stream& s, RgbPlane noisy, const std::string& name) {
  const SvgfParams& p = options_.svgf;
  s.noisy = std::move(noisy);
  // 0. A-SVGF: the per-pixel alpha from this frame's gradient samples [ASVGF18 Sec. 3.4, 3.5].
  if (options_.adaptive) adaptive_alpha_stream(s, name);
  // 1. Temporal accumulation of colour and luminance moments [SVGF17 Sec. 4.1, 4.2]. Without it (EAW,
  //    "none") every frame is a first frame: the temporal pass then returns its input with n = 1.
  s.seen_history = options_.temporal ? std::move(s.history) : TemporalHistory();
  const std::optional<TemporalAdaptive> adaptive = temporal_adaptive(s);
  time_pass("temporal", [&] { s.temporal = temporal_pass(s.noisy, surface_, s.seen_history, p, adaptive ? &*adaptive : nullptr); });
  log_pass("temporal", name)
      .writes(kTemporal, s.temporal.color)
      .writes(kMoment1, s.temporal.moment1)
      .writes(kMoment2, s.temporal.moment2)
      .writes(kHistoryLength, s.temporal.length)
      .pixel([this, &s, adaptive](int x, int y, Probe* probe) {
        temporal_pixel(s.noisy, surface_, s.seen_history, options_.svgf, x, y, probe, adaptive ? &*adaptive : nullptr);
      });

  // 2. The spatial filter, level by level: SVGF's variance-guided a-trous [Sec. 4.2-4.4] or EAW. Level i
  //    reads level i - 1's output (Stream::level_input_color).
  s.levels.clear();
  s.eaw_levels.clear();
  int history_level = -1;  // which level's output becomes the colour history; -1: the temporal output
  if (options_.spatial == SpatialFilter::Atrous) {
    time_pass("variance", [&] { s.variance = variance_pass(s.temporal, surface_, p); });
    log_pass("variance", name).writes(kVariance, s.variance).pixel([this, &s](int x, int y, Probe* probe) {
      variance_pixel(s.temporal, surface_, options_.svgf, x, y, probe);
    });
    for (int level = 0; level < p.atrous_levels; ++level) {
      time_pass("atrous", [&] {
        s.levels.push_back(atrous_level(s.level_input_color(level), s.level_input_variance(level), surface_, level, p));
      });
      const AtrousOutput& out = s.levels.back();
      // The a-trous level computes the prefilter of its input variance itself [SVGF17 Eq. 5]; probed on its own.
      log_pass("prefilter", name, level).writes(kLevelPrefiltered, out.prefiltered_variance)
          .pixel([&s, level](int x, int y, Probe* probe) {
            prefilter_variance_pixel(s.level_input_variance(level), x, y, probe);
          });
      log_pass("atrous", name, level)
          .writes(kLevel, out.color)
          .writes(kLevelVariance, out.variance)
          .pixel([this, &s, level](int x, int y, Probe* probe) {
            atrous_pixel(s.level_input_color(level), s.level_input_variance(level),
                         s.levels[size_t(level)].prefiltered_variance, surface_, level, options_.svgf, x, y, probe);
          });
    }
    // The first level's output is fed back as the colour history [Sec. 4.3].
    if (p.history_level < p.atrous_levels) history_level = p.history_level;
  } else if (options_.spatial == SpatialFilter::Eaw) {
    for (int level = 0; level < options_.eaw.levels; ++level) {
      time_pass("eaw", [&] {
        s.eaw_levels.push_back(eaw_level(s.level_input_color(level), position_, surface_, level, options_.eaw));
      });
      log_pass("eaw", name, level).writes(kLevel, s.eaw_levels.back()).pixel([this, &s, level](int x, int y, Probe* probe) {
        eaw_pixel(s.level_input_color(level), position_, surface_, level, options_.eaw, x, y, probe);
      });
    }
    if (options_.eaw.levels > 0) history_level = 0;
  }
  // The stream's result: the last level's output (the temporal output when no level ran).
  if (options_.spatial != SpatialFilter::None)
    log_pass(options_.spatial == SpatialFilter::Atrous ? "atrous" : "eaw", name).writes(kFiltered, s.spatial_result());
  // 2'. a-eaw: the (adaptive) temporal EMA of the spatial filter's output, with its own history, as A-SVGF puts
  //     its adaptive temporal filter after a per-frame denoiser (A-RAE) [ASVGF18 Sec. 4, Fig. 6] [ASVGF18 Eq. 1].
  s.ema_enabled = options_.ema_after_spatial;
  if (s.ema_enabled) {
    s.seen_ema_history = std::move(s.ema_history);
    time_pass("ema", [&] {
      s.ema = temporal_pass(s.spatial_result(), surface_, s.seen_ema_history, p, adaptive ? &*adaptive : nullptr);
    });
    log_pass("ema", name).writes(kEma, s.ema.color).pixel([this, &s, adaptive](int x, int y, Probe* probe) {
      temporal_pixel(s.spatial_result(), surface_, s.seen_ema_history, options_.svgf, x, y, probe,
                     adaptive ? &*adaptive : nullptr);
    });
    s.ema_history = {s.ema.color, s.ema.moment1, s.ema.moment2, s.ema.length, surface_};
  }

  // 3. What the next frame reads: the colour history, the moments, the history length, this G-buffer.
  const RgbPlane& history = history_level < 0 ? s.temporal.color
                            : s.levels.empty() ? s.eaw_levels[size_t(history_level)]
                                               : s.levels[size_t(history_level)].color;
  s.history = {history, s.temporal.moment1, s.temporal.moment2, s.temporal.length, surface_};
  return s.filtered();
}

InputChannels svgf_input_channels(const SvgfOptions& options) {
  // Both streams; without an indirect layer the indirect stream is filtered as black.
  InputChannels c =
      common_input_channels({"direct.R", "direct.G", "direct.B", "indirect.R", "indirect.G", "indirect.B"});
  if (options.spatial == SpatialFilter::Eaw)
    for (const char* axis : {"position.X", "position.Y", "position.Z"}) c.floats.push_back(axis);
  if (options.adaptive) {  // the gradient samples of trace/gradients.h
    c.floats.push_back("gradient.prev_direct");
    c.floats.push_back("gradient.prev_indirect");
    c.uints.push_back("gradient.source");
  }
  return c;
}

Frame SvgfFilter::filter(const Frame& in, Frame* dump) {
  times_.clear();
  surface_ = SurfacePlanes::from_frame(in);
  albedo_ = rgb_plane(in, "albedo");
  emission_ = rgb_plane(in, "emission");
  if (options_.spatial == SpatialFilter::Eaw) position_ = xyz_plane(in, "position");
  // A sequence must keep its size: the histories are per pixel.
  const RgbPlane& history = direct_.history.color;
  if (history.width != 0 && (history.width != in.width() || history.height != in.height()))
    throw Error(in.source + ": frame size changed within the sequence (" + std::to_string(in.width()) + "x" +
                std::to_string(in.height()) + ", was " + std::to_string(history.width) + "x" +
                std::to_string(history.height) + ")");
  if (options_.adaptive) {
    // The stratum size the gradient samples were made with, from the render's header (trace/gradients.h).
    stratum_size_ = frame_stratum_size(in, options_.name);
    gradient_source_ = in.uint_channel("gradient.source");
    // At most one sample per stratum (filters/input_check.h, the rule rtdr check applies), named with the frame.
    if (const std::vector<std::string> crowded = gradient_strata_problems(gradient_source_, stratum_size_);
        !crowded.empty())
      throw Error((in.source.empty() ? std::string("the input frame") : in.source) + ": " + crowded.front());
    direct_.prev_luminance = in.float_channel("gradient.prev_direct");
    indirect_.prev_luminance = in.float_channel("gradient.prev_indirect");
  }
  log_.begin(in.width(), in.height());

  // The two streams are filtered separately [SVGF17 Sec. 3].
  const RgbPlane& direct = filter_stream(direct_, rgb_plane(in, "direct"), "direct");
  const RgbPlane& indirect = filter_stream(indirect_, rgb_plane(in, "indirect"), "indirect");
  // Remodulate, recombine, tone map, TAA [SVGF17 Sec. 3].
  time_pass("modulate", [&] { color_ = remodulate(direct, indirect, albedo_, emission_); });
  log_pass("modulate").pixel([this](int x, int y, Probe* probe) {
    remodulate_pixel(direct_.filtered().at(x, y), indirect_.filtered().at(x, y), albedo_.at(x, y), emission_.at(x, y),
                     probe);
  });
  time_pass("tonemap", [&] { tonemapped_ = tonemap(color_, options_.tonemap); });
  log_pass("tonemap").writes(kTonemapped, tonemapped_).pixel([this](int x, int y, Probe* probe) {
    tonemap_pixel(color_.at(x, y), options_.tonemap, probe);
  });
  seen_taa_history_ = taa_history_;
  if (options_.taa && taa_history_.width == in.width()) {  // TAA's first frame passes its input on
    time_pass("taa", [&] { display_ = taa_pass(tonemapped_, taa_history_, surface_.motion, options_.taa_params); });
    log_pass("taa").pixel([this](int x, int y, Probe* probe) {
      taa_pixel(tonemapped_, seen_taa_history_, surface_.motion, x, y, options_.taa_params, TaaJitter{}, probe);
    });
  } else {
    display_ = tonemapped_;
  }
  taa_history_ = display_;
  if (dump) log_.dump(*dump);

  Frame out(in.width(), in.height());
  out.source = in.source;
  set_rgb_plane(out, layer_name(kColor), color_);
  set_rgb_plane(out, layer_name(kDisplay), display_);
  return out;
}

std::vector<PassUse> svgf_passes(const SvgfOptions& options) {
  std::vector<PassUse> passes;
  if (options.adaptive) {
    passes.push_back({&find_pass("gradient")});
    passes.push_back({&find_pass("gradient_atrous"), options.asvgf.gradient_levels});
    passes.push_back({&find_pass("adaptive_alpha")});
  }
  passes.push_back({&find_pass("temporal")});
  if (options.spatial == SpatialFilter::Atrous) {
    passes.push_back({&find_pass("variance")});
    passes.push_back({&find_pass("prefilter"), options.svgf.atrous_levels});
    passes.push_back({&find_pass("atrous"), options.svgf.atrous_levels});
  }
  if (options.spatial == SpatialFilter::Eaw) passes.push_back({&find_pass("eaw"), options.eaw.levels});
  if (options.ema_after_spatial) passes.push_back({&find_pass("ema")});
  passes.push_back({&find_pass("modulate")});
  passes.push_back({&find_pass("tonemap")});
  if (options.taa) passes.push_back({&find_pass("taa")});
  return passes;
}

std::vector<std::string> svgf_dump_channels(const SvgfOptions& options) { return dump_channels_of(svgf_passes(options)); }

std::vector<std::string> SvgfFilter::probe_passes() const {
  std::vector<std::string> names;
  for (const PassUse& use : svgf_passes(options_)) names.emplace_back(use.pass->name);
  return names;
}

}  // namespace rtdr
