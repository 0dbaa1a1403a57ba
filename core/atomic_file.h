// Writing outputs so that a reader never sees a partial one.
// - One file: write to a temporary name in the same folder, then rename over the destination (atomic on POSIX
//   file systems). On any failure the temporary is removed and rtdr::Error names the destination.
// - A whole run's folder of outputs (StagedOutputDir): every file goes into a hidden staging folder (StagingFolder),
//   and only a run that finishes moves them into the output folder, all or nothing. A run that fails leaves no
//   output at all.
#pragma once

#include <functional>
#include <memory>
#include <string>
#include <vector>

namespace rtdr {

// Calls write(tmp_path), which must create the file at tmp_path or throw; then renames it to `path`.
void write_file_atomically(const std::string& path, const std::function<void(const std::string& tmp_path)>& write);

// The common case: a text or binary blob.
void write_text_file(const std::string& path, const std::string& contents);

// A hidden folder that one process stages files in: <parent>/<prefix><16 random hex digits>, with a lock file beside
// it, <that>.lock, on which the process holds an exclusive flock(2) for as long as the folder is in use. The name is
// random, not the pid: pids repeat (every container's first process is 1) and a shared folder spans machines.
// The lock tells a live folder from a dead one: the kernel releases it when its process dies, however it dies
// (Ctrl-C, kill -9, the OOM killer), so a folder whose lock is free is stale, and the next StagingFolder made in
// the same parent with the same prefix removes it.
class StagingFolder {
 public:
  // Removes the stale folders of `prefix` in `parent` first (remove_stale), then creates this one. Throws
  // rtdr::Error with the system's reason when it cannot (`parent` read-only, missing, full).
  StagingFolder(const std::string& parent, const std::string& prefix);
  ~StagingFolder();  // removes the folder, whatever it holds, then its lock file
  StagingFolder(const StagingFolder&) = delete;
  StagingFolder& operator=(const StagingFolder&) = delete;

  const std::string& path() const { return path_; }

  // Removes every folder <parent>/<prefix>* whose lock file no live process holds, and the lock file; returns how
  // many. Folders of that prefix without a lock file are left alone (an older rtdr made them, or another program).
  static int remove_stale(const std::string& parent, const std::string& prefix);

 private:
  std::string path_;
  int lock_fd_ = -1;
};

// One file to move into place: from `from` to `to`, replacing a file at `to`.
struct FileMove {
  std::string from, to;
};

// Moves every file of `moves`, all or nothing. First every destination is checked: none may be a folder, and every
// folder on its path must be a folder or not exist yet (a file cannot become one), else rtdr::Error names it and
// nothing moves. Then each file moves with rename(2), a file it replaces being moved aside into `backup` (a folder
// on the same file system) first. If a move fails, every move before it is undone: the new files go back to `from`,
// the replaced ones back to `to`, and folders the moves created are removed; then rtdr::Error gives the reason.
// `rename` is the move itself (std::filesystem::rename unless a test fails one on purpose).
void move_all_or_nothing(const std::vector<FileMove>& moves, const std::string& backup,
                         const std::function<void(const std::string& from, const std::string& to)>& rename = {});

// The output folder of one run (`rtdr render`, `filter` or `eval` --out), all or nothing.
//
//   StagedOutputDir out("out/cornell");   // creates out/.rtdr-staging-<random>/ (or beside out/ if missing)
//   write_exr(out.file("frame_0000.exr"), frame);
//   out.commit();                          // creates out/ if needed and moves every staged file into it
//
// The staging folder (a StagingFolder) lies in the deepest folder of `dir`'s path that already exists, so it is on
// the same file system as `dir` and the final renames cannot fail for crossing one. Destroying an uncommitted
// StagedOutputDir (an exception unwinding) removes the staging folder: `dir` keeps exactly what it held before the
// run, and folders of its path that did not exist are not created. A process killed by a signal runs no
// destructor: its staging folder stays until the next run stages in the same place, which removes it.
class StagedOutputDir {
 public:
  explicit StagedOutputDir(const std::string& dir);  // throws rtdr::Error naming `dir` when it cannot be staged
  StagedOutputDir(const StagedOutputDir&) = delete;
  StagedOutputDir& operator=(const StagedOutputDir&) = delete;

  // Where to write the output file `name`, during the run.
  std::string file(const std::string& name) const;
  // The staging folder itself, for a program that writes several files into a folder it is given.
  const std::string& staging() const { return staging_->path(); }
  // Moves every staged file (those in staged folders too) into `dir`, replacing files of the same names, all or
  // nothing (move_all_or_nothing): a commit that fails leaves `dir` as it was. Call once, after the last write.
  void commit();

 private:
  std::string dir_;
  std::unique_ptr<StagingFolder> staging_;
};

}  // namespace rtdr
