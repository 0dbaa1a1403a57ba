// TRMV's filter as a Method. The pipeline and its order are in trmv.h; each pass's equations in its own header.
#include "filters/trmv/trmv.h"

#include "core/error.h"
#include "filters/svgf/modulate.h"
#include "filters/trmv/spatial.h"

#include <string>

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

InputChannels trmv_input_channels() {
  InputChannels c;
  c.floats = {"depth.Z",      "depth.dX",     "depth.dY",     "normal.X",     "normal.Y",     "normal.Z",
              "motion.X",     "motion.Y",     "albedo.R",     "albedo.G",     "albedo.B",     "emission.R",
              "emission.G",   "emission.B",   "indirect.R",   "indirect.G",   "indirect.B",   "position.X",
              "position.Y",   "position.Z",   "geonormal.X",  "geonormal.Y",  "geonormal.Z",  "direct.shading.R",
              "direct.shading.G", "direct.shading.B", "direct.visibility", "motion.shadow_splat.X",
              "motion.shadow_splat.Y"};
  c.uints = {"id.mesh", "motion.shadow_splat.valid"};
  for (const char* channel : {"emission.R", "emission.G", "emission.B", "indirect.R", "indirect.G", "indirect.B"})
    c.defaults[channel] = 0.0f;
  return c;
}

TrmvFilter::TrmvFilter(const MethodParams& params) : params_(params) {
  validate(params_.trmv);
  validate(params_.svgf);
  validate(params_.tonemap);
}

void TrmvFilter::reset() {
  visibility_ = {};
  indirect_ = {};
  prev_positions_ = {};
}

const RgbPlane& TrmvFilter::filter_component(Component& c, const RgbPlane& noisy, const TrmvMotion& motion,
                                             const FloatPlane& alpha) {
  const TrmvParams& p = params_.trmv;
  // 1. The spatial filter of the current frame: c~_i.
  time_pass("spatial", [&] { c.filtered = trmv_spatial_pass(noisy, surface_, p, params_.svgf); });
  // 2-3. The history along the component's motion, clamped to mu +- gamma sigma, blended [TRMV21 Eq. 2, Sec. 5].
  time_pass("temporal", [&] { c.temporal = trmv_temporal_pass(c.filtered, surface_.mesh, motion, c.history, alpha, p); });
  // 4. The clean-up, as strong as Eq. 4 and the clamp moved the blend [TRMV21 Eq. 7-8].
  time_pass("cleanup", [&] { c.cleaned = trmv_cleanup_pass(c.temporal, alpha, surface_, p, params_.svgf); });
  // Next frame's history: before the clean-up unless asked otherwise (history_after_cleanup).
  c.history.color = p.history_after_cleanup != 0 ? c.cleaned.color : c.temporal.color;
  c.history.mesh = surface_.mesh;
  return c.cleaned.color;
}

Frame TrmvFilter::filter(const Frame& in, Frame* dump) {
  times_.clear();
  const RgbPlane& history = indirect_.history.color;
  if (history.width != 0 && (history.width != in.width() || history.height != in.height()))
    throw Error(in.source + ": frame size changed within the sequence (" + std::to_string(in.width()) + "x" +
                std::to_string(in.height()) + ", was " + std::to_string(history.width) + "x" +
                std::to_string(history.height) + ")");
  if (dump && (dump->width() != in.width() || dump->height() != in.height())) *dump = Frame(in.width(), in.height());
  surface_ = SurfacePlanes::from_frame(in);
  const TrmvParams& p = params_.trmv;

  // Visibility: along the shadow motion with alpha^V [TRMV21 Eq. 3, Eq. 4], or along the surface motion.
  const TrmvMotion surface_motion{surface_.motion, {}};
  const TrmvMotion shadow_motion{xy_plane(in, "motion.shadow_splat"), in.uint_channel("motion.shadow_splat.valid")};
  FloatPlane alpha_v;  // empty: the constant alpha
  if (p.motion == 1) {
    const TrmvReceiver receiver{xyz_plane(in, "position"), xyz_plane(in, "geonormal"), surface_.mesh};
    time_pass("falloff", [&] { alpha_v = trmv_falloff_pass(receiver, shadow_motion, prev_positions_, p).alpha_v; });
  }
  // A pixel whose shadow motion is the surface motion (no splat landed) keeps its history along it.
  const TrmvMotion visibility_motion{p.motion == 1 ? shadow_motion.motion : surface_.motion, {}};
  const RgbPlane& v = filter_component(visibility_, grey_plane(in.float_channel("direct.visibility")),
                                       visibility_motion, alpha_v);
  const RgbPlane& indirect = filter_component(indirect_, rgb_plane(in, "indirect"), surface_motion, {});
  prev_positions_ = {xyz_plane(in, "position"), surface_.mesh};

  RgbPlane color, display;
  time_pass("modulate", [&] {
    color = remodulate(shade(rgb_plane(in, "direct.shading"), v), indirect, rgb_plane(in, "albedo"),
                       rgb_plane(in, "emission"));
  });
  time_pass("tonemap", [&] { display = tonemap(color, params_.tonemap); });

  Frame out(in.width(), in.height());
  out.source = in.source;
  set_rgb_plane(out, "color", color);
  set_rgb_plane(out, "display", display);
  return out;
}

Probe TrmvFilter::probe(const std::string& pass, int, int, const std::string&, int) const {
  throw Error("rtdr probe does not cover method trmv's passes yet (pass '" + pass + "')");
}

}  // namespace rtdr
