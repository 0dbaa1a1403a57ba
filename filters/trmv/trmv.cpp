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

}  // namespace

const RgbPlane& TrmvFilter::filter_component(Component& c) {
  const TrmvParams& p = params_.trmv;
  // 2-3. The history along the component's motion, tested, clamped to mu +- gamma sigma, blended [TRMV21 Eq. 2,
  // Sec. 5].
  c.seen_history = std::move(c.history);  // replaced below by this frame's
  time_pass("trmv_temporal", [&] {
    c.temporal = trmv_temporal_pass(c.filtered, surface_, c.motion, c.seen_history, c.alpha, p, params_.svgf);
  });
  // 4. The clean-up, as strong as Eq. 4 and the clamp moved the blend [TRMV21 Eq. 7-8], at its scaled window.
  TrmvParams cleanup = p;
  cleanup.cleanup_size = 2 * windows_.cleanup_radius + 1;
  time_pass("trmv_cleanup",
            [&] { c.cleaned = trmv_cleanup_pass(c.temporal, c.alpha, surface_, cleanup, params_.svgf); });
  // Next frame's history: before the clean-up unless asked otherwise (history_after_cleanup).
  c.history.color = p.history_after_cleanup != 0 ? c.cleaned.color : c.temporal.color;
  c.history.surface = surface_;
  return c.cleaned.color;
}

void TrmvFilter::prepare_visibility(const Frame& in, FloatPlane& theta) {
  const TrmvParams& p = params_.trmv;
  visibility_.noisy = grey_plane(in.float_channel("direct.visibility"));
  // The penumbra's width W at every in-shadow pixel [LLK*19] (shadow_filter = 1), which the splat carries.
  const bool penumbra = p.shadow_filter == 1;
  if (penumbra) {
    penumbra_inputs_ = TrmvPenumbraInputs::from_frame(in);
    time_pass("trmv_penumbra", [&] { penumbra_ = trmv_penumbra_pass(penumbra_inputs_); });
  }
  // The splat: m^V (and W) spread over the shadow filter's window, on each receiving surface [TRMV21 Sec. 4.1].
  splat_ = {};
  if (trmv_uses_splat(p)) {
    splat_inputs_ = trmv_splat_planes(in, surface_, penumbra ? penumbra_.width : FloatPlane());
    time_pass("trmv_splat", [&] { splat_ = trmv_splat_pass(splat_inputs_, windows_.splat_size); });
  }
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
  // Along the splatted shadow motion with alpha^V [TRMV21 Eq. 3, Eq. 4], or along the surface motion with the
  // constant alpha.
  visibility_.motion = trmv_visibility_motion(splat_, surface_.motion, p);
  shadow_motion_ = {visibility_.motion.motion, splat_.landed, {}, {}, {}};
  receiver_ = {xyz_plane(in, "position"), xyz_plane(in, "geonormal"), surface_.mesh, surface_.motion};
  seen_prev_positions_ = std::move(prev_positions_);  // replaced after the frame by this frame's
  visibility_.alpha = {};
  if (trmv_uses_shadow(p.motion))
    time_pass("trmv_falloff", [&] {
      TrmvFalloffOutput falloff = trmv_falloff_pass(receiver_, shadow_motion_, seen_prev_positions_, p);
      visibility_.alpha = std::move(falloff.alpha_v);
      theta = std::move(falloff.theta);
    });
}

void TrmvFilter::prepare_diffuse(const Frame& in) {
  const TrmvParams& p = params_.trmv;
  diffuse_.noisy = rgb_plane(in, "indirect.diffuse");
  // 1. The spatial filter: "a 4-level a-trous wavelet filter, essentially 32x32" [TRMV21 Sec. 5] (atrous.h).
  time_pass("trmv_atrous", [&] {
    diffuse_.filtered = p.diffuse_filter == 1
                            ? trmv_atrous_pass(diffuse_.noisy, surface_, windows_.atrous_levels, params_.svgf)
                            : bilateral(diffuse_.noisy, surface_, windows_, params_.svgf);
  });
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
}

