// Tone mapping with Reinhard02's global operator on luminance, a fixed exposure and a display clamp.
// The operator, its source and its deviations are in tonemap.h.
#include "filters/svgf/tonemap.h"

#include "core/color.h"
#include "core/error.h"
#include "core/parallel.h"

#include <sstream>

namespace rtdr {

std::vector<ParamInfo> tonemap_param_table() { return {RTDR_TONEMAP_PARAMS(RTDR_PARAM_ROW)}; }
std::vector<double> param_values(const TonemapParams& params) { return {RTDR_TONEMAP_PARAMS(RTDR_PARAM_VALUE)}; }
void validate(const TonemapParams& p) { check_params("tonemap", tonemap_param_table(), param_values(p)); }
std::string describe(const TonemapParams& p) { return describe_params(tonemap_param_table(), param_values(p)); }

glm::vec3 tonemap_pixel(const glm::vec3& colour, const TonemapParams& params, Probe* probe) {
  // World luminance L_w of the HDR colour (Rec. 709 Y, core/color.h).
  const float L_w = luminance(colour);
  note(probe, "L_w", L_w, "Reinhard02 Sec. 3.1: world luminance");
  // Black stays black; L_w <= 0 only comes from negative inputs, which have nothing to display.
  if (!(L_w > 0.0f)) {
    note(probe, "display colour", glm::vec3(0.0f), "L_w <= 0: black");
    return glm::vec3(0.0f);
  }
  // Scaled luminance L = exposure * L_w [Reinhard02 Eq. 2, a / L_w-bar replaced by a fixed exposure].
  const float L = params.exposure * L_w;
  note(probe, "L", L, "Reinhard02 Eq. 2");
  // Display luminance L_d = L / (1 + L): near-linear for dark values, approaching 1 for bright ones [Reinhard02 Eq. 3].
  const float L_d = L / (1.0f + L);
  note(probe, "L_d", L_d, "Reinhard02 Eq. 3");
  // Scale the colour so its luminance becomes L_d; the ratios of R, G, B (chromaticity) are kept.
  const float scale = L_d / L_w;
  note(probe, "scale L_d / L_w", scale, "luminance operator applied to colour");
  const glm::vec3 scaled = scale * colour;
  note(probe, "scaled colour", scaled, "");
  // Display clamp: a saturated bright colour can keep a channel above 1 (see tonemap.h).
  const glm::vec3 display = glm::clamp(scaled, 0.0f, 1.0f);
  note(probe, "display colour", display, "clamped to [0, 1]");
  return display;
}

RgbPlane tonemap(const RgbPlane& colour, const TonemapParams& params) {
  validate(params);
  RgbPlane display(colour.width, colour.height);
  parallel_rows(colour.height, [&](int y) {
    for (int x = 0; x < colour.width; ++x) display.at(x, y) = tonemap_pixel(colour.at(x, y), params);
  });
  return display;
}

}  // namespace rtdr
