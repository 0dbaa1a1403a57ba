// TRMV, the whole filter [TRMV21 Sec. 3-5], as a Method (filters/method.h): filter, then accumulate, per noisy
// component, each step a pass of its own (filters/trmv/README.md):
//   visibility V (direct.visibility):  spatial.h -> falloff.h (alpha^V, with the shadow motion) -> temporal.h
//                                      along the shadow motion (or the surface motion) -> cleanup.h
//   indirect (indirect):               spatial.h -> temporal.h along the surface motion -> cleanup.h
//   then direct = direct.shading x Vbar (the noise-free shading term, trace/README.md), remodulation with the
//   albedo, emission added [SVGF17 Sec. 3], and tone mapping (svgf/tonemap.h). TRMV has no TAA.
// This is the reverse of SVGF's order (accumulate, then filter) [TRMV21 Sec. 3].
//
// `trmv:motion=shadow` (TrmvParams::motion = 1, the default) drives the visibility's history with the splatted
// shadow motion (motion/shadow_splat.h) [TRMV21 Eq. 3] and Eq. 4's alpha^V; `motion=traditional` (0) with the
// back-projected surface motion [TRMV21 Eq. 1] and the constant alpha: the paper's "Trad." rows of Fig. 8, with
// (clamp_gamma = 3) and without (clamp_gamma = 0) the clamp. The indirect light follows the surface motion in
// both (the dual and glossy vectors of TRMV21 Sec. 4.2-4.3 are not implemented yet).
#pragma once

#include "filters/method.h"
#include "filters/surface_planes.h"
#include "filters/svgf/svgf_params.h"
#include "filters/svgf/tonemap.h"
#include "filters/trmv/cleanup.h"
#include "filters/trmv/falloff.h"
#include "filters/trmv/temporal.h"
#include "filters/trmv/trmv_params.h"

#include <string>

namespace rtdr {

// The channels trmv reads from each input frame.
InputChannels trmv_input_channels();

class TrmvFilter : public Method {
 public:
  explicit TrmvFilter(const MethodParams& params);
  std::string name() const override { return "trmv"; }
  Frame filter(const Frame& in, Frame* dump) override;
  void reset() override;
  // `stream` is the component: "visibility" (or "direct", whose noisy part it is) or "indirect"; `level` is unused.
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
  // Runs one component's passes on c.noisy, c.motion and c.alpha.
  const RgbPlane& filter_component(Component& c);
  void dump(Frame* dump, const FloatPlane& theta, const RgbPlane& tonemapped) const;
  const Component& component(const std::string& stream) const;

  MethodParams params_;
  SurfacePlanes surface_;
  Component visibility_, indirect_;
  TrmvMotion shadow_motion_;              // motion.shadow_splat and where a vector landed (.valid)
  TrmvReceiver receiver_;                 // this frame's s_i, n(s_i), for Eq. 4
  TrmvPreviousPositions prev_positions_;  // the previous frame's `position` and id.mesh, for Eq. 4
  TrmvPreviousPositions seen_prev_positions_;  // those the falloff pass read this frame
};

}  // namespace rtdr
