// The declarations of every filter pass, and the functions that expand their layer patterns. See passes.h.
#include "filters/passes.h"

#include "core/error.h"

#include <algorithm>

namespace rtdr {

const std::vector<PassDecl>& filter_passes() {
  using namespace layers;
  static const std::vector<PassDecl> passes = {
      {"gradient", "filters/asvgf/gradient_image.cpp", "[ASVGF18 Sec. 3.4, Eq. 3, Eq. 13]", PassScope::Stream,
       "the stream's 1-spp illumination; gradient.source, gradient.prev_<stream>; depth.Z, depth.dX/dY, normal, "
       "id.mesh; the stratum size in the header (rtdr.gradient.stratum_size)",
       {&kGradientDelta, &kGradientNorm, &kGradientLuminance, &kGradientVariance},
       {},
       "the stratum, its representative pixel, the gradient sample's two luminances, delta and Delta, and the "
       "stratum's mean luminance and variance"},
      {"gradient_atrous", "filters/asvgf/gradient_atrous.cpp", "[ASVGF18 Eq. 7-12]", PassScope::StreamLevel,
       "iteration i - 1's delta^, Delta^, l^ and Var(l^) (iteration 0: the gradient pass), on the stratum grid",
       {&kGradientLevelDelta, &kGradientLevelNorm, &kGradientLevelLuminance, &kGradientLevelVariance},
       {"sigma_z", "sigma_n", "sigma_l", "epsilon", "gradient_levels"},
       "z, n, l^ and g3x3(Var) at the stratum, then per tap: w_z, w_n, w_l, h w, delta and Delta; then the sums "
       "and the next iteration's values"},
      {"adaptive_alpha", "filters/asvgf/adaptive_alpha.cpp", "[ASVGF18 Eq. 14-15, Sec. 3.5]", PassScope::Stream,
       "the last reconstruction iteration's delta^ and Delta^",
       {&kLambda, &kAlpha},
       {"alpha", "alpha_moments", "alpha_max_radius"},
       "the pixel's stratum, its delta^, Delta^ and lambda, the largest lambda around it, alpha_i and alpha_mu_i"},
      {"temporal", "filters/svgf/temporal.cpp", "[SVGF17 Sec. 4.1, 4.2]", PassScope::Stream,
       "the stream's 1-spp illumination; depth.Z, normal, id.mesh and motion; last frame's colour history, "
       "moments, history length and G-buffer; with A-SVGF the adaptive_alpha pass's alpha_i, alpha_mu_i and lambda",
       {&kTemporal, &kMoment1, &kMoment2, &kHistoryLength},
       {"alpha", "alpha_moments", "temporal_depth_relative", "temporal_normal_cosine", "max_history", "history_rule"},
       "the back-projected position p', each bilinear tap's consistency tests (inside, mesh id, depth, normal) and "
       "weight, the 3x3 fallback when no tap is consistent, then alpha, C', mu1', mu2' and n"},
      {"variance", "filters/svgf/variance.cpp", "[SVGF17 Sec. 4.2]", PassScope::Stream,
       "the temporal pass's moments and history length; depth.Z, depth.dX/dY, normal, id.mesh",
       {&kVariance, &kVarianceSpatial},
       {"variance_min_history", "sigma_z", "sigma_n", "epsilon"},
       "n, then either mu2' - mu1'^2 (n >= variance_min_history) or the 7x7 spatial estimate: each tap's w_z, w_n "
       "and moments, and the weighted means"},
      {"prefilter", "filters/svgf/prefilter.cpp", "[SVGF17 Sec. 4.4, Eq. 5]", PassScope::StreamLevel,
       "the variance entering a-trous level i",
       {&kLevelPrefiltered},
       {},
       "each of the 3x3 taps' binomial weight g and variance, and g3x3(Var)(p)"},
      {"atrous", "filters/svgf/atrous.cpp", "[SVGF17 Eq. 1-5, Sec. 4.3]", PassScope::StreamLevel,
       "level i - 1's colour and variance (level 0: the temporal colour and the variance pass), the prefilter of "
       "that variance; depth.Z, depth.dX/dY, normal, id.mesh",
       {&kLevel, &kLevelVariance, &kFiltered},
       {"sigma_z", "sigma_n", "sigma_l", "epsilon", "atrous_levels", "kernel_size", "history_level"},
       "z, grad z, n, l and g3x3(Var) at p, then per tap: p - q, z(q), n(q), l(q), w_z, w_n, w_l, w, h, h w and "
       "Var(q); then the sums, c_{i+1}(p) and Var(c_{i+1}(p))"},
      {"eaw", "filters/baselines/eaw.cpp", "[EAW10]", PassScope::StreamLevel,
       "level i - 1's colour (level 0: the temporal colour); position, normal, id.mesh",
       {&kLevel, &kFiltered},
       {"sigma_rt", "sigma_n", "sigma_x", "levels"},
       "per tap: h, w_rt, w_n, w_x and w; then the sums and the level's colour"},
      {"ema", "filters/svgf/temporal.cpp", "[ASVGF18 Eq. 1, Sec. 4]", PassScope::Stream,
       "the spatial filter's result; depth.Z, normal, id.mesh and motion; last frame's EMA and G-buffer; the "
       "adaptive_alpha pass's alpha_i, alpha_mu_i and lambda",
       {&kEma},
       {"alpha", "alpha_moments", "temporal_depth_relative", "temporal_normal_cosine", "max_history", "history_rule"},
       "as the temporal pass, on the spatial filter's result instead of the 1-spp input"},
      {"modulate", "filters/svgf/modulate.cpp", "[SVGF17 Sec. 3]", PassScope::Frame,
       "both streams' filtered illumination; albedo, emission",
       {&kColor},
       {},
       "the demodulation factor max(albedo, 0.001), direct + indirect, the reflected radiance and the colour"},
      {"tonemap", "filters/svgf/tonemap.cpp", "[Reinhard02 Eq. 2, 3]", PassScope::Frame,
       "the modulate pass's colour",
       {&kTonemapped, &kDisplay},
       {"exposure"},
       "L_w, L = exposure L_w, L_d = L / (1 + L), and the display colour"},
      {"trmv_penumbra", "filters/trmv/penumbra.cpp", "[LLK*19, TRMV21 Sec. 4.1]", PassScope::Frame,
       "path.light and its instance, path.blocker and its instance; position, normal, id.instance; the trmv_splat "
       "pass's W",
       {&kTrmvPenumbraWidth, &kTrmvSigmaX, &kTrmvSigmaY},
       {"shadow_filter", "spatial_radius", "spatial_sigma", "footprint_height"},
       "(m_x, m_y), the light's diameter D and the penumbra's width W at the pixel"},
      {"trmv_splat", "filters/trmv/splat.cpp", "[TRMV21 Sec. 4.1]", PassScope::Frame,
       "motion.shadow and its validity; motion, id.instance, normal; the trmv_penumbra pass's W",
       {&kTrmvSplatX, &kTrmvSplatY, &kTrmvSplatLanded},
       {"splat_size", "spatial_radius", "footprint_height"},
       "the window's side, how many vectors landed, the splatted m^V and W"},
      {"trmv_spatial", "filters/trmv/spatial.cpp", "[TRMV21 Sec. 5]", PassScope::Frame,
       "direct.visibility; depth.Z, depth.dX/dY, normal, id.mesh; with shadow_filter = 1 the trmv_penumbra pass's "
       "std",
       {&kTrmvVisibilitySpatial},
       {"spatial_radius", "spatial_sigma", "footprint_height", "shadow_filter", "sigma_z", "sigma_n", "epsilon"},
       "the visibility's vertical 1-D pass at the pixel (the second of the two): per tap G(k), w_z, w_n and the "
       "value, then the sum of the weights and the result"},
      {"trmv_falloff", "filters/trmv/falloff.cpp", "[TRMV21 Eq. 4]", PassScope::Frame,
       "the trmv_splat pass's motion and where it landed; position, geonormal, id.mesh, motion; last frame's "
       "position, geonormal and id.mesh",
       {&kTrmvTheta, &kTrmvAlphaV},
       {"alpha", "falloff_sigma", "falloff_carry", "motion"},
       "x^V_{i-1}, the previous surface point s^V_{i-1} there, s_i and n(s_i) (carried back or not), theta, G and "
       "alpha^V"},
      {"trmv_atrous", "filters/trmv/atrous.cpp", "[TRMV21 Sec. 5]", PassScope::Frame,
       "indirect.diffuse; depth.Z, depth.dX/dY, normal, id.mesh",
       {&kTrmvDiffuseSpatial},
       {"diffuse_filter", "atrous_levels", "footprint_height", "sigma_z", "sigma_n", "epsilon"},
       "the diffuse light's a-trous level --level (the last by default) at the pixel: per tap w_z and w_n, the sum "
       "and the result (diffuse_filter = 0: the shadow filter's bilateral, not probed)"},
      {"trmv_reshade", "filters/trmv/reshade.cpp", "[TRMV21 Eq. 11]", PassScope::Frame,
       "path.direction, path.incoming, path.pdf; motion.dual and its validity; normal, depth, id.mesh, motion; last "
       "frame's cones, normals and G-buffer",
       {&kTrmvDiffuseReshaded},
       {"alpha", "motion", "cones", "cone_half_angle", "cone_transfer", "diffuse_filter", "atrous_levels"},
       "x^O, the normal there and the pixel's, the six transferred cones L'_k, their shares f_k, the blended H_k "
       "and the re-shaded L_o"},
      {"trmv_reflection", "filters/trmv/reflection.cpp", "[LLK*19, TRMV21 Sec. 5]", PassScope::Frame,
       "indirect.glossy; glossy.footprint and its validity; depth.Z, depth.dX/dY, normal, id.mesh",
       {&kTrmvGlossySpatial},
       {"glossy_filter", "glossy_radius", "footprint_height", "sigma_z", "sigma_n", "epsilon"},
       "the window, the footprint's precision S^-1, the sum of the weights and the result (glossy_filter = 0: the "
       "shadow filter's bilateral, not probed)"},
      {"trmv_temporal", "filters/trmv/temporal.cpp", "[TRMV21 Eq. 2, Sec. 5]", PassScope::Frame,
       "the component's c~ (trmv_spatial, trmv_atrous, trmv_reflection); its motion (visibility: the trmv_splat "
       "pass's or motion; diffuse: motion.dual or motion, and the trmv_reshade pass's history; glossy: "
       "motion.glossy, motion.glossy_mean or motion) and each vector's history test; last frame's history and "
       "G-buffer; visibility: the trmv_falloff pass's alpha^V",
       {&kTrmvVisibilityTemporal, &kTrmvVisibilityClamped, &kTrmvDiffuseTemporal, &kTrmvDiffuseClamped,
        &kTrmvGlossyTemporal, &kTrmvGlossyClamped},
       {"alpha", "clamp_gamma", "clamp_radius", "motion", "history_test", "shadow_receiver_test", "glossy_draw"},
       "x_{i-1}, the history test, the kept bilinear weights (or the re-shaded history), the fetched history, the "
       "window's mu and sigma, the clamped history, alpha and cbar_i"},
      {"trmv_cleanup", "filters/trmv/cleanup.cpp", "[TRMV21 Eq. 7, Eq. 8, Sec. 5]", PassScope::Frame,
       "the trmv_temporal pass's cbar_i, fetched and clamped history; alpha^V; depth.Z, normal, id.mesh",
       {&kTrmvWeightA, &kTrmvVisibilityWeightC, &kTrmvDiffuseWeightC, &kTrmvGlossyWeightC, &kTrmvVisibilityCleaned,
        &kTrmvDiffuseCleaned, &kTrmvGlossyCleaned},
       {"alpha", "cleanup_size", "footprint_height", "cleanup_sigma_max", "cleanup_eps", "history_after_cleanup"},
       "w_A, w_C and the clean-up's std at the pixel"},
      {"taa", "filters/taa/taa.cpp", "[Karis14]", PassScope::Frame,
       "the tone-mapped colour, last frame's display, motion",
       {&kDisplay},
       {"alpha", "clip_history", "jitter_period"},
       "the history position, its bilinear fetch, the 3x3 neighbourhood's box, the clipped history and the blend"},
  };
  return passes;
}

const PassDecl& find_pass(std::string_view name) {
  std::string known;
  for (const PassDecl& pass : filter_passes()) {
    if (pass.name == name) return pass;
    known += (known.empty() ? "" : ", ") + std::string(pass.name);
  }
  throw Error("there is no pass '" + std::string(name) + "' (passes: " + known + ")");
}

std::vector<std::string> dump_channels_of(const std::vector<PassUse>& passes, const std::vector<std::string>& streams) {
  std::vector<std::string> channels;
  for (const PassUse& use : passes)
    for (const LayerDecl* layer : use.pass->writes)
      if (layer->use == LayerUse::Dump)
        for (std::string& channel : expand_layer(*layer, use.levels, streams))
          if (std::find(channels.begin(), channels.end(), channel) == channels.end()) channels.push_back(std::move(channel));
  return channels;
}

std::string layer_name(const LayerDecl& layer, std::string_view stream, int level) {
  std::string name(layer.pattern);
  if (const size_t at = name.find("<s>"); at != std::string::npos) name.replace(at, 3, stream);
  if (const size_t at = name.find("<i>"); at != std::string::npos) name.replace(at, 3, std::to_string(level));
  return name;
}

std::vector<std::string> layer_channels(const LayerDecl& layer, std::string_view stream, int level) {
  const std::string name = layer_name(layer, stream, level);
  if (layer.type == LayerType::Scalar) return {name};
  return {name + ".R", name + ".G", name + ".B"};
}

std::vector<std::string> expand_layer(const LayerDecl& layer, int levels, const std::vector<std::string>& streams) {
  const bool per_stream = layer.pattern.find("<s>") != std::string_view::npos;
  const bool per_level = layer.pattern.find("<i>") != std::string_view::npos;
  std::vector<std::string> channels;
  for (const std::string& stream : streams) {
    for (int level = 0; level < (per_level ? levels : 1); ++level)
      for (std::string& c : layer_channels(layer, stream, per_level ? level : -1)) channels.push_back(std::move(c));
    if (!per_stream) break;
  }
  return channels;
}

bool layer_has_channel(const LayerDecl& layer, std::string_view channel) {
  // Match the pattern piece by piece: "<s>" against a stream name, "<i>" against the digits of a level.
  std::string_view pattern = layer.pattern;
  while (!pattern.empty()) {
    if (pattern.substr(0, 3) == "<s>") {
      pattern.remove_prefix(3);
      if (channel.substr(0, 6) == "direct") channel.remove_prefix(6);
      else if (channel.substr(0, 8) == "indirect") channel.remove_prefix(8);
      else if (channel.substr(0, 8) == kCombinedStream) channel.remove_prefix(8);
      else return false;
    } else if (pattern.substr(0, 3) == "<i>") {
      pattern.remove_prefix(3);
      size_t digits = 0;
      while (digits < channel.size() && channel[digits] >= '0' && channel[digits] <= '9') ++digits;
      if (digits == 0) return false;
      channel.remove_prefix(digits);
    } else {
      if (channel.empty() || channel.front() != pattern.front()) return false;
      pattern.remove_prefix(1);
      channel.remove_prefix(1);
    }
  }
  if (layer.type == LayerType::Scalar) return channel.empty();
  return channel == ".R" || channel == ".G" || channel == ".B";
}

std::string pass_writing(const std::string& channel) {
  std::string passes;
  for (const PassDecl& pass : filter_passes())
    for (const LayerDecl* layer : pass.writes)
      if (layer_has_channel(*layer, channel)) {
        passes += (passes.empty() ? "" : ", ") + std::string(pass.name);
        break;
      }
  return passes.empty() ? "?" : passes;
}

namespace {

void require_type(const LayerDecl& layer, LayerType type) {
  if (layer.type != type)
    throw Error("dump_layer: layer '" + std::string(layer.pattern) + "' is declared " +
                (layer.type == LayerType::Rgb ? "RGB" : "scalar") + " but was given a " +
                (type == LayerType::Rgb ? "RGB" : "scalar") + " plane (filters/passes.h)");
}

}  // namespace

void dump_layer(Frame* dump, const LayerDecl& layer, std::string_view stream, int level, const RgbPlane& plane) {
  require_type(layer, LayerType::Rgb);
  if (dump) set_rgb_plane(*dump, layer_name(layer, stream, level), plane);
}

void dump_layer(Frame* dump, const LayerDecl& layer, std::string_view stream, int level, const FloatPlane& plane) {
  require_type(layer, LayerType::Scalar);
  if (dump) set_float_plane(*dump, layer_name(layer, stream, level), plane);
}

}  // namespace rtdr
