// rtdr compare: runs a method (svgf, asvgf or trmv) over a rendered sequence on both back ends, the golden passes
// (cpu) and the shader ports (vulkan), frame by frame on the same inputs, and reports per channel how far the ports' outputs and intermediate
// buffers are from the golden ones (eval/frame_diff.h): every layer `rtdr filter --dump-passes` writes
// (docs/buffers.md), the colour and the display. Each back end keeps its own history, as `rtdr filter` would, so a
// frame's differences include what the earlier frames' differences left in the histories.
//
// Printed: one row per channel, in the pipeline's order (the outputs, then each pass's layers as filters/passes.h
// declares them), with the pass that writes it and its worst absolute and relative difference over the frames,
// each with the frame, the pixel and the two values there, then the bound the ports are held to for that channel
// (gpu/port_bounds.h, the table the tests assert; "-" where none is stated) and whether it holds. Last, a verdict:
// the largest relative difference, and PASS when every bounded channel is within its bound, else FAIL with the
// channels beyond, and exit 1 (after the report): a port check for scripts. A back end that leaves out a declared
// layer is an error. --csv writes one row per frame and channel. --max-rel-error fails (exit 1) when any channel's
// relative difference exceeds it, bounded or not.
#include "app/backend.h"
#include "app/commands.h"
#include "app/sequence.h"
#include "core/atomic_file.h"
#include "core/error.h"
#include "eval/frame_diff.h"
#include "filters/method.h"
#include "filters/passes.h"
#include "gpu/port_bounds.h"

#include <algorithm>
#include <cstdio>
#include <map>
#include <memory>
#include <optional>
#include <sstream>

namespace rtdr {
namespace {

struct CompareOptions {
  std::string method = "svgf";
  std::string in;
  std::string frames;
  std::string csv;
  double rel_floor = 1e-2;
  std::optional<double> max_rel_error;  // not checked when not given
  MethodParams params;
};

// A channel's worst pixel over the frames, and the frame it is in.
struct Worst {
  PixelError error;
  int frame = -1;
};

std::string where(const Worst& w) {
  if (w.frame < 0) return "-";
  char text[64];
  std::snprintf(text, sizeof text, "%d (%d, %d)", w.frame, w.error.x, w.error.y);
  return text;
}

// A value at a worst pixel, or "-" when no pixel differs.
std::string value(const Worst& w, float v) {
  if (w.frame < 0) return "-";
  char text[32];
  std::snprintf(text, sizeof text, "%.7g", v);
  return text;
}

// A bound as printed: "2e-03 rel", "0 abs", or "-" where none is stated.
std::string bound_text(const PortBound* bound, bool half) {
  if (!bound) return "-";
  char text[32];
  std::snprintf(text, sizeof text, "%.3g %s", bound->bound(half), bound->relative ? "rel" : "abs");
  return text;
}

// The overall verdict: each bounded channel against its bound, and the largest relative difference of all.
struct Verdict {
  int bounded = 0;
  std::vector<std::string> failed;  // "channel: difference > bound"
  const Worst* largest = nullptr;
  std::string largest_channel;

  // "ok", "FAIL" or "-" (no bound) for one channel, counting it.
  std::string judge(const std::string& channel, const PortBound* bound, bool half, double abs, double rel) {
    if (!bound) return "-";
    ++bounded;
    const double difference = bound->relative ? rel : abs;
    if (difference <= bound->bound(half)) return "ok";
    char text[160];
    std::snprintf(text, sizeof text, "%s %.3g > %s (%s)", channel.c_str(), difference, bound_text(bound, half).c_str(),
                  bound->test);
    failed.push_back(text);
    return "FAIL";
  }

