#include "filters/svgf/svgf_params.h"

#include "core/error.h"

namespace rtdr {

std::vector<ParamInfo> svgf_param_table() { return {RTDR_SVGF_PARAMS(RTDR_PARAM_ROW)}; }
std::vector<double> param_values(const SvgfParams& params) { return {RTDR_SVGF_PARAMS(RTDR_PARAM_VALUE)}; }
std::string describe(const SvgfParams& params) { return describe_params(svgf_param_table(), param_values(params)); }

bool set_param(SvgfParams& params, const std::string& key, double value) {
  RTDR_SVGF_PARAMS(RTDR_PARAM_SET)
  return false;
}

void validate(const SvgfParams& params) {
  check_params("svgf", svgf_param_table(), param_values(params));
  if (params.kernel_size != 3 && params.kernel_size != 5) throw Error("svgf parameter kernel_size must be 3 or 5");
}

}  // namespace rtdr
