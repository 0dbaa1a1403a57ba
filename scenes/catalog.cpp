#include "scenes/catalog.h"

#include <algorithm>
#include <filesystem>

namespace rtdr {

std::vector<std::string> shipped_scene_names() {
  std::vector<std::string> names;
  std::error_code ec;
  for (const auto& entry : std::filesystem::directory_iterator(RTDR_SCENE_DIR, ec))
    if (entry.path().extension() == ".gltf") names.push_back(entry.path().stem().string());
  std::sort(names.begin(), names.end());
  return names;
}

std::string shipped_scene_path(const std::string& name) { return std::string(RTDR_SCENE_DIR) + "/" + name + ".gltf"; }

}  // namespace rtdr
