// The App of `rtdr` (app/cli.h): the global --threads option and the subcommands of app/cmd_<name>.cpp (one per
// file; cmd_filter.cpp adds both filter and probe).
#include "app/cli.h"

namespace rtdr {

Cli::Cli() {
  app.require_subcommand(1);
  // An option a subcommand does not know falls through to rtdr's own: --threads is accepted before the
  // subcommand or after it (`rtdr --threads 1 render ...`, `rtdr render --threads 1 ...`). Set before the
  // subcommands are added, which inherit it.
  app.fallthrough();
  app.add_option("--threads", threads, "worker threads (0 = all cores); outputs are identical for any count")
      ->check(CLI::Range(0, 1024));
  commands = {add_render_command(app), add_filter_command(app), add_probe_command(app),
              add_eval_command(app),   add_bench_command(app),  add_compare_command(app),
              add_check_command(app),  add_view_command(app)};
  // Each subcommand's --help names the option it shares with rtdr, after its own footer.
  for (const Command& c : commands)
    c.app->footer(c.app->get_footer() + (c.app->get_footer().empty() ? "" : "\n\n") +
                  "Also: --threads N  worker threads (0 = all cores), before or after the subcommand; outputs are "
                  "identical for any count");
}

}  // namespace rtdr
