// The expansions of SVGF's parameter table (svgf_params.h): every row cites where its default comes from, e.g.
// alpha = 0.2 [SVGF17 Sec. 4.1] and sigma_z, sigma_n, sigma_l = 1, 128, 4 [SVGF17 Sec. 4.4, Eq. 3-5].
#include "filters/svgf/svgf_params.h"

#include "core/error.h"

#include <charconv>

namespace rtdr {

std::vector<ParamInfo> svgf_param_table() { return {RTDR_SVGF_PARAMS(RTDR_PARAM_ROW)}; }
std::vector<double> param_values(const SvgfParams& params) { return {RTDR_SVGF_PARAMS(RTDR_PARAM_VALUE)}; }
std::string describe(const SvgfParams& params) { return describe_params(svgf_param_table(), param_values(params)); }

bool set_param(SvgfParams& params, const std::string& key, double value) {
  RTDR_SVGF_PARAMS(RTDR_PARAM_SET)
  return false;
}

std::string changed_params(const SvgfParams& params, const SvgfParams& base) {
  const std::vector<ParamInfo> table = svgf_param_table();
  const std::vector<double> values = param_values(params), base_values = param_values(base);
  std::string text;
  for (size_t i = 0; i < table.size(); ++i) {
    if (values[i] == base_values[i]) continue;
    char digits[32];  // every parameter is a float or a small int: the shortest digits that read back exactly
    const auto end = std::to_chars(digits, digits + sizeof digits, float(values[i])).ptr;
    text += (text.empty() ? "" : ":") + table[i].name + "=" + std::string(digits, end);
  }
  return text;
}

void validate(const SvgfParams& params) {
  check_params("svgf", svgf_param_table(), param_values(params));
  if (params.kernel_size != 3 && params.kernel_size != 5) throw Error("svgf parameter kernel_size must be 3 or 5");
}

}  // namespace rtdr
