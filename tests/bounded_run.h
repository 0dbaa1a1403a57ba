// Running `rtdr` (RTDR_EXE) from a test with bounds: a time limit, after which it is killed, so that a regression
// that hangs (a FIFO opened for reading) fails the test instead of hanging the suite; optionally an address-space
// limit (RLIMIT_AS), so that a regression that allocates without bound fails with std::bad_alloc instead of
// meeting the out-of-memory killer on a shared machine; and the child's peak resident memory (ru_maxrss from
// wait4), so a test can assert what a run cost. fork and execve, no shell: the arguments reach rtdr as they are.
#pragma once

#include "cli_fixtures.h"

#include <fcntl.h>
#include <signal.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <thread>

namespace rtdr::cli {

struct BoundedRun {
  RunResult result;        // exit_code -1 when killed (by us or by a signal)
  bool timed_out = false;  // killed at the time limit
  long max_rss_kib = 0;    // the child's peak resident set, KiB (ru_maxrss)
};

// AddressSanitizer reserves terabytes of address space: an RLIMIT_AS would stop the sanitized rtdr at its start.
#if defined(__SANITIZE_ADDRESS__)
inline constexpr bool kAddressLimitWorks = false;
#else
inline constexpr bool kAddressLimitWorks = true;
#endif

// Runs rtdr `args` in `dir` (stdout and stderr captured as run_rtdr_args does), killed after `seconds`; with
// `address_limit` bytes > 0 (and kAddressLimitWorks), under that RLIMIT_AS.
inline BoundedRun run_rtdr_bounded(const std::vector<std::string>& args, const fs::path& dir, double seconds,
                                   uint64_t address_limit = 0) {
  std::vector<std::string> argv_text = {RTDR_EXE};
  argv_text.insert(argv_text.end(), args.begin(), args.end());
  std::vector<char*> argv;
  for (std::string& a : argv_text) argv.push_back(a.data());
  argv.push_back(nullptr);
  const fs::path out = dir / "stdout.txt", err = dir / "stderr.txt";
  const int out_fd = ::open(out.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0644);
  const int err_fd = ::open(err.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0644);
  const pid_t pid = fork();
  if (pid == 0) {  // the child: only async-signal-safe calls until execve
    ::dup2(out_fd, 1);
    ::dup2(err_fd, 2);
    if (address_limit > 0 && kAddressLimitWorks) {
      rlimit limit{rlim_t(address_limit), rlim_t(address_limit)};
      ::setrlimit(RLIMIT_AS, &limit);
    }
    ::execve(argv[0], argv.data(), environ);
    ::_exit(127);
  }
  ::close(out_fd);
  ::close(err_fd);
  BoundedRun run;
  if (pid < 0) {
    run.result = {-1, "", "cannot start " RTDR_EXE};
    return run;
  }
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::duration<double>(seconds);
  int status = 0;
  rusage usage{};
  while (::wait4(pid, &status, WNOHANG, &usage) == 0) {
    if (std::chrono::steady_clock::now() > deadline) {
      ::kill(pid, SIGKILL);
      ::wait4(pid, &status, 0, &usage);
      run.timed_out = true;
      break;
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  }
  run.max_rss_kib = usage.ru_maxrss;
  std::string joined;
  for (const std::string& a : args) joined += (joined.empty() ? "" : " ") + a;
  run.result = checked_for_sanitizers(
      {WIFEXITED(status) && !run.timed_out ? WEXITSTATUS(status) : -1, read_text(out), read_text(err)}, joined);
  return run;
}

}  // namespace rtdr::cli
