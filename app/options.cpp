// Parsing of the option values shared by several subcommands.
#include "app/commands.h"
#include "core/error.h"
#include "core/frame.h"        // kMaxFrameIndex
#include "raster/visibility.h"  // kMaxImageSize: the rasterizer's limit
#include "filters/trmv/trmv_params.h"
#include "trace/gradients.h"

#include <algorithm>
#include <charconv>
#include <functional>
#include <iterator>
#include <sstream>

namespace rtdr {
namespace {

// Parses a whole decimal integer; false on anything else (empty, sign, trailing text, overflow).
bool parse_int(std::string_view s, int& out) {
  if (s.empty()) return false;
  const auto [end, ec] = std::from_chars(s.data(), s.data() + s.size(), out);
  return ec == std::errc() && end == s.data() + s.size();
}

// TRMV's motion row takes its names as well as its numbers (trmv_params.h kTrmvMotionNames), as rtdr eval's
// specs do (trmv:motion=shadow or trmv:motion=1): a name becomes its number before the range check.
void accept_motion_names(CLI::Option* option) {
  std::string names;
  for (int m = 0; m < int(std::size(kTrmvMotionNames)); ++m)
    names += (m ? ", " : "") + std::string(kTrmvMotionNames[m]) + " " + std::to_string(m);
  option->description(option->get_description() + " (a name or its number: " + names + ")");
  option->transform(CLI::Validator(
      [names](std::string& value) {
        const int m = trmv_motion_from_name(value);
        if (m >= 0) value = std::to_string(m);
        int number = -1;
        if (m >= 0 || (parse_int(value, number) && number >= 0 && number < int(std::size(kTrmvMotionNames))))
          return std::string();
        return "'" + value + "' is not one of " + names;
      },
      "NAME|N", "TRMV motion"));
}

}  // namespace

Size parse_size(const std::string& text) {
  const size_t x = text.find('x');
  Size s{};
  if (x == std::string::npos || !parse_int(std::string_view(text).substr(0, x), s.width) ||
      !parse_int(std::string_view(text).substr(x + 1), s.height))
    throw Error("--size '" + text + "' is not WIDTHxHEIGHT, e.g. 1280x720");
  if (s.width < 1 || s.height < 1 || s.width > kMaxImageSize || s.height > kMaxImageSize)
    throw Error("--size '" + text + "': width and height must be between 1 and " + std::to_string(kMaxImageSize));
  return s;
}

FrameRange parse_frames(const std::string& text) {
  const size_t dash = text.find('-');
  FrameRange r{};
  const bool ok = dash == std::string::npos
                      ? parse_int(text, r.first) && (r.last = r.first, true)
                      : parse_int(std::string_view(text).substr(0, dash), r.first) &&
                            parse_int(std::string_view(text).substr(dash + 1), r.last);
  if (!ok || r.first < 0 || r.last < r.first || r.last > kMaxFrameIndex)
    throw Error("--frames '" + text + "' is not A-B or A with 0 <= A <= B <= " + std::to_string(kMaxFrameIndex) +
                ", e.g. 0-9");
  return r;
}

std::string frames_help(const std::string& more) {
  return "inclusive frame range A-B (0 <= A <= B <= " + std::to_string(kMaxFrameIndex) + ")" + more;
}

Pixel parse_pixel(const std::string& text, const std::string& flag) {
  const size_t comma = text.find(',');
  Pixel p{};
  if (comma == std::string::npos || !parse_int(std::string_view(text).substr(0, comma), p.x) ||
      !parse_int(std::string_view(text).substr(comma + 1), p.y))
    throw Error(flag + " '" + text + "' is not X,Y (two whole numbers, e.g. 640,360)");
  return p;
}

std::string param_flag(std::string_view prefix, std::string_view name) {
  std::string flag = "--" + std::string(prefix) + std::string(name);
  std::replace(flag.begin(), flag.end(), '_', '-');
  return flag;
}

// One flag per row of a parameter table: expanded inside a block that names the struct holding the values
// (`table`), the flags' prefix and their help group.
#define RTDR_PARAM_FLAG(type, name, def, lo, hi, symbol, source) \
  sub->add_option(param_flag(prefix, #name), table.name, std::string(source))->capture_default_str()->group(group);

// A row whose default differs by method (asvgf's alpha is 0.1, svgf's 0.2: filters/method.h's method_defaults) shows
// no single default; its help names each method's instead, e.g. "(default 0.1 for asvgf, a-eaw; 0.2 for the others)".
void show_method_defaults(CLI::Option* option, double table_default, const std::function<double(const MethodParams&)>& value) {
  std::string differ;
  double other = table_default;
  for (const std::string& name : method_names()) {
    const double v = value(method_defaults(name));
    if (v == table_default) continue;
    differ += (differ.empty() ? "" : ", ") + name;
    other = v;  // one other default is all the tables have; a second would need a longer text
  }
  if (differ.empty()) return;
  const auto text = [](double v) { std::ostringstream s; s << v; return s.str(); };
  option->default_str("");
  option->description(option->get_description() + " (default " + text(other) + " for " + differ + "; " +
                      text(table_default) + " for the others)");
}

void add_method_flags(CLI::App* sub, MethodParams& p, const std::string& method) {
#define RTDR_METHOD_DEFAULT_HELP(type, name, def, lo, hi, symbol, source)              \
  show_method_defaults(sub->get_option(param_flag(prefix, #name)), double(type(def)), \
                       [&](const MethodParams& m) { return double(table_of(m).name); });
#define RTDR_TABLE_FLAGS(member, table_prefix, TABLE, table_group)                          \
  {                                                                                         \
    auto& table = p.member;                                                                 \
    const auto table_of = [](const MethodParams& m) -> const auto& { return m.member; };    \
    const char *prefix = table_prefix, *group = table_group;                                \
    TABLE(RTDR_PARAM_FLAG)                                                                  \
    TABLE(RTDR_METHOD_DEFAULT_HELP)                                                         \
  }
  RTDR_METHOD_PARAM_TABLES(RTDR_TABLE_FLAGS)
#undef RTDR_TABLE_FLAGS
  accept_motion_names(sub->get_option(param_flag("trmv-", "motion")));
#undef RTDR_METHOD_DEFAULT_HELP
  // Once parsed: every row whose flag was not given takes the method's default. (An unknown method is left to
  // make_method, which names the known ones; nothing may throw here, inside CLI11's parse.)
  sub->parse_complete_callback([sub, &p, &method] {
    const std::vector<std::string> names = method_names();
    if (std::find(names.begin(), names.end(), method) == names.end()) return;
    const MethodParams defaults = method_defaults(method);
#define RTDR_DEFAULT_ROW(type, name, def, lo, hi, symbol, source) \
  if (sub->count(param_flag(prefix, #name)) == 0) table.name = from.name;
#define RTDR_TABLE_DEFAULTS(member, table_prefix, TABLE, table_group) \
  {                                                                   \
    auto& table = p.member;                                           \
    const auto& from = defaults.member;                               \
    const char* prefix = table_prefix;                                \
    TABLE(RTDR_DEFAULT_ROW)                                           \
  }
    RTDR_METHOD_PARAM_TABLES(RTDR_TABLE_DEFAULTS)
#undef RTDR_TABLE_DEFAULTS
#undef RTDR_DEFAULT_ROW
  });
}

void add_gradient_flags(CLI::App* sub, GradientParams& table) {
  const char *prefix = "gradient-", *group = "Gradient samples (with --gradients)";
  RTDR_GRADIENT_PARAMS(RTDR_PARAM_FLAG)
}

#undef RTDR_PARAM_FLAG

}  // namespace rtdr
