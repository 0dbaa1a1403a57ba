// Running another program without a shell: its arguments are passed as a vector, so no character in them (a
// quote, a semicolon, a space) is ever interpreted. `rtdr eval` draws its charts this way.
#pragma once

#include <string>
#include <vector>

namespace rtdr {

struct ProgramResult {
  int exit_code;             // the program's exit status; 128 + N when signal N ended it
  std::string error_output;  // everything it wrote to its standard error
};

// Runs argv[0] (an absolute path; PATH is not searched) with arguments argv[1..], waits for it, and returns its
// exit status and standard error. Its standard output is this process's. Throws rtdr::Error when it cannot
// be started at all.
ProgramResult run_program(const std::vector<std::string>& argv);

// The last non-empty line of a program's error output: the one line worth quoting in an rtdr::Error.
std::string last_line(const std::string& text);

}  // namespace rtdr
