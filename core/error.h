// User-facing errors. Anything that is the user's fault (a missing scene, a malformed EXR, a bad --size)
// throws rtdr::Error with a one-line message that names the file or flag; `rtdr` prints it as
// "rtdr: error: <message>" and exits with status 1. Programming errors stay asserts.
#pragma once

#include <stdexcept>
#include <string>

namespace rtdr {

struct Error : std::runtime_error {
  using std::runtime_error::runtime_error;
};

// An Error caused by a failed system call, with its errno, for a caller that treats some causes apart (a read-only
// cache is read, a full one fails the run: eval/frame_cache.h).
struct SystemError : Error {
  SystemError(const std::string& message, int code) : Error(message), code(code) {}
  int code;
};

}  // namespace rtdr
