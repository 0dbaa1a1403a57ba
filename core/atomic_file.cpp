#include "core/atomic_file.h"

#include "core/error.h"

#include <unistd.h>

#include <atomic>
#include <filesystem>
#include <fstream>

namespace rtdr {

void write_file_atomically(const std::string& path, const std::function<void(const std::string& tmp_path)>& write) {
  // The pid and a per-process counter keep concurrent writers of one destination apart.
  static std::atomic<unsigned> counter{0};
  const std::string tmp = path + ".tmp-" + std::to_string(::getpid()) + "-" + std::to_string(counter++);
  std::error_code ec;
  try {
    write(tmp);
  } catch (const std::exception& e) {
    std::filesystem::remove(tmp, ec);
    throw Error("cannot write '" + path + "': " + e.what());
  }
  std::filesystem::rename(tmp, path, ec);
  if (ec) {
    const std::string reason = ec.message();  // before remove() overwrites ec
    std::filesystem::remove(tmp, ec);
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

}  // namespace rtdr
