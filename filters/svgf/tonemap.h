// Tone mapping [SVGF17 Sec. 3, "Post Processing"]: HDR colour -> display-referred linear colour in [0, 1].
//
// Pass: tonemap(colour, params) -> display colour.
//   in:  linear HDR colour (remodulate's output, modulate.h)
//   out: linear display values in [0, 1], for taa/taa.h; sRGB encoding happens only when a PNG is written
//
// SVGF17 says only that "our filtered result goes through a tone mapping operator to handle a high dynamic
// range". We use the global operator of Reinhard, Stark, Shirley and Ferwerda 2002, "Photographic Tone
// Reproduction for Digital Images" [Reinhard02], on luminance:
//   L   = exposure * L_w             [Reinhard02 Eq. 2, with a fixed exposure in place of a / L_w-bar]
//   L_d = L / (1 + L)                [Reinhard02 Eq. 3]
// and the colour is scaled by L_d / L_w, which keeps its chromaticity (Reinhard02 defines the operator on
// luminance only). L_w is Rec. 709 luminance (core/color.h).
//
// Deviations from Reinhard02:
// - Eq. 2 scales by the key a (0.18) over the log-average luminance of the whole image (Eq. 1). We use
//   a fixed `exposure` instead, so the pass is per-pixel and a frame's exposure does not follow its
//   noise from frame to frame. exposure = a / L_w-bar recovers Eq. 2 exactly.
// - No L_white (Eq. 4) and no dodging-and-burning (Sec. 3.2): Eq. 3 alone maps luminance below 1.
// - Scaling by L_d / L_w keeps luminance below 1 but a bright saturated colour can still have a channel
//   above 1 (pure blue (0, 0, 10) scales to (0, 0, 5.8)). Each channel is then clamped to [0, 1], as a
//   display would: such colours lose luminance and may shift hue towards the primaries.
//
// Every tunable, declared once: X(type, name, default, min, max, symbol, source), as in svgf_params.h.
#pragma once

#define RTDR_TONEMAP_PARAMS(X)                                                                              \
  X(float, exposure, 1.0f, 0.0f, 1e9f, "a / L_w-bar",                                                         \
    "Reinhard02 Eq. 2's scale, held fixed; 1 maps luminance 1 to display 0.5 (Eq. 3)")

#include "filters/image.h"
#include "filters/probe.h"
#include "filters/params.h"

#include <glm/glm.hpp>

#include <string>
#include <vector>

namespace rtdr {

struct TonemapParams {
  RTDR_TONEMAP_PARAMS(RTDR_PARAM_FIELD)
};

// One row per parameter, for the CLI and the printed configuration.
std::vector<ParamInfo> tonemap_param_table();
std::vector<double> param_values(const TonemapParams& params);
// Throws rtdr::Error naming the first parameter outside its range.
void validate(const TonemapParams& p);
// "exposure = 1  (a / L_w-bar; Reinhard02 Eq. 2 ...)" one per line.
std::string describe(const TonemapParams& p);

// The golden per-pixel function: one HDR colour -> one display colour in [0, 1].
glm::vec3 tonemap_pixel(const glm::vec3& colour, const TonemapParams& params, Probe* probe = nullptr);

// tonemap_pixel over a frame.
RgbPlane tonemap(const RgbPlane& colour, const TonemapParams& params);

}  // namespace rtdr
