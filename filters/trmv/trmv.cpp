// TRMV's filter as a Method. The pipeline and its order are in trmv.h; each pass's equations in its own header.
#include "filters/trmv/trmv.h"

#include "core/error.h"
#include "filters/passes.h"
#include "filters/svgf/modulate.h"
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

Vec2Plane glossy_or_surface_motion(const Frame& in, const Vec2Plane& surface) {
  Vec2Plane m = xy_plane(in, "motion.glossy");
  const UIntPlane& valid = in.uint_channel("motion.glossy.valid");
  for (size_t i = 0; i < m.data.size(); ++i)
    if (valid.data[i] == 0) m.data[i] = surface.data[i];
  return m;
}

InputChannels trmv_input_channels() {
  // Not `direct`: its direct light is the shading term times the filtered visibility. Not `indirect`: its two
  // parts follow vectors of their own.
  InputChannels c = common_input_channels(
      {"indirect.diffuse.R", "indirect.diffuse.G", "indirect.diffuse.B", "indirect.glossy.R", "indirect.glossy.G",
       "indirect.glossy.B", "position.X", "position.Y", "position.Z", "geonormal.X", "geonormal.Y", "geonormal.Z",
       "direct.shading.R", "direct.shading.G", "direct.shading.B", "direct.visibility", "motion.shadow_splat.X",
       "motion.shadow_splat.Y", "motion.dual.X", "motion.dual.Y", "motion.glossy.X", "motion.glossy.Y",
       "path.direction.X", "path.direction.Y", "path.direction.Z", "path.incoming.R", "path.incoming.G",
       "path.incoming.B", "path.pdf"});
  c.uints.insert(c.uints.end(), {"motion.shadow_splat.valid", "motion.dual.valid", "motion.glossy.valid"});
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

const RgbPlane& TrmvFilter::filter_component(Component& c, const std::string& name, const Layers& layers) {
  using namespace layers;
  const TrmvParams& p = params_.trmv;
  // A component's planes as its layers hold them: visibility travels as (V, V, V), its layers are scalar.
  const auto write = [&](PassRun& run, const LayerDecl* layer, const RgbPlane& rgb) -> PassRun& {
    if (layer->type == LayerType::Rgb) return run.writes(*layer, rgb);
    FloatPlane first(rgb.width, rgb.height);
    for (size_t i = 0; i < rgb.data.size(); ++i) first.data[i] = rgb.data[i].x;
    return run.writes(*layer, std::move(first));
  };
  // 1. The spatial filter of the current frame: c~_i.
  time_pass("trmv_spatial", [&] { c.filtered = trmv_spatial_pass(c.noisy, surface_, p, params_.svgf); });
  write(log_pass("trmv_spatial", name), layers.spatial, c.filtered)
      .pixel([this, &c](int x, int y, Probe* probe) {  // the second (vertical) 1-D pass, on the first one's output
        const TrmvParams& q = params_.trmv;
        const RgbPlane rows = trmv_spatial_axis(c.noisy, surface_, kTrmvHorizontal, q.spatial_radius, FloatPlane(),
                                                q.spatial_sigma, params_.svgf);
        trmv_spatial_pixel(rows, surface_, kTrmvVertical, q.spatial_radius, q.spatial_sigma, params_.svgf, x, y, probe);
      });
  // 2-3. The history along the component's motion, clamped to mu +- gamma sigma, blended [TRMV21 Eq. 2, Sec. 5].
  c.seen_history = std::move(c.history);  // replaced below by this frame's
  time_pass("trmv_temporal", [&] {
    c.temporal = trmv_temporal_pass(c.filtered, surface_.mesh, c.motion, c.seen_history, c.alpha, p);
  });
  PassRun& temporal = log_pass("trmv_temporal", name);
  write(temporal, layers.temporal, c.temporal.color);
  write(temporal, layers.clamped, c.temporal.clamped).pixel([this, &c](int x, int y, Probe* probe) {
    trmv_temporal_pixel(c.filtered, surface_.mesh, c.motion, c.seen_history, c.alpha, params_.trmv, x, y, probe);
  });
  // 4. The clean-up, as strong as Eq. 4 and the clamp moved the blend [TRMV21 Eq. 7-8].
  time_pass("trmv_cleanup", [&] { c.cleaned = trmv_cleanup_pass(c.temporal, c.alpha, surface_, p, params_.svgf); });
  PassRun& cleanup = log_pass("trmv_cleanup", name);
  if (layers.w_a) cleanup.writes(*layers.w_a, c.cleaned.w_a);
  cleanup.writes(*layers.w_c, c.cleaned.w_c);
  write(cleanup, layers.cleaned, c.cleaned.color).pixel([this, &c](int x, int y, Probe* probe) {
    trmv_cleanup_weights_pixel(c.temporal, c.alpha, params_.trmv, x, y, probe);
  });
  // Next frame's history: before the clean-up unless asked otherwise (history_after_cleanup).
  c.history.color = p.history_after_cleanup != 0 ? c.cleaned.color : c.temporal.color;
  c.history.mesh = surface_.mesh;
  return c.cleaned.color;
}

void TrmvFilter::prepare_visibility(const Frame& in) {
  const TrmvParams& p = params_.trmv;
  // Along the shadow motion with alpha^V [TRMV21 Eq. 3, Eq. 4], or along the surface motion with the constant
  // alpha. A pixel on which no shadow vector landed has the surface motion in motion.shadow_splat.
  shadow_motion_ = {xy_plane(in, "motion.shadow_splat"), in.uint_channel("motion.shadow_splat.valid"), {}, {}};
  receiver_ = {xyz_plane(in, "position"), xyz_plane(in, "geonormal"), surface_.mesh};
  seen_prev_positions_ = std::move(prev_positions_);  // replaced after the frame by this frame's
  visibility_.alpha = {};
  if (trmv_uses_shadow(p.motion)) {
    time_pass("trmv_falloff", [&] {
      TrmvFalloffOutput falloff = trmv_falloff_pass(receiver_, shadow_motion_, seen_prev_positions_, p);
      visibility_.alpha = std::move(falloff.alpha_v);
      theta_ = std::move(falloff.theta);
    });
    log_pass("trmv_falloff", "visibility")
        .writes(layers::kTrmvTheta, theta_)
        .writes(layers::kTrmvAlphaV, visibility_.alpha)
        .pixel([this](int x, int y, Probe* probe) {
          trmv_falloff_pixel(receiver_, shadow_motion_, seen_prev_positions_, params_.trmv, x, y, probe);
        });
  }
  visibility_.noisy = grey_plane(in.float_channel("direct.visibility"));
  visibility_.motion = {trmv_uses_shadow(p.motion) ? shadow_motion_.motion : surface_.motion, {}, {}, {}};
}

void TrmvFilter::prepare_diffuse(const Frame& in) {
  const TrmvParams& p = params_.trmv;
  diffuse_.noisy = rgb_plane(in, "indirect.diffuse");
  seen_cones_ = std::move(cones_);  // replaced below by this frame's
  if (!trmv_uses_dual(p.motion)) {
    diffuse_.motion = {surface_.motion, {}, {}, {}};
    return;
  }
  // Along the dual motion [TRMV21 Eq. 6]: x^O at disoccluded pixels, the surface motion elsewhere (motion/dual.h).
  dual_motion_ = {xy_plane(in, "motion.dual"), in.uint_channel("motion.dual.valid"), {}, {}};
  diffuse_.motion = {dual_motion_.motion, {}, {}, {}};
  if (p.cones == 0) return;  // the colour at x^O (Fig. 6's repetition)
  // The cones: a disoccluded pixel's history re-shaded from the cones at x^O [TRMV21 Sec. 4.3, Eq. 11].
  cone_inputs_ = TrmvConeInputs::from_frame(in);
  time_pass("trmv_reshade", [&] {
    TrmvReshadeOutput r =
        trmv_reshade_pass(cone_inputs_, surface_, dual_motion_, seen_cones_, cone_layout_, p, params_.svgf);
    cones_ = std::move(r.history);
    diffuse_.motion.reshaded = std::move(r.reshaded);
    diffuse_.motion.reshaded_valid = std::move(r.reshaded_valid);
  });
  // The diffuse light's: the re-shaded history at a disoccluded pixel.
  log_pass("trmv_reshade", "diffuse")
      .writes(layers::kTrmvDiffuseReshaded, diffuse_.motion.reshaded)
      .pixel([this](int x, int y, Probe* probe) {
        glm::vec3 reshaded;
        trmv_reshade_pixel(seen_cones_, cone_layout_, surface_, dual_motion_, x, y, reshaded, probe);
      });
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
  const TrmvParams& p = params_.trmv;

  prepare_visibility(in);
  const RgbPlane& v = filter_component(visibility_, "visibility",
                                       {&kTrmvVisibilitySpatial, &kTrmvVisibilityTemporal, &kTrmvVisibilityClamped,
                                        &kTrmvWeightA, &kTrmvVisibilityWeightC, &kTrmvVisibilityCleaned});
  prepare_diffuse(in);
  const RgbPlane& diffuse = filter_component(diffuse_, "diffuse",
                                             {&kTrmvDiffuseSpatial, &kTrmvDiffuseTemporal, &kTrmvDiffuseClamped,
                                              nullptr, &kTrmvDiffuseWeightC, &kTrmvDiffuseCleaned});
  glossy_.noisy = rgb_plane(in, "indirect.glossy");
  glossy_.motion = {trmv_uses_glossy(p.motion) ? glossy_or_surface_motion(in, surface_.motion) : surface_.motion,
                    {}, {}, {}};
  const RgbPlane& glossy = filter_component(glossy_, "glossy",
                                            {&kTrmvGlossySpatial, &kTrmvGlossyTemporal, &kTrmvGlossyClamped, nullptr,
                                             &kTrmvGlossyWeightC, &kTrmvGlossyCleaned});
  prev_positions_ = {receiver_.position, surface_.mesh};

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
  std::vector<PassUse> passes = {{&find_pass("trmv_spatial")}};
  if (trmv_uses_shadow(p.motion)) passes.push_back({&find_pass("trmv_falloff")});
  if (trmv_uses_dual(p.motion) && p.cones != 0) passes.push_back({&find_pass("trmv_reshade")});
  for (const char* name : {"trmv_temporal", "trmv_cleanup", "tonemap"}) passes.push_back({&find_pass(name)});
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
  // "direct" names the visibility, direct light's noisy part.
  return Method::probe(pass, x, y, stream == "direct" ? "visibility" : stream, level);
}

}  // namespace rtdr
