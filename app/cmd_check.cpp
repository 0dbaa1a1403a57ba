// rtdr check: whether a directory of EXR frames, rendered by rtdr or written by your engine, can be the input of a
// method. It reads every frame and prints one line per problem, naming the file and the layer: a layer that is
// missing or lacks channels, a channel of the wrong type or holding NaN or infinity, a frame of another size than
// the first, a file that is no readable EXR, and for asvgf and a-eaw a frame without gradient samples or with two in
// one stratum: exactly the checks `rtdr filter` makes (app/sequence.h, filters/input_check.h). It checks
// every frame and every layer rather than stopping at the first problem, and exits 1 when it found any; channels
// that may be left out (emission, indirect: 0) are noted when absent, not counted as problems. The
// layers each method reads, and their conventions: docs/buffers.md, "Feeding your engine's frames".
#include "app/commands.h"
#include "app/sequence.h"
#include "core/error.h"
#include "core/exr_io.h"
#include "filters/method.h"

#include <cstdio>
#include <memory>
#include <optional>
#include <set>

namespace rtdr {
namespace {

struct CheckOptions {
  std::string method = "svgf";
  std::string in;
  std::string frames;
};

void run_check(const CheckOptions& o) {
  const std::unique_ptr<Method> method = make_method(o.method);  // throws for an unknown name, listing the known ones
  const InputChannels channels = method->inputs();
  const std::vector<SequenceFrame> frames = list_sequence(o.in, o.frames);
  std::optional<Frame> first;  // its size and file, without planes
  size_t problems = 0, bad_frames = 0;
  std::set<std::string> defaulted;  // channels some frame leaves out, which take their default
  for (const SequenceFrame& f : frames) {
    std::vector<std::string> found;
    try {
      const Frame frame = read_exr(f.path);
      found = sequence_input_problems(frame, channels, first ? &*first : nullptr);  // what filter refuses
      for (const auto& [name, value] : channels.defaults)
        if (!frame.has(name)) defaulted.insert(name);
      if (!first) {
        first = Frame(frame.width(), frame.height());
        first->source = f.path;
      }
    } catch (const Error& e) {
      found.push_back(e.what());  // not a readable EXR: read_exr's one line
    }
    for (const std::string& p : found) std::printf("%s: %s\n", f.path.c_str(), p.c_str());
    problems += found.size();
    bad_frames += !found.empty();
  }
  const std::string layers = std::to_string(channels.floats.size()) + " float and " +
                             std::to_string(channels.uints.size()) + " uint channels";
  if (problems)
    throw Error(std::to_string(problems) + " problem(s) in " + std::to_string(bad_frames) + " of " +
                std::to_string(frames.size()) + " frames of '" + o.in + "' as input of " + o.method + " (it reads " +
                layers + ", docs/buffers.md)");
  std::printf("ok: %zu frames of %dx%d in '%s' hold the %s that %s reads, all finite\n", frames.size(),
              first->width(), first->height(), o.in.c_str(), layers.c_str(), o.method.c_str());
  for (const std::string& name : defaulted)
    std::printf("note: some frames leave out %s, which then holds %g at every pixel\n", name.c_str(),
                double(channels.defaults.at(name)));
}

}  // namespace

Command add_check_command(CLI::App& app) {
  auto o = std::make_shared<CheckOptions>();
  CLI::App* sub = app.add_subcommand("check", "check that a directory of EXR frames can be a method's input: every "
                                              "missing or malformed layer, one line each");
  sub->add_option("--in", o->in, "directory of frame_NNNN.exr, from rtdr render or your engine")->required();
  sub->add_option("--method", o->method, "the method whose input the frames must be: " + [] {
    std::string names;
    for (const std::string& n : method_names()) names += (names.empty() ? "" : ", ") + n;
    return names;
  }())->capture_default_str();
  sub->add_option("--frames", o->frames, frames_help("; default: every frame in --in"));
  return {sub, [o] { run_check(*o); }};
}

}  // namespace rtdr
