// Running the real `rtdr` binary (RTDR_EXE) from tests, as a user would, in scratch folders.
#pragma once

#include "core/frame.h"

#include <catch2/catch.hpp>

#include <fcntl.h>
#include <spawn.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <set>
#include <sstream>
#include <string>
#include <vector>

namespace rtdr::cli {

namespace fs = std::filesystem;

struct RunResult {
  int exit_code;
  std::string out, err;
};

// A fresh, empty folder `name` under this process's scratch root `root` (e.g. "rtdr_cli_test").
inline fs::path scratch(const std::string& root, const std::string& name) {
  const fs::path dir = fs::temp_directory_path() / (root + "_" + std::to_string(::getpid())) / name;
  fs::remove_all(dir);
  fs::create_directories(dir);
  return dir;
}

inline std::string read_text(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

// In the sanitizer build (tools/sanitize.sh) rtdr is sanitized too: a report in its stderr fails the test,
// even a test that expects rtdr to fail, and shows the report.
inline RunResult checked_for_sanitizers(RunResult result, const std::string& args) {
  if (result.err.find("Sanitizer") != std::string::npos || result.err.find("runtime error:") != std::string::npos)
    FAIL_CHECK("sanitizer report from rtdr " << args << ":\n" << result.err);
  return result;
}

// Runs `rtdr` with `args` as its argument vector, through no shell: a quote, a space or "$(...)" in an
// argument reaches rtdr as it is. stdout and stderr are captured in files of `dir`; `env` entries
// ("NAME=value") are added to its environment.
// `wrapper` goes before rtdr (a program that runs the rest of its arguments, such as setpriv to run as another
// user), found on PATH.
inline RunResult run_rtdr_args(const std::vector<std::string>& args, const fs::path& dir,
                               const std::vector<std::string>& env = {},
                               const std::vector<std::string>& wrapper = {}) {
  std::vector<std::string> argv_text = wrapper;
  argv_text.push_back(RTDR_EXE);
  argv_text.insert(argv_text.end(), args.begin(), args.end());
  std::vector<char*> argv, envp;
  for (std::string& a : argv_text) argv.push_back(a.data());
  argv.push_back(nullptr);
  std::vector<std::string> env_text(env);
  for (char** e = environ; *e; ++e) env_text.push_back(*e);  // later duplicates lose: ours come first
  for (std::string& e : env_text) envp.push_back(e.data());
  envp.push_back(nullptr);

  const fs::path out = dir / "stdout.txt", err = dir / "stderr.txt";
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_addopen(&actions, 1, out.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
  posix_spawn_file_actions_addopen(&actions, 2, err.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
  pid_t pid = 0;
  const int spawned = posix_spawnp(&pid, argv[0], &actions, nullptr, argv.data(), envp.data());
  posix_spawn_file_actions_destroy(&actions);
  if (spawned != 0) return {-1, "", "cannot start " + argv_text[0]};
  int status = 0;
  waitpid(pid, &status, 0);
  std::string joined;
  for (const std::string& a : args) joined += (joined.empty() ? "" : " ") + a;
  return checked_for_sanitizers({WIFEXITED(status) ? WEXITSTATUS(status) : -1, read_text(out), read_text(err)}, joined);
}

// The whitespace-separated words of `text` (no quoting: for the tests' own command lines, whose paths hold no
// spaces).
inline std::vector<std::string> words(const std::string& text) {
  std::vector<std::string> out;
  std::istringstream in(text);
  for (std::string w; in >> w;) out.push_back(w);
  return out;
}

// Runs `rtdr args`, `args` split at whitespace (no shell reads it); `env` ("NAME=value ...") is set for it alone.
inline RunResult run_rtdr(const std::string& args, const fs::path& dir, const std::string& env = "") {
  return run_rtdr_args(words(args), dir, words(env));
}

// The cells of one line of a CSV file the command wrote (no quoting: its cells hold no commas); an empty last
// cell, after a trailing comma, counts.
inline std::vector<std::string> csv_cells(const std::string& line) {
  std::vector<std::string> cells;
  std::stringstream ss(line);
  for (std::string cell; std::getline(ss, cell, ',');) cells.push_back(cell);
  if (!line.empty() && line.back() == ',') cells.push_back("");
  return cells;
}

// A file's identity on disk, (device, inode); (0, 0) when it does not exist. A file written again, by a rename
// over it, has a new one: so a test tells a frame the cache read from one it rendered and stored again.
inline std::pair<uint64_t, uint64_t> file_id(const fs::path& path) {
  struct stat st {};
  if (::stat(path.c_str(), &st) != 0) return {0, 0};
  return {uint64_t(st.st_dev), uint64_t(st.st_ino)};
}

// The names of the files in `dir` (none when it does not exist).
inline std::set<std::string> files_in(const fs::path& dir) {
  std::set<std::string> names;
  if (fs::exists(dir))
    for (const auto& e : fs::directory_iterator(dir)) names.insert(e.path().filename().string());
  return names;
}

// A copy of frame `f` without channel `drop`: the input of a test that removes one layer.
inline Frame without(const Frame& f, const std::string& drop) {
  Frame out(f.width(), f.height());
  for (const auto& [name, plane] : f.float_channels())
    if (name != drop) out.add_float(name).data = plane.data;
  for (const auto& [name, plane] : f.uint_channels())
    if (name != drop) out.add_uint(name).data = plane.data;
  return out;
}

}  // namespace rtdr::cli
