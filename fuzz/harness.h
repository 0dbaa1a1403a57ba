// What the three harnesses share: the input file the loaders read, and the printing of expected errors.
#pragma once

#include <unistd.h>

#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <string>

namespace rtdr::fuzz {

// The loaders under test read files, not memory: each fuzz input is written to one file per process,
// /tmp/rtdr_fuzz_<pid>_<name>, overwritten by the next input and removed when the process ends.
// The pid keeps parallel fuzzers (libFuzzer's -jobs, or two harnesses at once) off each other's file.
class InputFile {
 public:
  // `name` ends in the extension the loader looks at, e.g. "scene.gltf".
  explicit InputFile(const std::string& name)
      : path_("/tmp/rtdr_fuzz_" + std::to_string(getpid()) + "_" + name) {}
  ~InputFile() { std::remove(path_.c_str()); }
  InputFile(const InputFile&) = delete;
  InputFile& operator=(const InputFile&) = delete;

  // Replaces the file's contents with the fuzz input; returns its path.
  const std::string& write(const uint8_t* data, size_t size) {
    std::FILE* f = std::fopen(path_.c_str(), "wb");
    // Failing to write is a broken machine (disk full, /tmp missing), not a finding: stop loudly.
    if (!f || std::fwrite(data, 1, size, f) != size || std::fclose(f) != 0) {
      std::perror(path_.c_str());
      std::exit(2);
    }
    return path_;
  }
  const std::string& path() const { return path_; }

 private:
  std::string path_;
};

// An error the project promises for bad input (rtdr::Error, CLI::ParseError): not a finding. Printed only
// when RTDR_FUZZ_VERBOSE is set, to see how far a seed gets: `RTDR_FUZZ_VERBOSE=1 build-fuzz/fuzz/<harness> FILE`.
inline void expected_error(const std::exception& e) {
  static const bool verbose = std::getenv("RTDR_FUZZ_VERBOSE") != nullptr;
  if (verbose) std::fprintf(stderr, "expected error: %s\n", e.what());
}

}  // namespace rtdr::fuzz
