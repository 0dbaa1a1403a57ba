// The App of `rtdr` (app/cli.h): the global --threads option and the subcommands of app/cmd_<name>.cpp (one per
// file; cmd_filter.cpp adds both filter and probe).
#include "app/cli.h"

namespace rtdr {

Cli::Cli() {
  app.require_subcommand(1);
  app.add_option("--threads", threads, "worker threads (0 = all cores); outputs are identical for any count")
      ->check(CLI::Range(0, 1024));
  commands = {add_render_command(app), add_filter_command(app), add_probe_command(app),
              add_eval_command(app),   add_bench_command(app),  add_compare_command(app),
              add_check_command(app),  add_view_command(app)};
}

}  // namespace rtdr