void TrmvFilter::prepare_glossy(const Frame& in) {
  const TrmvParams& p = params_.trmv;
  glossy_.noisy = rgb_plane(in, "indirect.glossy");
  // 1. The spatial filter: the BRDF lobe's footprint [TRMV21 Sec. 5, LLK*19] (reflection.h).
  time_pass("trmv_reflection", [&] {
    if (p.glossy_filter == 1) {
      footprint_ = TrmvFootprint::from_frame(in);
      glossy_.filtered =
          trmv_reflection_pass(glossy_.noisy, surface_, footprint_, windows_.glossy_radius, params_.svgf);
    } else {
      glossy_.filtered = bilateral(glossy_.noisy, surface_, windows_, params_.svgf);
    }
  });
  glossy_.motion = trmv_glossy_motion(in, surface_.motion, p);
}

Frame TrmvFilter::filter(const Frame& in, Frame* dump) {
  times_.clear();
  const RgbPlane& history = diffuse_.history.color;
  if (history.width != 0 && (history.width != in.width() || history.height != in.height()))
    throw Error(in.source + ": frame size changed within the sequence (" + std::to_string(in.width()) + "x" +
                std::to_string(in.height()) + ", was " + std::to_string(history.width) + "x" +
                std::to_string(history.height) + ")");
  if (dump && (dump->width() != in.width() || dump->height() != in.height())) *dump = Frame(in.width(), in.height());
  surface_ = SurfacePlanes::from_frame(in);
  windows_ = trmv_windows(params_.trmv, in.height());

  FloatPlane theta;
  prepare_visibility(in, theta);
  const RgbPlane& v = filter_component(visibility_);
  prepare_diffuse(in);
  const RgbPlane& diffuse = filter_component(diffuse_);
  prepare_glossy(in);
  const RgbPlane& glossy = filter_component(glossy_);
  prev_positions_ = {receiver_.position, receiver_.normal, surface_.mesh};

  RgbPlane color, display;
  time_pass("modulate", [&] { color = trmv_remodulate(in, v, diffuse, glossy); });
  time_pass("tonemap", [&] { display = tonemap(color, params_.tonemap); });
  this->dump(dump, theta, display);

  Frame out(in.width(), in.height());
  out.source = in.source;
  set_rgb_plane(out, layer_name(layers::kColor), color);
  set_rgb_plane(out, layer_name(layers::kDisplay), display);  // no TAA: the tone-mapped colour
  return out;
}

