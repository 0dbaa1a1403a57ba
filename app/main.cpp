// rtdr: the command line. Each subcommand lives in a file app/cmd_<name>.cpp (probe in cmd_filter.cpp, beside
// filter, whose pipeline it runs) and is registered in app/cli.cpp. User errors (rtdr::Error, CLI11 parse
// errors) print one line and exit non-zero; nothing is written partially because every output file is written
// to a temporary name and renamed.
#include "app/cli.h"
#include "core/error.h"
#include "core/parallel.h"

#include <CLI/CLI.hpp>

#include <cstdio>
#include <exception>
#include <string>

int main(int argc, char** argv) {
  rtdr::Cli cli;

  try {
    cli.app.parse(argc, argv);
  } catch (const CLI::Success& e) {  // --help
    return cli.app.exit(e);
  } catch (const CLI::ParseError& e) {
    // Point to the help of the subcommand whose options were being read, where there is one.
    std::string help = "rtdr --help";
    for (const CLI::App* sub : cli.app.get_subcommands()) help = "rtdr " + sub->get_name() + " --help";
    std::fprintf(stderr, "rtdr: error: %s (see %s)\n", e.what(), help.c_str());
    return 2;
  }

  try {
    rtdr::set_thread_count(cli.threads);
    for (const rtdr::Command& c : cli.commands)
      if (c.app->parsed()) c.run();
  } catch (const std::exception& e) {
    std::fprintf(stderr, "rtdr: error: %s\n", e.what());
    return 1;
  }
  return 0;
}
