// The `rtdr` command line as one object: the CLI11 App with --threads and every subcommand registered.
// app/main.cpp parses the real argv with it; fuzz/cli_args_fuzz.cpp builds the same one for each input,
// so the fuzzer always sees exactly the options a user can type.
#pragma once

#include "app/commands.h"

#include <CLI/CLI.hpp>

#include <vector>

namespace rtdr {

struct Cli {
  CLI::App app{"rtdr: Real-Time Denoiser Reference (SVGF, A-SVGF and Temporally Reliable Motion Vectors)"};
  int threads = 0;                // --threads: worker threads, 0 = all cores
  std::vector<Command> commands;  // one per subcommand; run the one whose app->parsed()

  Cli();
  // The subcommands point into `app`, so a Cli stays where it was made.
  Cli(const Cli&) = delete;
  Cli& operator=(const Cli&) = delete;
};

}  // namespace rtdr
