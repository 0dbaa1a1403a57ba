// Writing outputs so that a reader never sees a partial one.
// - One file: write to a temporary name in the same folder, then rename over the destination (atomic on POSIX
//   file systems). On any failure the temporary is removed and rtdr::Error names the destination.
// - A whole run's folder of outputs (StagedOutputDir): every file goes into a hidden staging folder, and only a
//   run that finishes moves them into the output folder. A run that fails leaves no output at all.
#pragma once

#include <functional>
#include <string>

namespace rtdr {

// Calls write(tmp_path), which must create the file at tmp_path or throw; then renames it to `path`.
void write_file_atomically(const std::string& path, const std::function<void(const std::string& tmp_path)>& write);

// The common case: a text or binary blob.
void write_text_file(const std::string& path, const std::string& contents);

// The output folder of one run (`rtdr render`, `filter` or `eval` --out), all or nothing.
//
//   StagedOutputDir out("out/cornell");   // creates out/.rtdr-staging-<pid>-<n>/ (or beside out/ if missing)
//   write_exr(out.file("frame_0000.exr"), frame);
//   out.commit();                          // creates out/ if needed and renames every staged file into it
//
// The staging folder lies in the deepest folder of `dir`'s path that already exists, so it is on the same file
// system as `dir` and the final renames cannot fail for crossing one. Destroying an uncommitted StagedOutputDir
// (an exception unwinding) removes the staging folder: `dir` keeps exactly what it held before the run, and
// folders of its path that did not exist are not created. A process killed by a signal runs no destructor and
// leaves the hidden staging folder behind; nothing else.
class StagedOutputDir {
 public:
  explicit StagedOutputDir(const std::string& dir);  // throws rtdr::Error naming `dir` when it cannot be staged
  ~StagedOutputDir();
  StagedOutputDir(const StagedOutputDir&) = delete;
  StagedOutputDir& operator=(const StagedOutputDir&) = delete;

  // Where to write the output file `name`, during the run.
  std::string file(const std::string& name) const;
  // The staging folder itself, for a program that writes several files into a folder it is given.
  const std::string& staging() const { return staging_; }
  // Moves every staged file into `dir`, replacing files of the same names. Call once, after the last write.
  void commit();

 private:
  std::string dir_;
  std::string staging_;
};

}  // namespace rtdr
