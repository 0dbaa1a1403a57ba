#include "core/atomic_file.h"

#include "core/error.h"

#include <unistd.h>

#include <filesystem>
#include <fstream>

namespace rtdr {

void write_file_atomically(const std::string& path, const std::function<void(const std::string& tmp_path)>& write) {
  // The pid keeps two processes writing the same destination from sharing a temporary.
  const std::string tmp = path + ".tmp-" + std::to_string(::getpid());
  std::error_code ec;
  try {
    write(tmp);
  } catch (const std::exception& e) {
    std::filesystem::remove(tmp, ec);
    throw Error("cannot write '" + path + "': " + e.what());
  }
  std::filesystem::rename(tmp, path, ec);
  if (ec) {
    std::filesystem::remove(tmp, ec);
    throw Error("cannot write '" + path + "': " + ec.message());
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

}  // namespace rtdr
