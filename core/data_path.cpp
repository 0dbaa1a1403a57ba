// Finding the data files of a build tree or of an installed RTDR. See data_path.h.
#include "core/data_path.h"

#include <cstdlib>
#include <filesystem>

namespace rtdr {

std::string installed_data_dir() { return RTDR_INSTALL_DATA_DIR; }

std::string data_path(const std::string& relative, const std::string& build_tree) {
  namespace fs = std::filesystem;
  std::error_code ec;
  const auto exists = [&ec](const fs::path& p) { return !p.empty() && fs::exists(p, ec); };
  if (const char* dir = std::getenv("RTDR_DATA_DIR"); dir && *dir && exists(fs::path(dir) / relative))
    return (fs::path(dir) / relative).string();
  const fs::path program = fs::read_symlink("/proc/self/exe", ec);  // empty where /proc is not mounted
  if (!ec && !program.empty()) {
    const fs::path installed = program.parent_path().parent_path() / "share" / "rtdr" / relative;
    if (exists(installed)) return installed.string();
  }
  if (exists(build_tree)) return build_tree;
  const fs::path configured = fs::path(RTDR_INSTALL_DATA_DIR) / relative;
  if (exists(configured)) return configured.string();
  return build_tree;
}

}  // namespace rtdr
