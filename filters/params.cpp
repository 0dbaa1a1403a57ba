#include "filters/params.h"

#include "core/error.h"

#include <cmath>
#include <sstream>

namespace rtdr {

void check_params(const std::string& what, const std::vector<ParamInfo>& table, const std::vector<double>& values) {
  for (size_t i = 0; i < table.size(); ++i)
    if (!(values[i] >= table[i].min && values[i] <= table[i].max)) {
      std::ostringstream msg;
      msg << what << " parameter " << table[i].name << " = " << values[i] << " is outside [" << table[i].min << ", "
          << table[i].max << "] (" << table[i].source << ")";
      throw Error(msg.str());
    }
}

void check_param_value(const char* name, double value, double lo, double hi, bool whole) {
  if (value >= lo && value <= hi && (!whole || value == std::floor(value))) return;  // false for NaN
  std::ostringstream msg;
  msg << "parameter " << name << " = " << value << " is not " << (whole ? "a whole number" : "a number") << " in ["
      << lo << ", " << hi << "]";
  throw Error(msg.str());
}

std::string describe_params(const std::vector<ParamInfo>& table, const std::vector<double>& values) {
  std::ostringstream out;
  for (size_t i = 0; i < table.size(); ++i)
    out << table[i].name << " = " << values[i] << "  (" << (table[i].symbol.empty() ? "" : table[i].symbol + "; ")
        << table[i].source << ")\n";
  return out.str();
}

}  // namespace rtdr
