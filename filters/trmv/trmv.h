// TRMV, the whole filter [TRMV21 Sec. 3-5], as a Method (filters/method.h): filter, then accumulate, per noisy
// component, each step a pass of its own (filters/trmv/README.md):
//   visibility V (direct.visibility):  spatial.h -> falloff.h (alpha^V, with the shadow motion) -> temporal.h
//                                      along the shadow motion (or the surface motion) -> cleanup.h
//   diffuse (indirect.diffuse):        spatial.h -> temporal.h along the dual motion, whose disoccluded pixels
//                                      take their history re-shaded from the cones at x^O (reshade.h), or along
//                                      the surface motion -> cleanup.h
//   glossy (indirect.glossy):          spatial.h -> temporal.h along the glossy motion (or the surface motion)
//                                      -> cleanup.h
//   then direct = direct.shading x Vbar (the noise-free shading term, trace/README.md), indirect = diffuse +
//   glossy, remodulation with the albedo, emission added [SVGF17 Sec. 3], and tone mapping (svgf/tonemap.h).
//   TRMV has no TAA.
// This is the reverse of SVGF's order (accumulate, then filter) [TRMV21 Sec. 3].
//
// Which vector each history follows is TrmvParams::motion (`trmv:motion=NAME`): `all` (4, the default, the
// paper's) gives each component its own: the splatted shadow motion (motion/shadow_splat.h) [TRMV21 Eq. 3] with
// Eq. 4's alpha^V for the visibility, the dual motion (motion/dual.h) [TRMV21 Eq. 6] for the diffuse light, the
// glossy motion (motion/glossy.h) [TRMV21 Eq. 5] for the glossy light. `traditional` (0) drives every history with
// the back-projected surface motion [TRMV21 Eq. 1] and the constant alpha: the paper's "Trad." rows (with
// clamp_gamma = 3 and without, clamp_gamma = 0). `shadow` (1), `dual` (2) and `glossy` (3) each swap in one
// vector alone, so that a comparison changes only that vector, as the paper's figures do.
#pragma once

#include "filters/method.h"
#include "filters/surface_planes.h"
#include "filters/svgf/svgf_params.h"
#include "filters/svgf/tonemap.h"
#include "filters/trmv/cleanup.h"
#include "filters/trmv/cones.h"
#include "filters/trmv/falloff.h"
#include "filters/trmv/reshade.h"
#include "filters/trmv/temporal.h"
#include "filters/trmv/trmv_params.h"

#include <string>

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
// The glossy light's motion: the glossy vector where Eq. 5 gave one [TRMV21 Eq. 5], the surface motion elsewhere
// (motion/glossy.h).
Vec2Plane glossy_or_surface_motion(const Frame& in, const Vec2Plane& surface);

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
    TrmvHistory history;          // cbar_{i-1} and the previous id.mesh: next frame's
    TrmvHistory seen_history;     // the history the temporal pass read this frame
    RgbPlane noisy;               // the 1-spp input (visibility as (V, V, V))
    TrmvMotion motion;            // the vectors its history followed
    FloatPlane alpha;             // alpha^V (visibility), or empty: the constant alpha
    RgbPlane filtered;            // c~_i [TRMV21 Eq. 2]
    TrmvTemporalOutput temporal;  // cbar_i, the fetched and clamped histories
    TrmvCleanupOutput cleaned;    // after the clean-up [TRMV21 Eq. 7-8]
  };
  // The layers a component's passes write (filters/passes.h): the spatial filter's, the temporal pass's blend and
  // clamped history, the clean-up's w_A (the visibility's alone, else null), w_C and result.
  struct Layers {
    const LayerDecl *spatial, *temporal, *clamped, *w_a, *w_c, *cleaned;
  };
  // Runs one component's passes on c.noisy, c.motion and c.alpha, and logs them as component `name`.
  const RgbPlane& filter_component(Component& c, const std::string& name, const Layers& layers);
  // The visibility's motion and alpha^V for this frame (the falloff pass when the shadow vector drives it).
  void prepare_visibility(const Frame& in);
  // The diffuse light's motion: the dual vector, with the cones' re-shaded history (the re-shade pass).
  void prepare_diffuse(const Frame& in);

  MethodParams params_;
  SurfacePlanes surface_;
  Component visibility_, diffuse_, glossy_;
  TrmvMotion shadow_motion_;              // motion.shadow_splat and where a vector landed (.valid)
  TrmvMotion dual_motion_;                // motion.dual and where Eq. 6 applied (.valid)
  ConeLayout cone_layout_;                // six cones of half-angle cone_half_angle (cones.h)
  TrmvConeHistory cones_;                 // this frame's cones: next frame's history
  TrmvConeHistory seen_cones_;            // those the re-shade pass read this frame
  TrmvConeInputs cone_inputs_;            // this frame's path samples
  TrmvReceiver receiver_;                 // this frame's s_i, n(s_i), for Eq. 4
  TrmvPreviousPositions prev_positions_;  // the previous frame's `position` and id.mesh, for Eq. 4
  TrmvPreviousPositions seen_prev_positions_;  // those the falloff pass read this frame
  FloatPlane theta_;                      // the falloff's theta [TRMV21 Eq. 4]
  RgbPlane color_, display_;              // the remodulated colour and its tone-mapped display
};

}  // namespace rtdr
