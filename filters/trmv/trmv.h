// TRMV, the whole filter [TRMV21 Sec. 3-5], as a Method (filters/method.h): filter, then accumulate, per noisy
// component, each with a spatial filter of its own [TRMV21 Sec. 5, "Choice of spatial filters"] and each step a
// pass of its own (filters/trmv/README.md); windows are the paper's 1080p pixels scaled to the frame (footprint.h):
//   visibility V (direct.visibility):  splat.h (the shadow motion m^V spread to the pixels around each shadow,
//                                      with the penumbra's width W from penumbra.h when shadow_filter = 1) ->
//                                      spatial.h (the 31x31 separable joint bilateral, or its std from the
//                                      penumbra) -> falloff.h (alpha^V) -> temporal.h along the splatted shadow
//                                      motion (or the surface motion) -> cleanup.h
//   diffuse (indirect.diffuse):        atrous.h (4 levels of a 3x3 kernel, w_z w_n) -> temporal.h along the dual
//                                      motion, whose disoccluded pixels take their history re-shaded from the cones
//                                      at x^O (reshade.h; each cone a-trous filtered), or along the surface motion
//                                      -> cleanup.h
//   glossy (indirect.glossy):          reflection.h (the BRDF lobe's footprint [LLK*19]) -> temporal.h along the
//                                      glossy motion (or the surface motion) -> cleanup.h
//   then direct = direct.shading x Vbar (the noise-free shading term, trace/README.md), indirect = diffuse +
//   glossy, remodulation with the albedo, emission added [SVGF17 Sec. 3], and tone mapping (svgf/tonemap.h).
//   TRMV has no TAA.
// This is the reverse of SVGF's order (accumulate, then filter) [TRMV21 Sec. 3].
//
// Which vector each history follows is TrmvParams::motion (`trmv:motion=NAME`): `all` (4, the default, the
// paper's) gives each component its own: the splatted shadow motion [TRMV21 Eq. 3] with Eq. 4's alpha^V for the
// visibility, the dual motion (motion/dual.h) [TRMV21 Eq. 6] for the diffuse light, the glossy motion
// (motion/glossy.h) [TRMV21 Eq. 5] for the glossy light. `traditional` (0) drives every history with the
// back-projected surface motion [TRMV21 Eq. 1] and the constant alpha: the paper's "Trad." rows.
// `shadow` (1), `dual` (2) and `glossy` (3) each swap in one vector alone, so that a comparison changes only that
// vector, as the paper's figures do. Each vector's history passes its own test (temporal.h; history_test = 0 is
// forced reuse, the "Trad. (No clamp)" row).
#pragma once

#include "filters/method.h"
#include "filters/surface_planes.h"
#include "filters/svgf/svgf_params.h"
#include "filters/svgf/tonemap.h"
#include "filters/trmv/cleanup.h"
#include "filters/trmv/cones.h"
#include "filters/trmv/falloff.h"
#include "filters/trmv/footprint.h"
#include "filters/trmv/penumbra.h"
#include "filters/trmv/reflection.h"
#include "filters/trmv/reshade.h"
#include "filters/trmv/splat.h"
#include "filters/trmv/temporal.h"
#include "filters/trmv/trmv_params.h"

#include <string>
#include <vector>

namespace rtdr {

// The channels trmv reads from each input frame.
InputChannels trmv_input_channels();
// The passes trmv runs with these parameters, in order (filters/passes.h), and the channels of their dump layers
// and the tone-mapped colour: what both back ends dump (TrmvFilter, gpu/trmv_vulkan.h).
std::vector<PassUse> trmv_passes(const TrmvParams& params);
std::vector<std::string> trmv_dump_channels(const TrmvParams& params);
// The colour from the three filtered components: direct = direct.shading x V, indirect = diffuse + glossy,
// remodulated with the albedo, emission added [TRMV21 Sec. 4.1] [SVGF17 Sec. 3]. `visibility` is (V, V, V).
RgbPlane trmv_remodulate(const Frame& in, const RgbPlane& visibility, const RgbPlane& diffuse, const RgbPlane& glossy);
// Each component's vectors and their history tests (temporal.h) under `params`, from the frame and the splat:
// the splatted shadow motion where a vector landed (no test, or the same mesh with shadow_receiver_test), else the
// surface motion (SVGF's test); the dual motion (the same mesh where Eq. 6 applied, SVGF's test elsewhere); the
// glossy motion (Eq. 5's draw, or its centre mu with glossy_draw = 0; the same mesh) where Eq. 5 gave one, else
// the surface motion. history_test = 0: no test anywhere. The Vulkan method reads the same.
TrmvMotion trmv_visibility_motion(const TrmvSplatOutput& splat, const Vec2Plane& surface, const TrmvParams& params);
TrmvMotion trmv_diffuse_motion(const Frame& in, const Vec2Plane& surface, const TrmvParams& params);
TrmvMotion trmv_glossy_motion(const Frame& in, const Vec2Plane& surface, const TrmvParams& params);
// The splat's planes from a frame: motion.shadow and .valid, `motion`, id.instance, `normal`, and `carried`.
TrmvSplatPlanes trmv_splat_planes(const Frame& in, const SurfacePlanes& surface, FloatPlane carried);
// Whether the splat runs: the shadow vector drives the visibility, or the penumbra filter needs its W.
bool trmv_uses_splat(const TrmvParams& params);

class TrmvFilter : public Method {
 public:
  explicit TrmvFilter(const MethodParams& params);
  std::string name() const override { return "trmv"; }
  Frame filter(const Frame& in, Frame* dump) override;
  void reset() override;
  std::unique_ptr<Method> clone() const override { return std::make_unique<TrmvFilter>(*this); }
  // `stream` is the component: "visibility" (or "direct", whose noisy part it is), "diffuse" or "glossy"; `level`
  // is unused. The pass log's probe (filters/pass_log.h).
  Probe probe(const std::string& pass, int x, int y, const std::string& stream, int level) const override;
  std::vector<std::string> probe_passes() const override;
  InputChannels inputs() const override { return trmv_input_channels(); }
  std::vector<std::string> dump_channels() const override;