  void print(bool judged) const {
    if (largest)
      std::printf("largest relative difference: %s, %.3g at frame %s\n", largest_channel.c_str(),
                  largest->error.error, where(*largest).c_str());
    if (!judged)
      std::printf("verdict: none (the bounds are stated for --rel-floor %g)\n", kPortRelFloor);
    else if (failed.empty())
      std::printf("verdict: PASS: all %d bounded channels within their bounds (gpu/port_bounds.h)\n", bounded);
    else
      std::printf("verdict: FAIL: %zu of %d bounded channels beyond their bounds\n", failed.size(), bounded);
  }
};

void run_compare(const CompareOptions& o) {
  if (!(o.rel_floor > 0.0)) throw Error("--rel-floor must be positive");
  if (o.max_rel_error && !(*o.max_rel_error >= 0.0)) throw Error("--max-rel-error must be 0 or more");
  const BackendMethod golden = make_backend_method("cpu", o.method, o.params);
  const BackendMethod port = make_backend_method("vulkan", o.method, o.params);
  const std::vector<SequenceFrame> frames = list_sequence(o.in, o.frames);
  // Every input is read and checked before anything runs, so bad input leaves no CSV.
  SequenceShape shape;
  for (const SequenceFrame& f : frames) read_filter_input(f.path, shape, golden.method->inputs());

  const VulkanContext& device = *port.context;
  std::printf("%s on %zu frame(s) of %s: cpu (golden) against vulkan (%s, %s inputs, %s illumination records)\n",
              o.method.c_str(), frames.size(), o.in.c_str(), device.device_name().c_str(),
              shader_inputs_name(device.shader_inputs()), illumination_records_name(device.illumination_records()));
  std::printf("relative difference: |vulkan - cpu| / max(|cpu|, %g)\n", o.rel_floor);

  std::ostringstream csv;
  csv << "frame,channel,max_abs,abs_x,abs_y,abs_cpu,abs_vulkan,max_rel,rel_x,rel_y,rel_cpu,rel_vulkan\n";
  csv.precision(9);
  // Every channel both back ends must write: the outputs, then the dump layers their passes declare.
  std::vector<std::string> channels;
  for (const LayerDecl* layer : {&layers::kColor, &layers::kDisplay})
    for (std::string& c : layer_channels(*layer)) channels.push_back(std::move(c));
  for (std::string& c : golden.method->dump_channels()) channels.push_back(std::move(c));
  const auto require_declared = [&](const Frame& frame, const char* backend) {
    for (const std::string& channel : channels)
      if (!frame.has(channel))
        throw Error(std::string("the ") + backend + " back end did not write '" + channel + "', which pass " +
                    pass_writing(channel) + " declares (filters/passes.h)");
  };

  std::map<std::string, Worst> worst_abs, worst_rel;
  for (const SequenceFrame& f : frames) {
    const Frame in = read_method_input(f.path, golden.method->inputs());
    const Frame reference = filter_with_dump(*golden.method, in);
    const Frame test = filter_with_dump(*port.method, in);
    require_declared(reference, "cpu");
    require_declared(test, "vulkan");
    for (const ChannelDiff& d : diff_channels(test, reference, o.rel_floor)) {
      if (keep_worst(worst_abs[d.channel].error, d.abs)) worst_abs[d.channel].frame = f.index;
      if (keep_worst(worst_rel[d.channel].error, d.rel)) worst_rel[d.channel].frame = f.index;
      csv << f.index << ',' << d.channel << ',' << d.abs.error << ',' << d.abs.x << ',' << d.abs.y << ','
          << d.abs.reference << ',' << d.abs.test << ',' << d.rel.error << ',' << d.rel.x << ',' << d.rel.y << ','
          << d.rel.reference << ',' << d.rel.test << '\n';
    }
  }

  // The channel column is as wide as the longest name, so the columns stay aligned.
  int width = 7;
  for (const std::string& channel : channels) width = std::max(width, int(channel.size()));
  std::printf("%-*s %-14s %10s %-18s %13s %13s %10s %-18s %9s %s\n", width, "channel", "pass", "max abs",
              "frame (x, y)", "cpu", "vulkan", "max rel", "frame (x, y)", "bound", "verdict");
  const Worst* beyond = nullptr;  // the worst channel beyond --max-rel-error
  std::string beyond_channel;
  int channels_beyond = 0;
  const bool half = device.illumination_records() == IlluminationRecords::Fp16;
  Verdict verdict;
  for (const std::string& channel : channels) {
    const Worst& a = worst_abs[channel];
    const Worst& r = worst_rel[channel];
    const PortBound* bound = o.rel_floor == kPortRelFloor ? find_port_bound(o.method, channel) : nullptr;
    const std::string judged = verdict.judge(channel, bound, half, a.error.error, r.error.error);
    std::printf("%-*s %-14s %10.3g %-18s %13s %13s %10.3g %-18s %9s %s\n", width, channel.c_str(),
                pass_writing(channel).c_str(), a.error.error, where(a).c_str(), value(a, a.error.reference).c_str(),
                value(a, a.error.test).c_str(), r.error.error, where(r).c_str(), bound_text(bound, half).c_str(),
                judged.c_str());
    if (!verdict.largest || r.error.error > verdict.largest->error.error) {
      verdict.largest = &r;
      verdict.largest_channel = channel;
    }
    if (o.max_rel_error && r.error.error > *o.max_rel_error) {
      ++channels_beyond;
      if (!beyond || r.error.error > beyond->error.error) {
        beyond = &r;
        beyond_channel = channel;
      }
    }
  }
  if (!o.csv.empty()) write_text_file(o.csv, csv.str());
  verdict.print(o.rel_floor == kPortRelFloor);
  if (!verdict.failed.empty())
    throw Error(std::to_string(verdict.failed.size()) + " channel(s) beyond the ports' bounds (gpu/port_bounds.h); "
                "the first: " + verdict.failed.front());
  if (beyond) {
    char text[160];
    std::snprintf(text, sizeof text, "%d channel(s) beyond --max-rel-error %g; the worst: %s, %.3g at frame %s",
                  channels_beyond, *o.max_rel_error, beyond_channel.c_str(), beyond->error.error,
                  where(*beyond).c_str());
    throw Error(text);
  }
}

}  // namespace

Command add_compare_command(CLI::App& app) {
  auto o = std::make_shared<CompareOptions>();
  CLI::App* sub = app.add_subcommand("compare", "run a method (svgf, asvgf or trmv) on the golden passes and on its "
                                                "Vulkan ports, report the per-channel differences of every output "
                                                "and intermediate buffer against the ports' bounds, and a verdict");
  sub->add_option("--method", o->method, "the method (svgf, asvgf or trmv: those with Vulkan ports)")->capture_default_str();
  sub->add_option("--in", o->in, "directory of frames written by rtdr render")->required();
  sub->add_option("--frames", o->frames, frames_help("; default: every frame in --in"));
  sub->add_option("--csv", o->csv, "also write one row per frame and channel to this CSV file");
  sub->add_option("--rel-floor", o->rel_floor, "relative differences are to max(|cpu|, this)")->capture_default_str();
  sub->add_option("--max-rel-error", o->max_rel_error,
                  "fail (exit 1, after the report) when a channel's relative difference exceeds this");
  add_method_flags(sub, o->params, o->method);
  return {sub, [o] { run_compare(*o); }};
}

}  // namespace rtdr
