// Every SVGF tunable, declared once: C++ name, type, default, valid range, the paper's symbol and where the
// value comes from. The table expands into the SvgfParams struct, the CLI flags (`--<name>` with hyphens, as
// `--sigma-l 4`; app/commands.h), the printed configuration and range checks. The shaders read the values they
// need from their push blocks (temporal_shared.h, variance_shared.h, atrous_shared.h), which gpu/ fills from
// SvgfParams.
//
// X(type, name, default, min, max, symbol, source)
#define RTDR_SVGF_PARAMS(X)                                                                                       \
  X(float, alpha, 0.2f, 0.0f, 1.0f, "alpha", "SVGF17 Sec. 4.1: colour EMA weight, 'alpha = 0.2 worked best'")     \
  X(float, alpha_moments, 0.2f, 0.0f, 1.0f, "alpha_mu", "SVGF17 Sec. 4.2: moments accumulate like colour")        \
  X(float, temporal_depth_relative, 0.1f, 0.0f, 1e9f, "", "SVGF17 Sec. 4.1 consistency: relative depth (temporal.h)") \
  X(float, temporal_normal_cosine, 0.9f, -1.0f, 1.0f, "", "SVGF17 Sec. 4.1 consistency: min n . n' (temporal.h)")     \
  X(float, sigma_z, 1.0f, 0.0f, 1e9f, "sigma_z", "SVGF17 Sec. 4.4, Eq. 3")                                       \
  X(float, sigma_n, 128.0f, 0.0f, 1e9f, "sigma_n", "SVGF17 Sec. 4.4, Eq. 4")                                     \
  X(float, sigma_l, 4.0f, 0.0f, 1e9f, "sigma_l", "SVGF17 Sec. 4.4, Eq. 5")                                       \
  X(float, epsilon, 1e-4f, 1e-12f, 1.0f, "epsilon", "SVGF17 Eq. 3 and 5: a small value to avoid division by zero (> 0: 0/0 on flat planes)") \
  X(int, atrous_levels, 5, 0, 10, "", "SVGF17 Sec. 4.3: 'a five-level wavelet transform'")                        \
  X(int, kernel_size, 5, 3, 5, "", "5: the 5x5 B3 kernel of SVGF17 Eq. 1; 3: the 3x3 box of ASVGF18 Sec. 4")      \
  X(int, history_level, 0, 0, 9, "", "SVGF17 Sec. 4.3: the first level's output is the colour history")          \
  X(int, variance_min_history, 4, 0, 1000, "", "SVGF17 Sec. 4.2: '<4 frames after a disocclusion' -> 7x7 spatial")\
  X(int, max_history, 0, 0, 100000, "n_max", "0 = none; Falcor-style alpha = max(alpha, 1/n) (a deviation)")     \
  X(int, streams, 2, 1, 2, "", "2: direct and indirect filtered apart (SVGF17 Sec. 3); 1: their sum, one stream, one gradient (ASVGF18 Sec. 4)")

#ifdef __cplusplus
#pragma once
#include "filters/params.h"

namespace rtdr {

struct SvgfParams {
  RTDR_SVGF_PARAMS(RTDR_PARAM_FIELD)
};

std::vector<ParamInfo> svgf_param_table();
std::vector<double> param_values(const SvgfParams& params);
// Throws rtdr::Error naming the first parameter outside its range.
void validate(const SvgfParams& params);
// "alpha = 0.2  (alpha; SVGF17 Sec. 4.1 ...)" one per line.
std::string describe(const SvgfParams& params);
// Sets the parameter called `key` (a row name of the table); false when there is no such row.
bool set_param(SvgfParams& params, const std::string& key, double value);
// The parameters that differ from `base` (the table's defaults, or a method's: filters/method.h) as "name=value"
// joined by ':', e.g. "atrous_levels=4:kernel_size=3" ("" when none does): what follows "svgf:" in a method spec
// (eval/experiment.h), which set_param reads back.
std::string changed_params(const SvgfParams& params, const SvgfParams& base = {});

}  // namespace rtdr
#endif
