#include "core/atomic_file.h"

#include "core/error.h"

#include <unistd.h>

#include <atomic>
#include <filesystem>
#include <fstream>

namespace rtdr {
namespace fs = std::filesystem;
namespace {

// "<pid>-<n>": the pid and a per-process counter keep concurrent writers of one destination apart.
std::string unique_suffix() {
  static std::atomic<unsigned> counter{0};
  return std::to_string(::getpid()) + "-" + std::to_string(counter++);
}

}  // namespace

void write_file_atomically(const std::string& path, const std::function<void(const std::string& tmp_path)>& write) {
  const std::string tmp = path + ".tmp-" + unique_suffix();
  std::error_code ec;
  try {
    write(tmp);
  } catch (const std::exception& e) {
    fs::remove(tmp, ec);
    throw Error("cannot write '" + path + "': " + e.what());
  }
  fs::rename(tmp, path, ec);
  if (ec) {
    const std::string reason = ec.message();  // before remove() overwrites ec
    fs::remove(tmp, ec);
    throw Error("cannot write '" + path + "': " + reason);
  }
}

void write_text_file(const std::string& path, const std::string& contents) {
  write_file_atomically(path, [&](const std::string& tmp) {
    std::ofstream out(tmp, std::ios::binary);
    out << contents;
    out.close();
    if (!out) throw Error("write failed");
  });
}

StagedOutputDir::StagedOutputDir(const std::string& dir) : dir_(dir) {
  std::error_code ec;
  if (fs::exists(dir, ec) && !fs::is_directory(dir, ec)) throw Error("--out '" + dir + "' is a file, not a folder");
  // The deepest existing folder of the path: `dir` itself on a rerun, else the nearest existing ancestor, which
  // must be a folder (in "a.txt/b", the file a.txt stops the path from ever being created).
  fs::path existing = fs::absolute(dir, ec).lexically_normal();
  while (!fs::exists(existing, ec) && existing.has_relative_path()) existing = existing.parent_path();
  if (!fs::is_directory(existing, ec)) throw Error("--out '" + dir + "' is not a folder that can be created");
  staging_ = (existing / (".rtdr-staging-" + unique_suffix())).string();
  if (!fs::create_directory(staging_, ec))
    throw Error("--out '" + dir + "' cannot be written (" + (ec ? ec.message() : "staging folder exists") + ")");
}

StagedOutputDir::~StagedOutputDir() {
  std::error_code ec;
  fs::remove_all(staging_, ec);  // gone after commit(); holds every staged file after a failure
}

std::string StagedOutputDir::file(const std::string& name) const { return (fs::path(staging_) / name).string(); }

void StagedOutputDir::commit() {
  std::error_code ec;
  fs::create_directories(dir_, ec);
  if (!fs::is_directory(dir_, ec)) throw Error("--out '" + dir_ + "' is not a folder that can be created");
  for (const fs::directory_entry& entry : fs::directory_iterator(staging_)) {
    fs::rename(entry.path(), fs::path(dir_) / entry.path().filename(), ec);
    if (ec) throw Error("cannot move '" + entry.path().filename().string() + "' into --out '" + dir_ + "': " + ec.message());
  }
  fs::remove(staging_, ec);  // empty now
}

}  // namespace rtdr
