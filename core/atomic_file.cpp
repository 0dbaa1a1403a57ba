#include "core/atomic_file.h"

#include "core/error.h"

#include <fcntl.h>
#include <sys/file.h>
#include <sys/stat.h>
#include <unistd.h>

#include <atomic>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <random>

namespace rtdr {
namespace fs = std::filesystem;
namespace {

// 16 random hex digits (the kernel's random source), and a per-process counter: a name no other process, on this
// machine or another sharing the folder, picks at the same time.
std::string unique_suffix() {
  static std::atomic<unsigned> counter{0};
  std::random_device device;
  const unsigned long long r = (static_cast<unsigned long long>(device()) << 32) ^ device();
  char s[40];
  std::snprintf(s, sizeof s, "%016llx-%u", r, counter++);
  return s;
}

std::string system_reason() { return std::strerror(errno); }

// Whether `fd` is still the file at `path` (a cleaner may have removed the file between our open and our lock).
bool same_file(int fd, const std::string& path) {
  struct stat a {}, b {};
  return ::fstat(fd, &a) == 0 && ::stat(path.c_str(), &b) == 0 && a.st_dev == b.st_dev && a.st_ino == b.st_ino;
}

constexpr const char* kLockSuffix = ".lock";

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

// ---- StagingFolder

StagingFolder::StagingFolder(const std::string& parent, const std::string& prefix) {
  remove_stale(parent, prefix);
  for (int attempt = 0; attempt < 8; ++attempt) {
    const std::string path = (fs::path(parent) / (prefix + unique_suffix())).string();
    const std::string lock = path + kLockSuffix;
    const int fd = ::open(lock.c_str(), O_RDWR | O_CREAT | O_EXCL | O_CLOEXEC, 0644);
    if (fd < 0 && errno == EEXIST) continue;
    if (fd < 0) throw SystemError("cannot create a staging folder in '" + parent + "': " + system_reason(), errno);
    // Between our open and our lock a cleaner may have locked and removed the file: then it is not ours, try again.
    if (::flock(fd, LOCK_EX) != 0 || !same_file(fd, lock)) {
      ::close(fd);
      continue;
    }
    if (::mkdir(path.c_str(), 0755) != 0) {
      const int code = errno;
      ::unlink(lock.c_str());
      ::close(fd);
      throw SystemError("cannot create a staging folder in '" + parent + "': " + std::strerror(code), code);
    }
    path_ = path;
    lock_fd_ = fd;
    return;
  }
  throw Error("cannot create a staging folder in '" + parent + "': no free name after 8 tries");
}

StagingFolder::~StagingFolder() {
  std::error_code ec;
  fs::remove_all(path_, ec);  // still holding the lock, so no cleaner touches it meanwhile
  ::unlink((path_ + kLockSuffix).c_str());
  ::close(lock_fd_);
}

int StagingFolder::remove_stale(const std::string& parent, const std::string& prefix) {
  std::error_code ec;
  int removed = 0;
  std::vector<std::string> locks;
  for (fs::directory_iterator it(parent, ec), end; !ec && it != end; it.increment(ec)) {
    const std::string name = it->path().filename().string();
    const size_t n = std::strlen(kLockSuffix);
    if (name.rfind(prefix, 0) == 0 && name.size() > prefix.size() + n && name.compare(name.size() - n, n, kLockSuffix) == 0)
      locks.push_back(it->path().string());
  }
  for (const std::string& lock : locks) {
    const int fd = ::open(lock.c_str(), O_RDWR | O_CLOEXEC);
    if (fd < 0) continue;
    // Free means no live process holds it. Removing both while holding it keeps a creator from adopting them.
    if (::flock(fd, LOCK_EX | LOCK_NB) == 0 && same_file(fd, lock)) {
      fs::remove_all(lock.substr(0, lock.size() - std::strlen(kLockSuffix)), ec);
      ::unlink(lock.c_str());
      ++removed;
    }
    ::close(fd);
  }
  return removed;
}

// ---- move_all_or_nothing

void move_all_or_nothing(const std::vector<FileMove>& moves, const std::string& backup,
                         const std::function<void(const std::string& from, const std::string& to)>& rename) {
  std::error_code ec;
  // 1. Every destination, before anything moves.
  for (const FileMove& m : moves) {
    if (fs::is_directory(m.to, ec)) throw Error("cannot replace '" + m.to + "': it is a folder");
    for (fs::path p = fs::path(m.to).parent_path(); !p.empty() && p != p.root_path(); p = p.parent_path())
      if (fs::exists(p, ec) && !fs::is_directory(p, ec))
        throw Error("cannot write '" + m.to + "': '" + p.string() + "' is a file, not a folder");
  }
  const auto move = [&](const std::string& from, const std::string& to) {
    if (rename) return rename(from, to);
    fs::rename(from, to);  // throws fs::filesystem_error with the reason
  };
  // 2. The moves, each one recorded so that it can be undone.
  struct Done {
    const FileMove* move;
    std::string replaced;  // where the file it replaced waits, "" if none
  };
  std::vector<Done> done;
  std::vector<fs::path> created;  // folders made for the destinations, outermost first
  try {
    fs::create_directories(backup);
    for (size_t k = 0; k < moves.size(); ++k) {
      const FileMove& m = moves[k];
      for (fs::path p = fs::path(m.to).parent_path(); !p.empty() && !fs::exists(p); p = p.parent_path())
        created.insert(created.begin(), p);
      fs::create_directories(fs::path(m.to).parent_path());
      Done d{&m, ""};
      if (fs::exists(fs::symlink_status(m.to))) {
        d.replaced = (fs::path(backup) / std::to_string(k)).string();
        move(m.to, d.replaced);
      }
      try {
        move(m.from, m.to);
      } catch (...) {
        if (!d.replaced.empty()) fs::rename(d.replaced, m.to, ec);  // put back the one just moved aside
        throw;
      }
      done.push_back(d);
    }
  } catch (const std::exception& e) {
    // 3. Undo, newest first: the new file back to its staging place, the replaced one back to its destination.
    for (auto it = done.rbegin(); it != done.rend(); ++it) {
      fs::rename(it->move->to, it->move->from, ec);
      if (!it->replaced.empty()) fs::rename(it->replaced, it->move->to, ec);
    }
    for (auto it = created.rbegin(); it != created.rend(); ++it) fs::remove(*it, ec);  // only if empty
    throw Error(std::string("cannot move the outputs into place, so none was: ") + e.what());
  }
}

// ---- StagedOutputDir

StagedOutputDir::StagedOutputDir(const std::string& dir) : dir_(dir) {
  std::error_code ec;
  if (fs::exists(dir, ec) && !fs::is_directory(dir, ec)) throw Error("--out '" + dir + "' is a file, not a folder");
  // The deepest existing folder of the path: `dir` itself on a rerun, else the nearest existing ancestor, which
  // must be a folder (in "a.txt/b", the file a.txt stops the path from ever being created).
  fs::path existing = fs::absolute(dir, ec).lexically_normal();
  while (!fs::exists(existing, ec) && existing.has_relative_path()) existing = existing.parent_path();
  if (!fs::is_directory(existing, ec)) throw Error("--out '" + dir + "' is not a folder that can be created");
  try {
    staging_ = std::make_unique<StagingFolder>(existing.string(), ".rtdr-staging-");
  } catch (const Error& e) {
    throw Error("--out '" + dir + "' cannot be written: " + e.what());
  }
}

std::string StagedOutputDir::file(const std::string& name) const { return (fs::path(staging()) / name).string(); }

void StagedOutputDir::commit() {
  // Every staged file, in staged folders too, to the same place below `dir`; moved aside files wait in a folder
  // of the staging folder, which is on the same file system.
  const fs::path backup = fs::path(staging()) / ".replaced";
  std::vector<FileMove> moves;
  std::error_code ec;
  for (fs::recursive_directory_iterator it(staging(), ec), end; !ec && it != end; it.increment(ec))
    if (!it->is_directory())
      moves.push_back({it->path().string(), (fs::path(dir_) / fs::relative(it->path(), staging())).string()});
  if (ec) throw Error("cannot read the staged outputs of --out '" + dir_ + "': " + ec.message());
  if (fs::exists(dir_, ec) && !fs::is_directory(dir_, ec))
    throw Error("--out '" + dir_ + "' is not a folder that can be created");
  try {
    move_all_or_nothing(moves, backup.string());
    fs::create_directories(dir_);  // a run with no outputs still leaves its folder
  } catch (const std::exception& e) {
    throw Error("--out '" + dir_ + "': " + e.what());
  }
  staging_.reset();  // removes the staging folder: empty but for the files the moves replaced
}

}  // namespace rtdr
