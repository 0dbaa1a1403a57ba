#include "filters/svgf/svgf_params.h"

#include "core/error.h"

#include <sstream>

namespace rtdr {

std::vector<ParamInfo> svgf_param_table() {
  return {
#define RTDR_SVGF_ROW(type, name, def, lo, hi, symbol, source) {#name, symbol, source, double(def), double(lo), double(hi)},
      RTDR_SVGF_PARAMS(RTDR_SVGF_ROW)
#undef RTDR_SVGF_ROW
  };
}

void validate(const SvgfParams& p) {
#define RTDR_SVGF_CHECK(type, name, def, lo, hi, symbol, source)                                             \
  if (!(double(p.name) >= double(lo) && double(p.name) <= double(hi)))                                     \
    throw Error("svgf parameter " #name " = " + std::to_string(p.name) + " is outside [" + std::to_string(lo) + \
                ", " + std::to_string(hi) + "]");
  RTDR_SVGF_PARAMS(RTDR_SVGF_CHECK)
#undef RTDR_SVGF_CHECK
  if (p.kernel_size != 3 && p.kernel_size != 5) throw Error("svgf parameter kernel_size must be 3 or 5");
}

std::string describe(const SvgfParams& p) {
  std::ostringstream out;
#define RTDR_SVGF_LINE(type, name, def, lo, hi, symbol, source) \
  out << #name << " = " << p.name << "  (" << (std::string(symbol).empty() ? "" : symbol "; ") << source << ")\n";
  RTDR_SVGF_PARAMS(RTDR_SVGF_LINE)
#undef RTDR_SVGF_LINE
  return out.str();
}

}  // namespace rtdr
