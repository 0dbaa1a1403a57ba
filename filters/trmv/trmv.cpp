// TRMV's filter as a Method. The pipeline and its order are in trmv.h; each pass's equations in its own header.
#include "filters/trmv/trmv.h"

#include "core/error.h"
#include "filters/passes.h"
#include "filters/svgf/modulate.h"
#include "filters/trmv/atrous.h"
#include "filters/trmv/spatial.h"

#include <algorithm>
#include <string>
#include <utility>

namespace rtdr {
namespace {

// Visibility is one value per pixel; the passes take RGB planes, so it travels as (V, V, V).
RgbPlane grey_plane(const FloatPlane& v) {
  RgbPlane out(v.width, v.height);
  for (size_t i = 0; i < v.data.size(); ++i) out.data[i] = glm::vec3(v.data[i]);
  return out;
}

// direct ~= shading x visibility [TRMV21 Sec. 4.1]: the noise-free shading term times the filtered visibility
// (trace/README.md says why this replaces the whole `direct`, BSDF-hit emission included).
RgbPlane shade(const RgbPlane& shading, const RgbPlane& visibility) {
  RgbPlane out(shading.width, shading.height);
  for (size_t i = 0; i < out.data.size(); ++i) out.data[i] = shading.data[i] * visibility.data[i].x;
  return out;
}

}  // namespace

RgbPlane trmv_remodulate(const Frame& in, const RgbPlane& visibility, const RgbPlane& diffuse, const RgbPlane& glossy) {
  RgbPlane indirect = diffuse;
  for (size_t i = 0; i < indirect.data.size(); ++i) indirect.data[i] += glossy.data[i];
  return remodulate(shade(rgb_plane(in, "direct.shading"), visibility), indirect, rgb_plane(in, "albedo"),
                    rgb_plane(in, "emission"));
}

namespace {

// The history test of a vector (temporal.h), or none for forced reuse (history_test = 0).
uint32_t test_of(const TrmvParams& p, uint32_t test) { return p.history_test != 0 ? test : kTrmvTestNone; }

// `effect` where `use` is 1 (with `effect_test`), else the surface motion (with SVGF's test).
TrmvMotion effect_or_surface(const Vec2Plane& effect, const UIntPlane& use, const Vec2Plane& surface,
                             uint32_t effect_test, const TrmvParams& p) {
  TrmvMotion m{surface, {}, UIntPlane(surface.width, surface.height), {}, {}};
  for (size_t i = 0; i < m.motion.data.size(); ++i) {
    const bool effect_here = use.data[i] != 0;
    if (effect_here) m.motion.data[i] = effect.data[i];
    m.test.data[i] = test_of(p, effect_here ? effect_test : kTrmvTestSurface);
  }
  return m;
}

}  // namespace

bool trmv_uses_splat(const TrmvParams& p) { return trmv_uses_shadow(p.motion) || p.shadow_filter == 1; }

TrmvSplatPlanes trmv_splat_planes(const Frame& in, const SurfacePlanes& surface, FloatPlane carried) {
  return {xy_plane(in, "motion.shadow"), in.uint_channel("motion.shadow.valid"), surface.motion,
          in.uint_channel("id.instance"),  surface.normal,                       std::move(carried)};
}

TrmvMotion trmv_visibility_motion(const TrmvSplatOutput& splat, const Vec2Plane& surface, const TrmvParams& p) {
  if (!trmv_uses_shadow(p.motion)) {  // the surface motion everywhere [TRMV21 Eq. 1]
    const UIntPlane none(surface.width, surface.height, 0u);
    return effect_or_surface(surface, none, surface, kTrmvTestSurface, p);
  }
  // The splatted shadow motion where a vector landed [TRMV21 Eq. 3, Sec. 4.1]: Eq. 4 handles another receiver, so no
  // test unless shadow_receiver_test asks for the same mesh (temporal.h).
  const uint32_t shadow_test = p.shadow_receiver_test != 0 ? kTrmvTestMesh : kTrmvTestNone;
  return effect_or_surface(splat.motion, splat.landed, surface, shadow_test, p);
}

TrmvMotion trmv_diffuse_motion(const Frame& in, const Vec2Plane& surface, const TrmvParams& p) {
  if (!trmv_uses_dual(p.motion)) {
    const UIntPlane none(surface.width, surface.height, 0u);
    return effect_or_surface(surface, none, surface, kTrmvTestSurface, p);
  }
  // x^O at disoccluded pixels, with the same mesh as its test [TRMV21 Eq. 6]; the surface motion elsewhere.
  TrmvMotion m = effect_or_surface(xy_plane(in, "motion.dual"), in.uint_channel("motion.dual.valid"), surface,
                                   kTrmvTestMesh, p);
  return m;
}

TrmvMotion trmv_glossy_motion(const Frame& in, const Vec2Plane& surface, const TrmvParams& p) {
  if (!trmv_uses_glossy(p.motion)) {
    const UIntPlane none(surface.width, surface.height, 0u);
    return effect_or_surface(surface, none, surface, kTrmvTestSurface, p);
  }
  // Eq. 5's draw, or the lobe's centre mu (glossy_draw = 0), where Eq. 5 gave a vector; the reflector's mesh as its
  // test [TRMV21 Eq. 5].
  const Vec2Plane glossy = xy_plane(in, p.glossy_draw != 0 ? "motion.glossy" : "motion.glossy_mean");
  return effect_or_surface(glossy, in.uint_channel("motion.glossy.valid"), surface, kTrmvTestMesh, p);
}

InputChannels trmv_input_channels() {
  // Not `direct`: its direct light is the shading term times the filtered visibility. Not `indirect`: its two
  // parts follow vectors of their own.
  InputChannels c = common_input_channels(
      {"indirect.diffuse.R", "indirect.diffuse.G", "indirect.diffuse.B", "indirect.glossy.R", "indirect.glossy.G",
       "indirect.glossy.B", "position.X", "position.Y", "position.Z", "geonormal.X", "geonormal.Y", "geonormal.Z",
       "direct.shading.R", "direct.shading.G", "direct.shading.B", "direct.visibility", "motion.shadow.X",
       "motion.shadow.Y", "motion.dual.X", "motion.dual.Y", "motion.glossy.X", "motion.glossy.Y",
       "motion.glossy_mean.X", "motion.glossy_mean.Y", "glossy.footprint.XX", "glossy.footprint.XY",
       "glossy.footprint.YY", "path.light.X", "path.light.Y", "path.light.Z", "path.blocker.X", "path.blocker.Y",
       "path.blocker.Z", "path.direction.X", "path.direction.Y", "path.direction.Z", "path.incoming.R",
       "path.incoming.G", "path.incoming.B", "path.pdf"});
  c.uints.insert(c.uints.end(), {"id.instance", "motion.shadow.valid", "motion.dual.valid", "motion.glossy.valid",
                                 "glossy.footprint.valid", "path.light.instance", "path.blocker.instance"});
  // An engine that does not split its indirect light puts it all in indirect.diffuse.
  for (const char* channel : {"indirect.diffuse.R", "indirect.diffuse.G", "indirect.diffuse.B", "indirect.glossy.R",
                              "indirect.glossy.G", "indirect.glossy.B"})
    c.defaults[channel] = 0.0f;
  return c;
}

TrmvFilter::TrmvFilter(const MethodParams& params)
    : params_(params), cone_layout_(make_cone_layout(params.trmv.cone_half_angle)) {
  validate(params_.trmv);
  validate(params_.svgf);
  validate(params_.tonemap);
}

void TrmvFilter::reset() {
  visibility_ = {};
  diffuse_ = {};
  glossy_ = {};
  prev_positions_ = {};
  cones_ = {};
}

namespace {

// The separable joint bilateral at the shadow filter's window [TRMV21 Sec. 5] (spatial.h).
RgbPlane bilateral(const RgbPlane& c, const SurfacePlanes& s, const TrmvWindows& w, const SvgfParams& edges) {
  return trmv_spatial_pass(c, s, w.shadow_radius, w.shadow_sigma, edges);
}

// A component's planes as its layers hold them: visibility travels as (V, V, V), its layers are scalar.
PassRun& write(PassRun& run, const LayerDecl* layer, const RgbPlane& rgb) {
  if (layer->type == LayerType::Rgb) return run.writes(*layer, rgb);
  FloatPlane first(rgb.width, rgb.height);
  for (size_t i = 0; i < rgb.data.size(); ++i) first.data[i] = rgb.data[i].x;
  return run.writes(*layer, std::move(first));
}

}  // namespace

const RgbPlane& TrmvFilter::filter_component(Component& c, const std::string& name, const Layers& layers) {
  const TrmvParams& p = params_.trmv;
  // 2-3. The history along the component's motion, tested, clamped to mu +- gamma sigma, blended [TRMV21 Eq. 2,
  // Sec. 5]. (1., the spatial filter, is the component's own: prepare_visibility, _diffuse, _glossy.)
  c.seen_history = std::move(c.history);  // replaced below by this frame's
  time_pass("trmv_temporal", [&] {
    c.temporal = trmv_temporal_pass(c.filtered, surface_, c.motion, c.seen_history, c.alpha, p, params_.svgf);
  });
  PassRun& temporal = log_pass("trmv_temporal", name);
  write(temporal, layers.temporal, c.temporal.color);
  write(temporal, layers.clamped, c.temporal.clamped).pixel([this, &c](int x, int y, Probe* probe) {
    trmv_temporal_pixel(c.filtered, surface_, c.motion, c.seen_history, c.alpha, params_.trmv, params_.svgf, x, y,
                        probe);
  });
  // 4. The clean-up, as strong as Eq. 4 and the clamp moved the blend [TRMV21 Eq. 7-8], at its scaled window.
  cleanup_params_ = p;
  cleanup_params_.cleanup_size = 2 * windows_.cleanup_radius + 1;
  time_pass("trmv_cleanup",
            [&] { c.cleaned = trmv_cleanup_pass(c.temporal, c.alpha, surface_, cleanup_params_, params_.svgf); });
  PassRun& cleanup = log_pass("trmv_cleanup", name);
  if (layers.w_a) cleanup.writes(*layers.w_a, c.cleaned.w_a);
  cleanup.writes(*layers.w_c, c.cleaned.w_c);
  write(cleanup, layers.cleaned, c.cleaned.color).pixel([this, &c](int x, int y, Probe* probe) {
    trmv_cleanup_weights_pixel(c.temporal, c.alpha, cleanup_params_, x, y, probe);
  });
  // Next frame's history: before the clean-up unless asked otherwise (history_after_cleanup).
  c.history.color = p.history_after_cleanup != 0 ? c.cleaned.color : c.temporal.color;
  c.history.surface = surface_;
  return c.cleaned.color;
}

PassRun* TrmvFilter::prepare_splat(const Frame& in) {
  using namespace layers;
  const TrmvParams& p = params_.trmv;
  // The penumbra's width W at every in-shadow pixel [LLK*19] (shadow_filter = 1), which the splat carries.
  const bool penumbra = p.shadow_filter == 1;
  PassRun* penumbra_run = nullptr;
  if (penumbra) {
    penumbra_inputs_ = TrmvPenumbraInputs::from_frame(in);
    time_pass("trmv_penumbra", [&] { penumbra_ = trmv_penumbra_pass(penumbra_inputs_); });
    penumbra_run = &log_pass("trmv_penumbra", "visibility").writes(kTrmvPenumbraWidth, penumbra_.width);
    penumbra_run->pixel([this](int x, int y, Probe* probe) {
      float width;
      glm::vec2 metres;
      trmv_penumbra_pixel(penumbra_inputs_, trmv_light_diameters(penumbra_inputs_.light, penumbra_inputs_.light_id),
                          x, y, width, metres, probe);
    });
  }
  // The splat: m^V (and W) spread over the shadow filter's window, on each receiving surface [TRMV21 Sec. 4.1].
  splat_ = {};
  if (!trmv_uses_splat(p)) return penumbra_run;
  splat_inputs_ = trmv_splat_planes(in, surface_, penumbra ? penumbra_.width : FloatPlane());
  time_pass("trmv_splat", [&] { splat_ = trmv_splat_pass(splat_inputs_, windows_.splat_size); });
  FloatPlane mx(in.width(), in.height()), my = mx, landed = mx;
  for (size_t i = 0; i < mx.data.size(); ++i) {
    mx.data[i] = splat_.motion.data[i].x;
    my.data[i] = splat_.motion.data[i].y;
    landed.data[i] = float(splat_.landed.data[i]);
  }
  log_pass("trmv_splat", "visibility")
      .writes(kTrmvSplatX, std::move(mx))
      .writes(kTrmvSplatY, std::move(my))
      .writes(kTrmvSplatLanded, std::move(landed))
      .pixel([this](int x, int y, Probe* probe) {
        trmv_splat_pixel(splat_inputs_, windows_.splat_size, x, y, probe);
      });
  return penumbra_run;
}

void TrmvFilter::prepare_visibility(const Frame& in) {
  using namespace layers;
  const TrmvParams& p = params_.trmv;
  visibility_.noisy = grey_plane(in.float_channel("direct.visibility"));
  const bool penumbra = p.shadow_filter == 1;
  PassRun* penumbra_run = prepare_splat(in);
  // 1. The spatial filter: the 31x31 separable joint bilateral [TRMV21 Sec. 5], or its std per pixel and axis from
  //    the splatted penumbra (penumbra.h).
  time_pass("trmv_spatial", [&] {
    if (!penumbra) {
      visibility_.filtered = bilateral(visibility_.noisy, surface_, windows_, params_.svgf);
      return;
    }
    trmv_penumbra_sigmas(splat_.carried, penumbra_.metres, kTrmvPenumbraSigmaFloor, windows_.shadow_sigma, sigma_x_,
                         sigma_y_);
    visibility_.filtered =
        trmv_spatial_pass(visibility_.noisy, surface_, windows_.shadow_radius, sigma_x_, sigma_y_, params_.svgf);
  });
  if (penumbra_run) penumbra_run->writes(kTrmvSigmaX, sigma_x_).writes(kTrmvSigmaY, sigma_y_);
  write(log_pass("trmv_spatial", "visibility"), &kTrmvVisibilitySpatial, visibility_.filtered)
      .pixel([this](int x, int y, Probe* probe) {  // the second (vertical) 1-D pass, on the first one's output
        const bool per_pixel = params_.trmv.shadow_filter == 1;
        const int r = windows_.shadow_radius;
        const RgbPlane rows = trmv_spatial_axis(visibility_.noisy, surface_, kTrmvHorizontal, r,
                                                per_pixel ? sigma_x_ : FloatPlane(), windows_.shadow_sigma,
                                                params_.svgf);
        const float sigma = per_pixel ? sigma_y_.at(x, y) : windows_.shadow_sigma;
        trmv_spatial_pixel(rows, surface_, kTrmvVertical, r, sigma, params_.svgf, x, y, probe);
      });
  // Along the splatted shadow motion with alpha^V [TRMV21 Eq. 3, Eq. 4], or along the surface motion with the
  // constant alpha.
  visibility_.motion = trmv_visibility_motion(splat_, surface_.motion, p);
  shadow_motion_ = {visibility_.motion.motion, splat_.landed, {}, {}, {}};
  receiver_ = {xyz_plane(in, "position"), xyz_plane(in, "geonormal"), surface_.mesh, surface_.motion};
  seen_prev_positions_ = std::move(prev_positions_);  // replaced after the frame by this frame's
  visibility_.alpha = {};
  if (!trmv_uses_shadow(p.motion)) return;
  time_pass("trmv_falloff", [&] {
    TrmvFalloffOutput falloff = trmv_falloff_pass(receiver_, shadow_motion_, seen_prev_positions_, p);
    visibility_.alpha = std::move(falloff.alpha_v);
    theta_ = std::move(falloff.theta);
  });
  log_pass("trmv_falloff", "visibility")
      .writes(kTrmvTheta, theta_)
      .writes(kTrmvAlphaV, visibility_.alpha)
      .pixel([this](int x, int y, Probe* probe) {
        trmv_falloff_pixel(receiver_, shadow_motion_, seen_prev_positions_, params_.trmv, x, y, probe);
      });
}

void TrmvFilter::prepare_diffuse(const Frame& in) {
  const TrmvParams& p = params_.trmv;
  diffuse_.noisy = rgb_plane(in, "indirect.diffuse");
  // 1. The spatial filter: "a 4-level a-trous wavelet filter, essentially 32x32" [TRMV21 Sec. 5] (atrous.h), each
  //    level logged on the one before; or the shadow filter's bilateral (diffuse_filter = 0, not probed).
  diffuse_levels_.clear();
  time_pass("trmv_atrous", [&] {
    if (p.diffuse_filter != 1) {
      diffuse_.filtered = bilateral(diffuse_.noisy, surface_, windows_, params_.svgf);
      return;
    }
    diffuse_levels_.reserve(size_t(windows_.atrous_levels));
    for (int level = 0; level < windows_.atrous_levels; ++level)
      diffuse_levels_.push_back(trmv_atrous_level(level == 0 ? diffuse_.noisy : diffuse_levels_.back(), surface_,
                                                  level, params_.svgf));
    diffuse_.filtered = diffuse_levels_.empty() ? diffuse_.noisy : diffuse_levels_.back();
  });
  if (diffuse_levels_.empty()) {
    log_pass("trmv_atrous", "diffuse").writes(layers::kTrmvDiffuseSpatial, diffuse_.filtered);
  } else {
    for (int level = 0; level < int(diffuse_levels_.size()); ++level) {
      PassRun& run = log_pass("trmv_atrous", "diffuse", level);
      if (level + 1 == int(diffuse_levels_.size())) run.writes(layers::kTrmvDiffuseSpatial, diffuse_.filtered);
      run.pixel([this, level](int x, int y, Probe* probe) {
        trmv_atrous_pixel(level == 0 ? diffuse_.noisy : diffuse_levels_[size_t(level - 1)], surface_, level,
                          params_.svgf, x, y, probe);
      });
    }
  }
  seen_cones_ = std::move(cones_);  // replaced below by this frame's
  diffuse_.motion = trmv_diffuse_motion(in, surface_.motion, p);
  if (!trmv_uses_dual(p.motion) || p.cones == 0) return;  // cones = 0: the colour at x^O (Fig. 6's repetition)
  // The cones: a disoccluded pixel's history re-shaded from the cones at x^O [TRMV21 Sec. 4.3, Eq. 11], each cone
  // filtered as the diffuse light is.
  dual_motion_ = {xy_plane(in, "motion.dual"), in.uint_channel("motion.dual.valid"), {}, {}, {}};
  cone_inputs_ = TrmvConeInputs::from_frame(in);
  const TrmvConeFilter filter{p.diffuse_filter == 1, windows_.atrous_levels, windows_.shadow_radius,
                              windows_.shadow_sigma};
  time_pass("trmv_reshade", [&] {
    TrmvReshadeOutput r =
        trmv_reshade_pass(cone_inputs_, surface_, dual_motion_, seen_cones_, cone_layout_, filter, p, params_.svgf);
    cones_ = std::move(r.history);
    filtered_cones_ = std::move(r.filtered);
    diffuse_.motion.reshaded = std::move(r.reshaded);
    diffuse_.motion.reshaded_valid = std::move(r.reshaded_valid);
  });
  // The diffuse light's: the re-shaded history at a disoccluded pixel.
  log_pass("trmv_reshade", "diffuse")
      .writes(layers::kTrmvDiffuseReshaded, diffuse_.motion.reshaded)
      .pixel([this](int x, int y, Probe* probe) {
        glm::vec3 reshaded;
        trmv_reshade_pixel(seen_cones_, cone_layout_, surface_, dual_motion_, trmv_cones_of(filtered_cones_, x, y),
                           params_.trmv.cone_transfer == 0, x, y, reshaded, probe);
      });
}

void TrmvFilter::prepare_glossy(const Frame& in) {
  const TrmvParams& p = params_.trmv;
  glossy_.noisy = rgb_plane(in, "indirect.glossy");
  // 1. The spatial filter: the BRDF lobe's footprint [TRMV21 Sec. 5, LLK*19] (reflection.h); or the shadow filter's
  //    bilateral (glossy_filter = 0, not probed).
  time_pass("trmv_reflection", [&] {
    if (p.glossy_filter == 1) {
      footprint_ = TrmvFootprint::from_frame(in);
      glossy_.filtered =
          trmv_reflection_pass(glossy_.noisy, surface_, footprint_, windows_.glossy_radius, params_.svgf);
    } else {
      glossy_.filtered = bilateral(glossy_.noisy, surface_, windows_, params_.svgf);
    }
  });
  PassRun& run = log_pass("trmv_reflection", "glossy").writes(layers::kTrmvGlossySpatial, glossy_.filtered);
  if (p.glossy_filter == 1)
    run.pixel([this](int x, int y, Probe* probe) {
      trmv_reflection_pixel(glossy_.noisy, surface_, footprint_, windows_.glossy_radius, params_.svgf, x, y, probe);
    });
  glossy_.motion = trmv_glossy_motion(in, surface_.motion, p);
}

Frame TrmvFilter::filter(const Frame& in, Frame* dump) {
  using namespace layers;
  times_.clear();
  const RgbPlane& history = diffuse_.history.color;
  if (history.width != 0 && (history.width != in.width() || history.height != in.height()))
    throw Error(in.source + ": frame size changed within the sequence (" + std::to_string(in.width()) + "x" +
                std::to_string(in.height()) + ", was " + std::to_string(history.width) + "x" +
                std::to_string(history.height) + ")");
  log_.begin(in.width(), in.height());
  surface_ = SurfacePlanes::from_frame(in);
  windows_ = trmv_windows(params_.trmv, in.height());

  prepare_visibility(in);
  const RgbPlane& v = filter_component(visibility_, "visibility",
                                       {&kTrmvVisibilityTemporal, &kTrmvVisibilityClamped, &kTrmvWeightA,
                                        &kTrmvVisibilityWeightC, &kTrmvVisibilityCleaned});
  prepare_diffuse(in);
  const RgbPlane& diffuse = filter_component(diffuse_, "diffuse",
                                             {&kTrmvDiffuseTemporal, &kTrmvDiffuseClamped, nullptr,
                                              &kTrmvDiffuseWeightC, &kTrmvDiffuseCleaned});
  prepare_glossy(in);
  const RgbPlane& glossy = filter_component(glossy_, "glossy",
                                            {&kTrmvGlossyTemporal, &kTrmvGlossyClamped, nullptr, &kTrmvGlossyWeightC,
                                             &kTrmvGlossyCleaned});
  prev_positions_ = {receiver_.position, receiver_.normal, surface_.mesh};

  time_pass("modulate", [&] { color_ = trmv_remodulate(in, v, diffuse, glossy); });
  time_pass("tonemap", [&] { display_ = tonemap(color_, params_.tonemap); });
  log_pass("tonemap").writes(kTonemapped, display_).pixel([this](int x, int y, Probe* probe) {
    tonemap_pixel(color_.at(x, y), params_.tonemap, probe);
  });
  if (dump) log_.dump(*dump);

  Frame out(in.width(), in.height());
  out.source = in.source;
  set_rgb_plane(out, layer_name(kColor), color_);
  set_rgb_plane(out, layer_name(kDisplay), display_);  // no TAA: the tone-mapped colour
  return out;
}

std::vector<PassUse> trmv_passes(const TrmvParams& p) {
  std::vector<PassUse> passes;
  const auto add = [&](const char* name) { passes.push_back({&find_pass(name)}); };
  if (p.shadow_filter == 1) add("trmv_penumbra");
  if (trmv_uses_splat(p)) add("trmv_splat");
  add("trmv_spatial");
  if (trmv_uses_shadow(p.motion)) add("trmv_falloff");
  add("trmv_atrous");
  if (trmv_uses_dual(p.motion) && p.cones != 0) add("trmv_reshade");
  for (const char* name : {"trmv_reflection", "trmv_temporal", "trmv_cleanup", "tonemap"}) add(name);
  return passes;
}

std::vector<std::string> TrmvFilter::probe_passes() const {
  std::vector<std::string> names;
  for (const PassUse& use : trmv_passes(params_.trmv)) names.emplace_back(use.pass->name);
  return names;
}

std::vector<std::string> TrmvFilter::dump_channels() const { return trmv_dump_channels(params_.trmv); }

std::vector<std::string> trmv_dump_channels(const TrmvParams& params) { return dump_channels_of(trmv_passes(params)); }

Probe TrmvFilter::probe(const std::string& pass, int x, int y, const std::string& stream, int level) const {
  // "direct" names the visibility, direct light's noisy part; the a-trous's level -1 is its last.
  if (pass == "trmv_atrous" && level < 0) level = windows_.atrous_levels - 1;
  return Method::probe(pass, x, y, stream == "direct" ? "visibility" : stream, level);
}

}  // namespace rtdr
