// Input files opened only when they are regular files. See regular_file.h.
#include "core/regular_file.h"

#include "core/error.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <ext/stdio_filebuf.h>

#include <cerrno>
#include <cstring>

namespace rtdr {
namespace {

std::string kind_of(mode_t mode) {
  if (S_ISREG(mode)) return "a regular file";
  if (S_ISDIR(mode)) return "a folder";
  if (S_ISFIFO(mode)) return "a FIFO";
  if (S_ISSOCK(mode)) return "a socket";
  if (S_ISCHR(mode)) return "a character device";
  if (S_ISBLK(mode)) return "a block device";
  return "not a file";
}

}  // namespace

std::string describe_path_kind(const std::string& path) {
  struct stat st {};
  if (::stat(path.c_str(), &st) == 0) return kind_of(st.st_mode);
  return errno == ENOENT || errno == ENOTDIR ? "missing" : std::strerror(errno);
}

RegularFile::RegularFile(const std::string& path, const std::string& context) : path_(path), context_(context) {
  const std::string named = context + ": it";
  // What the path is, before opening it: opening a device can do things (a terminal, a tape).
  const std::string kind = describe_path_kind(path);
  if (kind == "missing") throw Error(named + " does not exist");
  if (kind.rfind("a ", 0) != 0) throw Error(named + " cannot be opened (" + kind + ")");  // stat's reason
  if (kind != "a regular file") throw Error(named + " is " + kind + ", not a regular file");
  // Then open it, O_NONBLOCK so that a FIFO put in its place meanwhile cannot block the open, and check what was
  // opened: that is what is read.
  const int fd = ::open(path.c_str(), O_RDONLY | O_NONBLOCK | O_NOCTTY | O_CLOEXEC);
  if (fd < 0) throw Error(named + " cannot be opened (" + std::strerror(errno) + ")");
  struct stat st {};
  const bool stated = ::fstat(fd, &st) == 0;
  if (!stated || !S_ISREG(st.st_mode)) {
    const std::string opened = stated ? kind_of(st.st_mode) : std::string(std::strerror(errno));
    ::close(fd);
    throw Error(named + " is " + opened + ", not a regular file");
  }
  size_ = uint64_t(st.st_size);
  // A regular file never blocks; reads go back to the ordinary mode all the same.
  ::fcntl(fd, F_SETFL, ::fcntl(fd, F_GETFL) & ~O_NONBLOCK);
  buffer_ = std::make_unique<__gnu_cxx::stdio_filebuf<char>>(fd, std::ios::in | std::ios::binary);  // closes fd
  stream_.rdbuf(buffer_.get());
}

RegularFile::~RegularFile() = default;

std::vector<unsigned char> RegularFile::read_all(uint64_t limit, const std::string& limit_reason) {
  if (size_ > limit)
    throw Error(context_ + ": it holds " + std::to_string(size_) + " bytes, more than the " + std::to_string(limit) +
                " " + limit_reason);
  std::vector<unsigned char> bytes(size_);
  stream_.seekg(0);
  if (!stream_.read(reinterpret_cast<char*>(bytes.data()), std::streamsize(size_)))
    throw Error(context_ + ": it cannot be read whole (" + std::to_string(stream_.gcount()) + " of " +
                std::to_string(size_) + " bytes)");
  return bytes;
}

}  // namespace rtdr
