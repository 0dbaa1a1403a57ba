// core/subprocess.h: a program runs with its arguments exactly as given (no shell reads them), and its exit
// status and standard error come back.
#include "core/subprocess.h"
#include "core/error.h"

#include <catch2/catch.hpp>

#include <string>

TEST_CASE("run_program: arguments reach the program verbatim, with quotes, semicolons and $(...) not interpreted") {
  // sh prints its first argument ($1) to stderr: if a shell had read it, the quote would have broken the line
  // or $(...) would have run.
  const std::string hostile = "it's; $(echo injected) `echo too` \"x\" *";
  const rtdr::ProgramResult r = rtdr::run_program({"/bin/sh", "-c", "printf '%s\\n' \"$1\" >&2; exit 3", "sh", hostile});
  CHECK(r.exit_code == 3);
  CHECK(r.error_output == hostile + "\n");
}

TEST_CASE("run_program: exit status 0, a large error output read to its end, and a signal as 128 + N") {
  CHECK(rtdr::run_program({"/bin/true"}).exit_code == 0);
  // 200 kB: more than a pipe holds, so the parent must read while the child writes.
  const rtdr::ProgramResult big = rtdr::run_program({"/bin/sh", "-c", "head -c 200000 /dev/zero | tr '\\0' x >&2"});
  CHECK(big.exit_code == 0);
  CHECK(big.error_output.size() == 200000);
  CHECK(rtdr::run_program({"/bin/sh", "-c", "kill -9 $$"}).exit_code == 128 + 9);
}

TEST_CASE("run_program: a program that does not exist is an rtdr::Error naming it") {
  CHECK_THROWS_WITH(rtdr::run_program({"/nonexistent/python3", "x"}),
                    Catch::Contains("/nonexistent/python3") && Catch::Contains("No such file"));
  CHECK_THROWS_AS(rtdr::run_program({}), rtdr::Error);
}

TEST_CASE("last_line: the last non-empty line, without its line break") {
  CHECK(rtdr::last_line("Traceback\n  File x\nOSError: disk full\n") == "OSError: disk full");
  CHECK(rtdr::last_line("one line") == "one line");
  CHECK(rtdr::last_line("a\nb\n\n  \n") == "b");
  CHECK(rtdr::last_line("") == "");
  CHECK(rtdr::last_line("\n\n") == "");
}
