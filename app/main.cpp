// rtdr: the command line. Each subcommand lives in its own file (cmd_<name>.cpp) and registers itself
// here. User errors (rtdr::Error, CLI11 parse errors) print one line and exit non-zero; nothing is
// written partially because every output file is written to a temporary name and renamed.
#include "app/commands.h"
#include "core/error.h"
#include "core/parallel.h"

#include <CLI/CLI.hpp>

#include <cstdio>
#include <exception>

int main(int argc, char** argv) {
  CLI::App app{"rtdr: Real-Time Denoiser Reference (SVGF, A-SVGF, Temporally Reliable Motion Vectors)"};
  app.require_subcommand(1);
  int threads = 0;
  app.add_option("--threads", threads, "worker threads (0 = all cores); outputs are identical for any count")
      ->check(CLI::Range(0, 1024));

  const std::vector<rtdr::Command> commands = {rtdr::add_render_command(app), rtdr::add_filter_command(app),
                                               rtdr::add_probe_command(app), rtdr::add_eval_command(app),
                                               rtdr::add_bench_command(app), rtdr::add_compare_command(app)};

  try {
    app.parse(argc, argv);
  } catch (const CLI::Success& e) {  // --help
    return app.exit(e);
  } catch (const CLI::ParseError& e) {
    std::fprintf(stderr, "rtdr: error: %s (see rtdr --help)\n", e.what());
    return 2;
  }

  try {
    rtdr::set_thread_count(threads);
    for (const rtdr::Command& c : commands)
      if (c.app->parsed()) c.run();
  } catch (const std::exception& e) {
    std::fprintf(stderr, "rtdr: error: %s\n", e.what());
    return 1;
  }
  return 0;
}
