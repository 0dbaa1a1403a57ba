// Input files are opened only when they are regular files. A FIFO opened for reading blocks until some process
// writes to it (forever, when none does), a folder cannot be read as bytes, and a device such as /dev/zero or
// /dev/urandom never ends: each is refused at once, with a message that says what the path is.
//
// The check cannot be raced: the path is opened first, with O_NONBLOCK (so opening a FIFO returns at once instead
// of waiting for a writer), and what was opened is then checked with fstat; the bytes read are those of the file
// checked, even if the path is replaced in between. A symbolic link to a regular file is a regular file.
#pragma once

#include <cstdint>
#include <istream>
#include <memory>
#include <string>
#include <vector>

namespace rtdr {

// What `path` is, for a message: "a regular file", "a folder", "a FIFO", "a socket", "a character device",
// "a block device", "missing" (or the reason stat gives, "Permission denied").
std::string describe_path_kind(const std::string& path);

class RegularFile {
 public:
  // Opens `path` for reading. Otherwise throws a one-line rtdr::Error "<context>: it is a FIFO, not a regular
  // file" (or "<context>: it does not exist", "<context>: it cannot be opened (<reason>)"); `context` names the
  // file and what it is for ("cannot read EXR file 'in/frame_0001.exr'").
  RegularFile(const std::string& path, const std::string& context);
  ~RegularFile();
  RegularFile(const RegularFile&) = delete;
  RegularFile& operator=(const RegularFile&) = delete;

  // Its size when it was opened, in bytes.
  uint64_t size() const { return size_; }
  const std::string& path() const { return path_; }
  // The file as a buffered binary stream, at its start when opened.
  std::istream& stream() { return stream_; }
  // Every byte, when the file holds at most `limit` of them (its size when opened); otherwise throws
  // "<context>: it holds N bytes, more than the M <limit_reason>". A short read throws too.
  std::vector<unsigned char> read_all(uint64_t limit, const std::string& limit_reason);

 private:
  uint64_t size_ = 0;
  std::string path_, context_;
  std::unique_ptr<std::streambuf> buffer_;  // owns the file descriptor
  std::istream stream_{nullptr};
};

}  // namespace rtdr