void TrmvFilter::dump(Frame* dump, const FloatPlane& theta, const RgbPlane& tonemapped) const {
  if (!dump) return;
  using namespace layers;
  const TrmvParams& p = params_.trmv;
  const auto first = [](const RgbPlane& rgb) {  // visibility travels as (V, V, V)
    FloatPlane out(rgb.width, rgb.height);
    for (size_t i = 0; i < rgb.data.size(); ++i) out.data[i] = rgb.data[i].x;
    return out;
  };
  if (p.shadow_filter == 1) {
    dump_layer(dump, kTrmvPenumbraWidth, {}, -1, penumbra_.width);
    dump_layer(dump, kTrmvSigmaX, {}, -1, sigma_x_);
    dump_layer(dump, kTrmvSigmaY, {}, -1, sigma_y_);
  }
  if (trmv_uses_splat(p)) {
    FloatPlane mx(splat_.motion.width, splat_.motion.height), my = mx, landed = mx;
    for (size_t i = 0; i < mx.data.size(); ++i)
      mx.data[i] = splat_.motion.data[i].x, my.data[i] = splat_.motion.data[i].y, landed.data[i] = float(splat_.landed.data[i]);
    dump_layer(dump, kTrmvSplatX, {}, -1, mx);
    dump_layer(dump, kTrmvSplatY, {}, -1, my);
    dump_layer(dump, kTrmvSplatLanded, {}, -1, landed);
  }
  dump_layer(dump, kTrmvVisibilitySpatial, {}, -1, first(visibility_.filtered));
  dump_layer(dump, kTrmvDiffuseSpatial, {}, -1, diffuse_.filtered);
  dump_layer(dump, kTrmvGlossySpatial, {}, -1, glossy_.filtered);
  if (trmv_uses_shadow(p.motion)) {
    dump_layer(dump, kTrmvTheta, {}, -1, theta);
    dump_layer(dump, kTrmvAlphaV, {}, -1, visibility_.alpha);
  }
  if (trmv_uses_dual(p.motion) && p.cones != 0) dump_layer(dump, kTrmvDiffuseReshaded, {}, -1, diffuse_.motion.reshaded);
  dump_layer(dump, kTrmvWeightA, {}, -1, visibility_.cleaned.w_a);
  dump_layer(dump, kTrmvVisibilityTemporal, {}, -1, first(visibility_.temporal.color));
  dump_layer(dump, kTrmvVisibilityClamped, {}, -1, first(visibility_.temporal.clamped));
  dump_layer(dump, kTrmvDiffuseTemporal, {}, -1, diffuse_.temporal.color);
  dump_layer(dump, kTrmvDiffuseClamped, {}, -1, diffuse_.temporal.clamped);
  dump_layer(dump, kTrmvGlossyTemporal, {}, -1, glossy_.temporal.color);
  dump_layer(dump, kTrmvGlossyClamped, {}, -1, glossy_.temporal.clamped);
  dump_layer(dump, kTrmvVisibilityWeightC, {}, -1, visibility_.cleaned.w_c);
  dump_layer(dump, kTrmvDiffuseWeightC, {}, -1, diffuse_.cleaned.w_c);
  dump_layer(dump, kTrmvGlossyWeightC, {}, -1, glossy_.cleaned.w_c);
  dump_layer(dump, kTrmvVisibilityCleaned, {}, -1, first(visibility_.cleaned.color));
  dump_layer(dump, kTrmvDiffuseCleaned, {}, -1, diffuse_.cleaned.color);
  dump_layer(dump, kTrmvGlossyCleaned, {}, -1, glossy_.cleaned.color);
  dump_layer(dump, kTonemapped, {}, -1, tonemapped);
}

std::vector<std::string> trmv_passes(const TrmvParams& p) {
  std::vector<std::string> passes;
  if (p.shadow_filter == 1) passes.push_back("trmv_penumbra");
  if (trmv_uses_splat(p)) passes.push_back("trmv_splat");
  passes.push_back("trmv_spatial");
  if (trmv_uses_shadow(p.motion)) passes.push_back("trmv_falloff");
  passes.push_back("trmv_atrous");
  if (trmv_uses_dual(p.motion) && p.cones != 0) passes.push_back("trmv_reshade");
  passes.insert(passes.end(), {"trmv_reflection", "trmv_temporal", "trmv_cleanup"});
  return passes;
}

std::vector<std::string> TrmvFilter::probe_passes() const { return trmv_passes(params_.trmv); }

std::vector<std::string> TrmvFilter::dump_channels() const { return trmv_dump_channels(params_.trmv); }

std::vector<std::string> trmv_dump_channels(const TrmvParams& params) {
  std::vector<std::string> channels;
  for (const std::string& name : trmv_passes(params))
    for (const LayerDecl* layer : find_pass(name).writes)
      for (std::string& c : layer_channels(*layer)) channels.push_back(std::move(c));
  for (std::string& c : layer_channels(layers::kTonemapped)) channels.push_back(std::move(c));
  return channels;
}