 private:
  // One noisy component: its history, and what each of its passes saw and made this frame (for the probe).
  struct Component {
    TrmvHistory history;          // cbar_{i-1} and the previous G-buffer: next frame's
    TrmvHistory seen_history;     // the history the temporal pass read this frame
    RgbPlane noisy;               // the 1-spp input (visibility as (V, V, V))
    TrmvMotion motion;            // the vectors its history followed
    FloatPlane alpha;             // alpha^V (visibility), or empty: the constant alpha
    RgbPlane filtered;            // c~_i [TRMV21 Eq. 2]
    TrmvTemporalOutput temporal;  // cbar_i, the fetched and clamped histories
    TrmvCleanupOutput cleaned;    // after the clean-up [TRMV21 Eq. 7-8]
  };
  // The layers a component's temporal and clean-up passes write (filters/passes.h): the blend and clamped history,
  // the clean-up's w_A (the visibility's alone, else null), w_C and result.
  struct Layers {
    const LayerDecl *temporal, *clamped, *w_a, *w_c, *cleaned;
  };
  // Runs one component's temporal and clean-up passes on c.filtered, c.motion and c.alpha, and logs them as
  // component `name`.
  const RgbPlane& filter_component(Component& c, const std::string& name, const Layers& layers);
  // The visibility's splat, spatial filter, motion and alpha^V for this frame (the penumbra, splat, spatial and
  // falloff passes).
  void prepare_visibility(const Frame& in);
  // Its penumbra (shadow_filter = 1) and splat passes; returns the penumbra's log entry (null without it), to which
  // the spatial pass adds the std per axis.
  PassRun* prepare_splat(const Frame& in);
  // The diffuse light's spatial filter and motion: the dual vector, with the cones' re-shaded history (the
  // a-trous and re-shade passes).
  void prepare_diffuse(const Frame& in);
  // The glossy light's spatial filter and motion (the reflection pass).
  void prepare_glossy(const Frame& in);

  MethodParams params_;
  SurfacePlanes surface_;
  TrmvWindows windows_;                   // this frame's windows (footprint.h)
  TrmvParams cleanup_params_;             // params_.trmv with the clean-up's window at this frame's size
  Component visibility_, diffuse_, glossy_;
  TrmvPenumbraInputs penumbra_inputs_;    // this frame's light samples and receivers (penumbra.h)
  TrmvPenumbraOutput penumbra_;           // W and the metres per pixel (shadow_filter = 1)
  TrmvSplatPlanes splat_inputs_;          // what the splat read
  TrmvSplatOutput splat_;                 // the splatted shadow motion and W
  FloatPlane sigma_x_, sigma_y_;          // the penumbra filter's std per pixel (shadow_filter = 1)
  std::vector<RgbPlane> diffuse_levels_;  // the diffuse light's a-trous levels (diffuse_filter = 1), for the probe
  TrmvFootprint footprint_;               // the glossy lobe's footprint (glossy_filter = 1)
  TrmvMotion shadow_motion_;              // the splatted shadow motion and where a vector landed (.valid)
  TrmvMotion dual_motion_;                // motion.dual and where Eq. 6 applied (.valid)
  ConeLayout cone_layout_;                // six cones of half-angle cone_half_angle (cones.h)
  TrmvConeHistory cones_;                 // this frame's cones: next frame's history
  TrmvConeHistory seen_cones_;            // those the re-shade pass read this frame
  TrmvConeInputs cone_inputs_;            // this frame's path samples
  std::array<RgbPlane, kConeCount> filtered_cones_;  // this frame's L~_k (the re-shade pass's), for the probe
  TrmvReceiver receiver_;                 // this frame's s_i, n(s_i), for Eq. 4
  TrmvPreviousPositions prev_positions_;  // the previous frame's `position`, `geonormal` and id.mesh, for Eq. 4
  TrmvPreviousPositions seen_prev_positions_;  // those the falloff pass read this frame
  FloatPlane theta_;                      // the falloff's theta [TRMV21 Eq. 4]
  RgbPlane color_, display_;              // the remodulated colour and its tone-mapped display
};

}  // namespace rtdr
