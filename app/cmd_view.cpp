// rtdr view: filters a sequence once and serves a page, on 127.0.0.1 only, that steps through every pass of every
// frame and explains any clicked pixel with every term of its golden equation (docs/view.md).
#include "app/commands.h"
#include "app/view_sequence.h"
#include "app/view_server.h"

#include <cstdio>
#include <memory>

namespace rtdr {
namespace {

void run_view(const ViewOptions& o) {
  // The page's files and the port first: a broken install or a taken port fails before minutes of filtering.
  const std::map<std::string, std::string> assets = view_asset_routes(default_view_asset_dirs());
  require_port_free(o.port);
  std::printf("rtdr view: filtering %s with %s, keeping every pass of every frame\n", o.in.c_str(), o.method.c_str());
  std::fflush(stdout);
  const ViewSequence view(o, [](const std::string& line) {
    std::printf("%s\n", line.c_str());
    std::fflush(stdout);
  });
  serve_view(view, assets, o.port, [&](int port) {
    std::printf("RTDR view of %s on %s: http://127.0.0.1:%d/  (Ctrl-C to stop)\n", o.method.c_str(), o.in.c_str(),
                port);
    std::fflush(stdout);
  });
}

}  // namespace

Command add_view_command(CLI::App& app) {
  auto o = std::make_shared<ViewOptions>();
  CLI::App* sub = app.add_subcommand("view", "step through every pass in the browser and probe any pixel (docs/view.md)");
  sub->add_option("--method", o->method, "the method to filter with and probe")->capture_default_str();
  sub->add_option("--in", o->in, "directory of frames written by rtdr render")->required();
  sub->add_option("--ref", o->ref, "reference frames of the same indices (rtdr render --spp N): error map and metrics");
  sub->add_option("--port-dumps", o->port_dumps,
                  "rtdr filter --backend vulkan --dump-passes of the same frames: golden against port");
  sub->add_option("--frames", o->frames,
                  frames_help("; the frames to view (default: all); history is built from the first frame of --in"));
  sub->add_option("--port", o->port, "port on 127.0.0.1 (0: any free port)")->capture_default_str()->check(CLI::Range(0, 65535));
  add_method_flags(sub, o->params, o->method);
  return {sub, [o] { run_view(*o); }};
}

}  // namespace rtdr
