// The expansions of A-SVGF's parameter table (asvgf_params.h): five reconstruction iterations [ASVGF18 Sec. 3.4], the
// maximum over 3x3 strata [ASVGF18 Sec. 3.5], the history-length rule [ASVGF18 Sec. 4].
#include "filters/asvgf/asvgf_params.h"

namespace rtdr {

std::vector<ParamInfo> asvgf_param_table() { return {RTDR_ASVGF_PARAMS(RTDR_PARAM_ROW)}; }
std::vector<double> param_values(const AsvgfParams& params) { return {RTDR_ASVGF_PARAMS(RTDR_PARAM_VALUE)}; }
void validate(const AsvgfParams& p) { check_params("asvgf", asvgf_param_table(), param_values(p)); }

bool set_param(AsvgfParams& params, const std::string& key, double value) {
  RTDR_ASVGF_PARAMS(RTDR_PARAM_SET)
  return false;
}

}  // namespace rtdr
