// The subcommands of `rtdr`. Each add_*_command declares its options on a new subcommand of `app`
// and returns the function that runs it once the whole command line has been parsed.
#pragma once

#include "filters/method.h"
#include "trace/gradients.h"

#include <CLI/CLI.hpp>

#include <functional>
#include <string>
#include <string_view>
#include <vector>

namespace rtdr {

struct Command {
  CLI::App* app;
  std::function<void()> run;
};

Command add_render_command(CLI::App& app);
Command add_bench_command(CLI::App& app);
Command add_filter_command(CLI::App& app);
Command add_probe_command(CLI::App& app);
Command add_eval_command(CLI::App& app);
Command add_compare_command(CLI::App& app);
Command add_check_command(CLI::App& app);
Command add_view_command(CLI::App& app);

// The help of every --frames flag: "inclusive frame range A-B (0 <= A <= B <= 999999)" and then `more`.
std::string frames_help(const std::string& more);

// Shared option parsing, with one-line rtdr::Error messages naming the flag.
struct Size {
  int width;
  int height;
};
Size parse_size(const std::string& text);  // "WxH", each in [1, 16384]
struct FrameRange {
  int first;
  int last;  // inclusive
};
FrameRange parse_frames(const std::string& text);  // "A-B" or "A", 0 <= A <= B <= kMaxFrameIndex (core/frame.h)
// "X,Y", two whole decimal numbers; throws rtdr::Error naming `flag` otherwise (trailing text, overflow).
struct Pixel {
  int x;
  int y;
};
Pixel parse_pixel(const std::string& text, const std::string& flag);
// Every parameter table a method reads, as flags: SVGF's rows as --<name>, A-SVGF's, EAW's, tone mapping's, TAA's
// and TRMV's as --asvgf-<name>, --eaw-<name>, --tonemap-<name>, --taa-<name> and --trmv-<name>, each name with
// hyphens for underscores (--atrous-levels, --taa-clip-history). Each flag's help is its row's source; the value is range-checked when the
// method is made. A flag not given takes the default of the method named by `method` once the command line is
// parsed (filters/method.h's method_defaults: asvgf's alpha is 0.1, not the 0.2 that --help shows for svgf).
void add_method_flags(CLI::App* sub, MethodParams& params, const std::string& method);
// Those tables, listed once for every reader of the flags (add_method_flags, the CLI fuzzer): each as
// T(member of MethodParams, flag prefix, its X-macro table, help group).
#define RTDR_METHOD_PARAM_TABLES(T)                                            \
  T(svgf, "", RTDR_SVGF_PARAMS, "SVGF parameters (svgf's defaults)")           \
  T(asvgf, "asvgf-", RTDR_ASVGF_PARAMS, "A-SVGF parameters (method asvgf)")      \
  T(eaw, "eaw-", RTDR_EAW_PARAMS, "EAW parameters (methods eaw, eaw-accum)")     \
  T(tonemap, "tonemap-", RTDR_TONEMAP_PARAMS, "Tone mapping parameters")        \
  T(taa, "taa-", RTDR_TAA_PARAMS, "TAA parameters")                            \
  T(trmv, "trmv-", RTDR_TRMV_PARAMS, "TRMV parameters (method trmv)")
// A-SVGF's gradient sample parameters (trace/gradients.h) as --gradient-<name>, for rtdr render --gradients.
void add_gradient_flags(CLI::App* sub, GradientParams& params);
// The flag of row `name` of a table whose flags start with `prefix` ("", "eaw-", "tonemap-", "taa-", "gradient-").
std::string param_flag(std::string_view prefix, std::string_view name);

}  // namespace rtdr
