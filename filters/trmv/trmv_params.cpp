// The expansions of TRMV's parameter table (trmv_params.h): alpha [TRMV21 Sec. 5], the falloff's std
// [TRMV21 Eq. 4], the mu +- 3 sigma clamp and the 9x9 clean-up [TRMV21 Sec. 5], epsilon [TRMV21 Eq. 8].
#include "filters/trmv/trmv_params.h"

#include "core/error.h"

#include <iterator>
#include <string>

namespace rtdr {

std::vector<ParamInfo> trmv_param_table() { return {RTDR_TRMV_PARAMS(RTDR_PARAM_ROW)}; }
std::vector<double> param_values(const TrmvParams& params) { return {RTDR_TRMV_PARAMS(RTDR_PARAM_VALUE)}; }

void validate(const TrmvParams& p) {
  check_params("trmv", trmv_param_table(), param_values(p));
  // A K x K window centred on the pixel reaches (K - 1) / 2 pixels each way; an even K has no centre.
  if (p.cleanup_size % 2 == 0)
    throw Error("trmv parameter cleanup_size = " + std::to_string(p.cleanup_size) + " must be odd (TRMV21 Sec. 5: 9x9)");
  if (p.splat_size != 0 && p.splat_size % 2 == 0)
    throw Error("trmv parameter splat_size = " + std::to_string(p.splat_size) +
                " must be odd, or 0 for the shadow filter's window (TRMV21 Sec. 4.1)");
}

int trmv_motion_from_name(const std::string& name) {
  for (int m = 0; m < int(std::size(kTrmvMotionNames)); ++m)
    if (name == kTrmvMotionNames[m]) return m;
  return -1;
}

bool set_param(TrmvParams& params, const std::string& key, double value) {
  RTDR_TRMV_PARAMS(RTDR_PARAM_SET)
  return false;
}

}  // namespace rtdr
