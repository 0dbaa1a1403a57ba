// The SVGF pipeline: passes in the paper's order, histories carried between frames, every intermediate
// buffer kept for dumps and probes. See svgf.h.
#include "filters/svgf/svgf.h"

#include "core/error.h"
#include "filters/svgf/modulate.h"
#include "filters/svgf/prefilter.h"
#include "filters/svgf/variance.h"

#include <algorithm>

namespace rtdr {

// Every logged layer is named by its declaration in filters/passes.h, listed in docs/buffers.md.
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

std::optional<TemporalAdaptive> SvgfFilter::temporal_adaptive(const Stream& s) const {
  if (!options_.adaptive) return std::nullopt;
  return s.asvgf.temporal(options_.asvgf);
}

const RgbPlane& SvgfFilter::filter_stream(Stream& s, RgbPlane noisy, FloatPlane prev_luminance,
                                          const std::string& name) {
  const SvgfParams& p = options_.svgf;
  s.noisy = std::move(noisy);
  // 0. A-SVGF: the per-pixel alpha from this frame's gradient samples [ASVGF18 Sec. 3.4, 3.5] (filters/asvgf/asvgf.h),
  //    its passes logged beside SVGF's.
  if (options_.adaptive)
    s.asvgf.filter(s.noisy, std::move(prev_luminance), gradient_samples_, surface_, p, options_.asvgf, name,
                   [this](const std::string& pass, const std::function<void()>& run) { time_pass(pass, run); }, log_);
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
    log_pass("variance", name)
        .writes(kVariance, s.variance)
        .writes(kVarianceSpatial, variance_spatial_plane(s.temporal.length, surface_.mesh, p))  // for the dump alone
        .pixel([this, &s](int x, int y, Probe* probe) { variance_pixel(s.temporal, surface_, options_.svgf, x, y, probe); });
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
  if (options.adaptive) add_gradient_inputs(c);  // the gradient samples of trace/gradients.h
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
  // A-SVGF: the gradient samples, and the stratum size they were made with (the render's header, trace/gradients.h).
  if (options_.adaptive) gradient_samples_ = GradientSamples::from_frame(in, options_.name);
  log_.begin(in.width(), in.height());

  const auto prev_luminance = [&](const char* stream) {  // A-SVGF: gradient.prev_<stream>
    return options_.adaptive ? in.float_channel("gradient.prev_" + std::string(stream)) : FloatPlane();
  };
  if (options_.svgf.streams == 2) {
    // The two streams are filtered separately [SVGF17 Sec. 3].
    filtered_[0] = &filter_stream(direct_, rgb_plane(in, "direct"), prev_luminance("direct"), "direct");
    filtered_[1] = &filter_stream(indirect_, rgb_plane(in, "indirect"), prev_luminance("indirect"), "indirect");
  } else {
    // One stream, direct + indirect, with one gradient [ASVGF18 Sec. 4]: luminance is linear, so the previous
    // frame's luminance of the sum is the sum of the two (the samples' albedo divides out of both alike).
    const OneStream one = one_stream(in, options_.adaptive);
    filtered_[0] = &filter_stream(direct_, one.illumination, one.prev_luminance, kCombinedStream);
    no_light_ = RgbPlane(in.width(), in.height());
    filtered_[1] = &no_light_;
  }
  // Remodulate, recombine, tone map, TAA [SVGF17 Sec. 3].
  time_pass("modulate", [&] { color_ = remodulate(*filtered_[0], *filtered_[1], albedo_, emission_); });
  log_pass("modulate").pixel([this](int x, int y, Probe* probe) {
    remodulate_pixel(filtered_[0]->at(x, y), filtered_[1]->at(x, y), albedo_.at(x, y), emission_.at(x, y), probe);
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

std::vector<std::string> svgf_streams(const SvgfParams& params) {
  if (params.streams == 1) return {kCombinedStream};
  return {"direct", "indirect"};
}

OneStream one_stream(const Frame& in, bool adaptive) {
  OneStream one{rgb_plane(in, "direct"), FloatPlane()};
  const RgbPlane indirect = rgb_plane(in, "indirect");
  for (size_t i = 0; i < one.illumination.data.size(); ++i) one.illumination.data[i] += indirect.data[i];
  if (adaptive) {  // gradient.prev_direct + gradient.prev_indirect
    one.prev_luminance = in.float_channel("gradient.prev_direct");
    const FloatPlane& prev_indirect = in.float_channel("gradient.prev_indirect");
    for (size_t i = 0; i < one.prev_luminance.data.size(); ++i) one.prev_luminance.data[i] += prev_indirect.data[i];
  }
  return one;
}

std::vector<PassUse> svgf_passes(const SvgfOptions& options) {
  std::vector<PassUse> passes;
  if (options.adaptive) passes = asvgf_passes(options.asvgf);
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

std::vector<std::string> svgf_dump_channels(const SvgfOptions& options) {
  return dump_channels_of(svgf_passes(options), svgf_streams(options.svgf));
}

std::vector<std::string> SvgfFilter::probe_passes() const {
  std::vector<std::string> names;
  for (const PassUse& use : svgf_passes(options_)) names.emplace_back(use.pass->name);
  return names;
}

}  // namespace rtdr
