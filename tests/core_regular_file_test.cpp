// Tests of core/regular_file.cpp: a regular file (and a link to one) opens and reads whole; a missing path, a
// folder, a FIFO, a device and a file over the size limit are refused with one line saying what the path is. The
// FIFO has a writer (this test holds it open), so that a regression that opened it blocking would read it instead
// of hanging: the test then fails on the missing refusal.
#include "core/regular_file.h"

#include "core/error.h"

#include <catch2/catch.hpp>

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>

namespace fs = std::filesystem;
using namespace rtdr;

namespace {

fs::path scratch_dir() {
  const fs::path dir = fs::temp_directory_path() / ("rtdr_regular_file_test_" + std::to_string(::getpid()));
  fs::remove_all(dir);
  fs::create_directories(dir);
  return dir;
}

std::string refusal(const std::string& path) {
  try {
    RegularFile file(path, "reading '" + path + "'");
  } catch (const Error& e) {
    return e.what();
  }
  return "(opened)";
}

}  // namespace

TEST_CASE("regular file: a file and a link to one open and read whole, with their size") {
  const fs::path dir = scratch_dir();
  std::ofstream(dir / "data.bin", std::ios::binary) << std::string("\0abc\xff", 5);
  fs::create_symlink(dir / "data.bin", dir / "link.bin");
  for (const fs::path& p : {dir / "data.bin", dir / "link.bin"}) {
    RegularFile file(p.string(), "test");
    CHECK(file.size() == 5);
    CHECK(file.read_all(5, "bytes") == std::vector<unsigned char>{0, 'a', 'b', 'c', 0xff});
    CHECK(file.read_all(100, "bytes").size() == 5);  // again, from the start
  }
  RegularFile file((dir / "data.bin").string(), "reading 'data.bin'");
  CHECK_THROWS_WITH(file.read_all(4, "bytes allowed"), "reading 'data.bin': it holds 5 bytes, more than the 4 bytes allowed");
  fs::remove_all(dir);
}

TEST_CASE("regular file: missing, folder, FIFO and device are refused at once, saying what the path is") {
  const fs::path dir = scratch_dir();
  fs::create_directories(dir / "folder");
  REQUIRE(::mkfifo((dir / "fifo").c_str(), 0600) == 0);
  const int writer = ::open((dir / "fifo").c_str(), O_RDWR | O_NONBLOCK);  // a FIFO with a writer never blocks
  REQUIRE(writer >= 0);
  const std::string fifo = (dir / "fifo").string(), folder = (dir / "folder").string();
  CHECK(refusal(fifo) == "reading '" + fifo + "': it is a FIFO, not a regular file");
  CHECK(refusal(folder) == "reading '" + folder + "': it is a folder, not a regular file");
  CHECK(refusal("/dev/null") == "reading '/dev/null': it is a character device, not a regular file");
  CHECK(refusal((dir / "missing").string()) == "reading '" + (dir / "missing").string() + "': it does not exist");
  CHECK(refusal((dir / "folder" / "x" / "y").string()).find("does not exist") != std::string::npos);
  CHECK(describe_path_kind(fifo) == "a FIFO");
  CHECK(describe_path_kind((dir / "missing").string()) == "missing");
  ::close(writer);
  fs::remove_all(dir);
}