const TrmvFilter::Component& TrmvFilter::component(const std::string& stream) const {
  if (stream == "visibility" || stream == "direct") return visibility_;  // direct's noisy part is its visibility
  if (stream == "diffuse") return diffuse_;
  if (stream == "glossy") return glossy_;
  throw Error("--stream '" + stream + "' is not one of trmv's components: visibility (or direct), diffuse, glossy");
}

Probe TrmvFilter::probe(const std::string& pass, int x, int y, const std::string& stream, int level) const {
  const std::vector<std::string> passes = probe_passes();
  if (std::find(passes.begin(), passes.end(), pass) == passes.end()) {
    find_pass(pass);  // throws, listing the passes, when there is no such pass at all
    throw Error("method trmv does not run pass '" + pass + "' with these parameters");
  }
  if (surface_.width() == 0) throw Error("probe: no frame has been filtered yet");
  if (x < 0 || y < 0 || x >= surface_.width() || y >= surface_.height())
    throw Error("--pixel " + std::to_string(x) + "," + std::to_string(y) + " is outside the " +
                std::to_string(surface_.width()) + "x" + std::to_string(surface_.height()) + " frame");
  // Re-run the pass's golden per-pixel function on exactly the inputs it saw, with the probe attached.
  const TrmvParams& p = params_.trmv;
  const Component& c = component(stream);
  const SvgfParams& edges = params_.svgf;
  Probe probe;
  if (pass == "trmv_penumbra") {
    float width;
    glm::vec2 metres;
    trmv_penumbra_pixel(penumbra_inputs_, trmv_light_diameters(penumbra_inputs_.light, penumbra_inputs_.light_id), x,
                        y, width, metres, &probe);
  }
  if (pass == "trmv_splat") trmv_splat_pixel(splat_inputs_, windows_.splat_size, x, y, &probe);
  if (pass == "trmv_spatial") {  // the visibility's; the second (vertical) 1-D pass, on the first one's output
    const int r = windows_.shadow_radius;
    const bool per_pixel = p.shadow_filter == 1;
    const RgbPlane rows = trmv_spatial_axis(visibility_.noisy, surface_, kTrmvHorizontal, r,
                                            per_pixel ? sigma_x_ : FloatPlane(), windows_.shadow_sigma, edges);
    const float sigma = per_pixel ? sigma_y_.at(x, y) : windows_.shadow_sigma;
    trmv_spatial_pixel(rows, surface_, kTrmvVertical, r, sigma, edges, x, y, &probe);
  }
  if (pass == "trmv_falloff") trmv_falloff_pixel(receiver_, shadow_motion_, seen_prev_positions_, p, x, y, &probe);
  if (pass == "trmv_atrous") {  // the diffuse light's, at `level` (the last by default), on the levels before it
    const int last = windows_.atrous_levels - 1, at = level < 0 ? last : std::min(level, last);
    if (p.diffuse_filter == 1)
      trmv_atrous_pixel(trmv_atrous_pass(diffuse_.noisy, surface_, at, edges), surface_, at, edges, x, y, &probe);
  }
  if (pass == "trmv_reshade") {  // the diffuse light's: the re-shaded history at a disoccluded pixel
    glm::vec3 reshaded;
    trmv_reshade_pixel(seen_cones_, cone_layout_, surface_, dual_motion_, trmv_cones_of(filtered_cones_, x, y),
                       p.cone_transfer == 0, x, y, reshaded, &probe);
  }
  if (pass == "trmv_reflection" && p.glossy_filter == 1)
    trmv_reflection_pixel(glossy_.noisy, surface_, footprint_, windows_.glossy_radius, edges, x, y, &probe);
  if (pass == "trmv_temporal")
    trmv_temporal_pixel(c.filtered, surface_, c.motion, c.seen_history, c.alpha, p, edges, x, y, &probe);
  if (pass == "trmv_cleanup") trmv_cleanup_weights_pixel(c.temporal, c.alpha, p, x, y, &probe);
  return probe;
}

}  // namespace rtdr
