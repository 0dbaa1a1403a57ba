// rtdr filter: runs a denoising method over a rendered sequence and writes the filtered frames.
// rtdr probe:  runs it up to one frame, then prints every term of one pass at one pixel.
#include "app/backend.h"
#include "app/commands.h"
#include "app/preview.h"
#include "app/probe_report.h"
#include "app/sequence.h"
#include "filters/passes.h"
#include "core/atomic_file.h"
#include "core/error.h"
#include "core/exr_io.h"
#include "filters/image.h"
#include "filters/method.h"

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <memory>

namespace rtdr {
namespace {

struct FilterOptions {
  std::string method = "svgf";
  std::string backend = "cpu";
  std::string in, out;
  std::string frames;
  bool dump = false;
  MethodParams params;
};

void run_filter(const FilterOptions& o) {
  const BackendMethod backend = make_backend_method(o.backend, o.method, o.params);
  Method* method = backend.method.get();
  const std::vector<SequenceFrame> frames = list_sequence(o.in, o.frames);
  std::error_code ec;
  if (std::filesystem::equivalent(o.in, o.out, ec))
    throw Error("--out '" + o.out + "' is --in: the filtered frames would overwrite their inputs");

  // Every input is read and checked before anything is written: every channel the method reads, in every frame.
  SequenceShape shape;
  for (const SequenceFrame& f : frames) read_filter_input(f.path, shape, method->inputs());
  // And every output goes into a staging folder until the last frame is done: a failed run leaves no output.
  StagedOutputDir out(o.out);

  std::printf("method %s (%s%s) on %zu frame(s) of %s\n%s", method->name().c_str(), o.backend.c_str(),
              backend.context ? (", " + backend.context->device_name()).c_str() : "", frames.size(), o.in.c_str(),
              describe_method_params(o.method, o.params).c_str());
  for (const SequenceFrame& f : frames) {
    const Frame in = read_method_input(f.path, method->inputs());
    const Frame filtered = about_frame(f, [&] { return o.dump ? filter_with_dump(*method, in) : method->filter(in); });
    require_finite_output(filtered, "frame " + std::to_string(f.index) + " of --in '" + o.in + "'", pass_writing);
    write_exr(out.file(frame_name(f.index, "exr")), filtered);
    write_display_png(out.file(frame_name(f.index, "png")), rgb_plane(filtered, "display"));
    double total = 0.0;
    for (const auto& [pass, ms] : method->pass_times()) total += ms;
    std::printf("frame %d  %.1f ms  -> %s\n", f.index, total, frame_path(o.out, f.index, "exr").c_str());
  }
  out.commit();
}

struct ProbeOptions {
  std::string method = "svgf";
  std::string in;
  int frame = 0;
  std::string pixel;
  std::string pass = "atrous";
  std::string stream = "direct";
  int level = 0;
  bool json = false;
  MethodParams params;
};

void run_probe(const ProbeOptions& o) {
  const auto [x, y] = parse_pixel(o.pixel, "--pixel");
  const std::unique_ptr<Method> method = make_method(o.method, o.params);
  // A pass the method does not run is refused before any frame is read, with the passes it runs.
  const std::vector<std::string> passes = method->probe_passes();
  if (std::find(passes.begin(), passes.end(), o.pass) == passes.end()) {
    std::string known;
    for (const std::string& p : passes) known += (known.empty() ? "" : ", ") + p;
    throw Error("--pass '" + o.pass + "' is not a pass of method " + o.method + " with these parameters; its passes: " +
                known + " (rtdr probe --help says what each prints)");
  }
  // The history of frame F is built by every frame before it: run the method from the first frame on.
  const std::vector<SequenceFrame> all = list_sequence(o.in, "");
  SequenceShape shape;
  bool found = false;
  for (const SequenceFrame& f : all) {
    if (f.index > o.frame) break;
    const Frame in = read_filter_input(f.path, shape, method->inputs());
    about_frame(f, [&] { return method->filter(in, nullptr); });
    found = f.index == o.frame;
  }
  if (!found) throw Error("--frame " + std::to_string(o.frame) + " is not in --in '" + o.in + "'");
  const Probe probe = method->probe(o.pass, x, y, o.stream, o.level);
  if (o.json) {
    std::printf("%s", probe_json_text({o.method, o.frame, x, y, o.pass, o.stream, o.level}, probe).c_str());
  } else {
    std::printf("# %s %s, frame %d, pixel (%d, %d), stream %s, level %d\n# group | term = value | source\n%s",
                o.method.c_str(), o.pass.c_str(), o.frame, x, y, o.stream.c_str(), o.level, probe.text().c_str());
  }
}

}  // namespace

Command add_filter_command(CLI::App& app) {
  auto o = std::make_shared<FilterOptions>();
  CLI::App* sub = app.add_subcommand("filter", "denoise a rendered sequence with one method");
  sub->add_option("--method", o->method, "svgf, asvgf, a-eaw, accum, eaw, eaw-accum, none or trmv")->capture_default_str();
  sub->add_option("--backend", o->backend, "cpu (the golden passes) or vulkan (the shader ports: svgf, asvgf, trmv)")
      ->capture_default_str();
  sub->add_option("--in", o->in, "directory of frames written by rtdr render")->required();
  sub->add_option("--out", o->out, "output directory (created if missing)")->required();
  sub->add_option("--frames", o->frames, frames_help("; default: every frame in --in"));
  sub->add_flag("--dump-passes", o->dump, "also write every intermediate buffer of every pass (docs/buffers.md)");
  add_method_flags(sub, o->params, o->method);
  return {sub, [o] { run_filter(*o); }};
}

Command add_probe_command(CLI::App& app) {
  auto o = std::make_shared<ProbeOptions>();
  CLI::App* sub = app.add_subcommand("probe", "print every term of one pass at one pixel");
  sub->add_option("--method", o->method, "the method whose pass to probe")->capture_default_str();
  sub->add_option("--in", o->in, "directory of frames written by rtdr render")->required();
  sub->add_option("--frame", o->frame, "frame index (earlier frames are filtered first, for history)")->required();
  sub->add_option("--pixel", o->pixel, "X,Y")->required();
  // The passes, from their declarations (filters/passes.h): the names for --pass, and what each prints below.
  std::string names, passes = "Passes (the method runs some of them; rtdr probe says which when asked for another):";
  for (const PassDecl& pass : filter_passes()) {
    names += (names.empty() ? "" : ", ") + std::string(pass.name);
    passes += "\n  " + std::string(pass.name) + " " + std::string(pass.cite) + " (" + std::string(pass.golden) +
              "): " + std::string(pass.probe);
  }
  sub->add_option("--pass", o->pass, names)->capture_default_str();
  sub->footer(passes);
  sub->add_option("--stream", o->stream,
                  "direct or indirect (for per-stream passes; combined with --streams 1); trmv: visibility (or "
                  "direct), diffuse or glossy")
      ->capture_default_str();
  sub->add_option("--level", o->level, "a-trous / EAW level")->capture_default_str();
  sub->add_flag("--json", o->json, "print JSON instead of text");
  add_method_flags(sub, o->params, o->method);
  return {sub, [o] { run_probe(*o); }};
}

}  // namespace rtdr
