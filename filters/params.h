// Tunables declared once. Each algorithm lists its parameters in one X-macro table,
//   X(type, name, default, min, max, symbol, source)
// and these expansions turn the table into its struct, its rows (for CLI flags, docs and the printed
// configuration) and its range checks, so no parameter's default or range is written twice. The shaders do not
// include the tables: each port's push block (filters/svgf/*_shared.h) carries the values its pass reads.
#pragma once

#include <string>
#include <type_traits>
#include <vector>

namespace rtdr {

struct ParamInfo {
  std::string name, symbol, source;
  double default_value, min, max;
};

// Throws rtdr::Error naming `what`, the first parameter outside its [min, max], and its value.
void check_params(const std::string& what, const std::vector<ParamInfo>& table, const std::vector<double>& values);
// "name = value  (symbol; source)", one line per parameter.
std::string describe_params(const std::vector<ParamInfo>& table, const std::vector<double>& values);
// Throws rtdr::Error unless `value` lies in [lo, hi] and, when `whole` (an int parameter), is a whole number. It is
// checked as a double, before any cast: casting 1e30 or NaN to int is undefined behaviour, and 2.9 would
// silently become 2.
void check_param_value(const char* name, double value, double lo, double hi, bool whole);

}  // namespace rtdr

// Expansions for a parameter table X-macro: a struct member with its default, a ParamInfo row, and the
// current value of the member of `params`.
#define RTDR_PARAM_FIELD(type, name, def, lo, hi, symbol, source) type name = def;
#define RTDR_PARAM_ROW(type, name, def, lo, hi, symbol, source) \
  ::rtdr::ParamInfo{#name, symbol, source, double(def), double(lo), double(hi)},
#define RTDR_PARAM_VALUE(type, name, def, lo, hi, symbol, source) double(params.name),
// Sets member `name` of `params` to `value` when `key` names it (inside a function returning bool), after
// checking the value against the row's range and type.
#define RTDR_PARAM_SET(type, name, def, lo, hi, symbol, source)                                  \
  if (key == #name) {                                                                             \
    ::rtdr::check_param_value(#name, value, double(lo), double(hi), std::is_integral_v<type>);     \
    params.name = type(value);                                                                    \
    return true;                                                                                  \
  }
