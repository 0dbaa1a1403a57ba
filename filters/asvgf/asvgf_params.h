// Every A-SVGF tunable of the filter side [ASVGF18 Sec. 3.4, 3.5], declared once (filters/params.h explains the X-macro). The rest of
// A-SVGF's parameters are SVGF's (svgf_params.h): the edge-stopping sigmas and epsilon of the reconstruction
// [ASVGF18 Sec. 3.4: "chosen as for SVGF"], alpha (0.1 for asvgf [ASVGF18 Sec. 5]) and the 3x3 box a-trous
// [ASVGF18 Sec. 4]. The stratum size is the render's (trace/gradients.h), read from the frame's header.
//
// The last four rows choose how a gradient sample enters the reconstruction and becomes lambda (gradient_image.h,
// GradientForm; README.md, "Deviations and choices"); their defaults are the paper's.
//
// X(type, name, default, min, max, symbol, source)
#define RTDR_ASVGF_PARAMS(X)                                                                                      \
  X(int, gradient_levels, 5, 0, 10, "", "ASVGF18 Sec. 3.4: five a-trous iterations on the stratum grid")          \
  X(int, alpha_max_radius, 1, 0, 4, "", "ASVGF18 Sec. 3.5: alpha_i is the maximum over 3x3 strata (radius 1)")     \
  X(int, history_rule, 0, 0, 1, "",                                                                                \
    "0: n = 1 + (1 - lambda) n_{i-1}, a dropped history restarts (ASVGF18 Sec. 4); 1: SVGF's count, never shortened") \
  X(int, gradient_normalize, 0, 0, 1, "",                                                                          \
    "0: after the reconstruction, lambda = |delta^| / Delta^ (ASVGF18 Eq. 14); 1: before it, per sample, beside a "  \
    "sample-present weight (Q2RTX, RTGL1)")                                                                         \
  X(int, gradient_exponent, 1, 1, 2, "p", "the ratio |delta| / Delta to the power p: 1 (ASVGF18 Eq. 14); 2 (Q2RTX)")  \
  X(float, gradient_scale, 1.0f, 0.0f, 1.0f, "k",                                                                  \
    "the ratio times k: 1 (ASVGF18 Eq. 14); 0.1 (RayTracedGL1, for indirect light)")                               \
  X(int, gradient_abs, 0, 0, 1, "",                                                                                \
    "0: signed delta filtered (ASVGF18 Eq. 12); 1: abs(delta), so that opposite changes cannot cancel")

#pragma once
#include "filters/params.h"

namespace rtdr {

struct AsvgfParams {
  RTDR_ASVGF_PARAMS(RTDR_PARAM_FIELD)
};

std::vector<ParamInfo> asvgf_param_table();
std::vector<double> param_values(const AsvgfParams& params);
// Throws rtdr::Error naming the first parameter outside its range.
void validate(const AsvgfParams& params);
// Sets the parameter called `key`; false when there is no such row.
bool set_param(AsvgfParams& params, const std::string& key, double value);

}  // namespace rtdr
