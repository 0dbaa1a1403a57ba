// libFuzzer harness for the command line of `rtdr` (app/cli.h): the App that main() parses, then the
// checks each subcommand runs on its values before doing any work (app/commands.h parse_size and
// parse_frames, the SVGF parameter ranges, method names and eval's method specs, back-end names). It never
// runs a subcommand: that would render, read and write files, and take seconds.
//
// An input is an argument list: the bytes split at every NUL or newline, after an implicit "rtdr"; the
// seeds (fuzz/corpus/cli_args_fuzz/) are command lines from README.md, one argument per line.
//
// Bad arguments must end in CLI::ParseError (CLI11 prints it as one line) or rtdr::Error. A finding is
// anything else: a crash, a sanitizer report, a hang, another exception escaping, or a check that passes
// a value it promises to reject (a --size outside [1, kMaxImageSize], a --frames range with A > B or beyond
// kMaxFrameIndex).
#include "fuzz/harness.h"

#include "app/backend.h"
#include "app/cli.h"
#include "core/error.h"
#include "core/frame.h"  // kMaxFrameIndex
#include "eval/experiment.h"
#include "filters/method.h"
#include "raster/visibility.h"  // kMaxImageSize
#include "scenes/gltf_loader.h"

#include <cstdio>
#include <cstdlib>
#include <sstream>
#include <string>
#include <vector>

namespace {

// Aborts with a message; libFuzzer saves the input that got here.
void finding(const std::string& what) {
  std::fprintf(stderr, "finding: %s\n", what.c_str());
  std::abort();
}

// The input's arguments: each ends at a NUL or newline byte (an empty one is an empty argument); a last
// argument without a separator after it counts too, so "render\n--size\n8x8\n" is three arguments.
std::vector<std::string> split_arguments(const uint8_t* data, size_t size) {
  std::vector<std::string> args;
  std::string arg;
  for (size_t i = 0; i < size; ++i) {
    if (data[i] == '\0' || data[i] == '\n') {
      args.push_back(arg);
      arg.clear();
    } else {
      arg += char(data[i]);
    }
  }
  if (!arg.empty()) args.push_back(arg);
  return args;
}

// The value of `flag` in `sub` as the subcommand's code sees it: what was typed, else the default; ""
// for a flag this subcommand does not have.
std::string value(const CLI::App* sub, const std::string& flag) {
  const CLI::Option* o = sub->get_option_no_throw(flag);
  if (!o) return "";
  return o->count() > 0 ? o->as<std::string>() : o->get_default_str();
}

bool has(const CLI::App* sub, const std::string& flag) { return sub->get_option_no_throw(flag) != nullptr; }

// The method parameters the subcommand's flags hold: each row of the four tables (app/commands.h's
// add_method_flags) that was given, converted by CLI11 exactly as it converted it into the command's own.
rtdr::MethodParams method_params(const CLI::App* sub) {
  rtdr::MethodParams p;
#define RTDR_FUZZ_READ_FLAG(type, name, def, lo, hi, symbol, source)                                    \
  if (const CLI::Option* o = sub->get_option_no_throw(rtdr::param_flag(prefix, #name)); o && o->count() > 0) \
    table.name = o->as<type>();
#define RTDR_FUZZ_READ_TABLE(member, table_prefix, TABLE, group) \
  {                                                              \
    auto& table = p.member;                                      \
    const char* prefix = table_prefix;                           \
    TABLE(RTDR_FUZZ_READ_FLAG)                                   \
  }
  RTDR_METHOD_PARAM_TABLES(RTDR_FUZZ_READ_TABLE)
#undef RTDR_FUZZ_READ_TABLE
#undef RTDR_FUZZ_READ_FLAG
  return p;
}

// What the subcommands check before they touch a file, by flag name (every subcommand spells a flag the
// same way, so one function covers them all).
void check_values(const CLI::App* sub) {
  if (has(sub, "--size")) {
    const rtdr::Size s = rtdr::parse_size(value(sub, "--size"));
    if (s.width < 1 || s.height < 1 || s.width > rtdr::kMaxImageSize || s.height > rtdr::kMaxImageSize)
      finding("parse_size accepted '" + value(sub, "--size") + "'");
  }
  if (!value(sub, "--frames").empty()) {
    const rtdr::FrameRange r = rtdr::parse_frames(value(sub, "--frames"));
    if (r.first < 0 || r.last < r.first || r.last > rtdr::kMaxFrameIndex)
      finding("parse_frames accepted '" + value(sub, "--frames") + "'");
  }
  if (has(sub, "--alpha")) rtdr::validate(method_params(sub).svgf);  // the parameter flags come as one group
  if (has(sub, "--method")) rtdr::make_method(value(sub, "--method"), method_params(sub));
  if (has(sub, "--backend")) rtdr::parse_backends(value(sub, "--backend"));
  if (has(sub, "--methods") && value(sub, "--methods") != "all") {
    // rtdr eval: comma-separated method specs (app/cmd_eval.cpp), each parsed as eval/experiment.h says.
    std::stringstream ss(value(sub, "--methods"));
    for (std::string spec; std::getline(ss, spec, ',');)
      if (!spec.empty()) rtdr::parse_method_spec(spec);
  }
  if (has(sub, "--scene")) rtdr::resolve_scene_path(value(sub, "--scene"));
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  std::vector<std::string> args = split_arguments(data, size);
  args.insert(args.begin(), "rtdr");
  std::vector<const char*> argv;
  for (const std::string& a : args) argv.push_back(a.c_str());

  rtdr::Cli cli;  // a fresh App per input: parsing leaves state in it
  try {
    cli.app.parse(int(argv.size()), argv.data());
    for (const CLI::App* sub : cli.app.get_subcommands()) check_values(sub);
  } catch (const CLI::ParseError& e) {  // CLI11's one-line error (or --help)
    rtdr::fuzz::expected_error(e);
  } catch (const rtdr::Error& e) {  // a subcommand's one-line error for a bad value
    rtdr::fuzz::expected_error(e);
  }
  return 0;
}
