#include "scenes/catalog.h"

#include "core/data_path.h"

#include <algorithm>
#include <filesystem>

namespace rtdr {

std::string shipped_scene_dir() { return data_path("scenes", RTDR_SCENE_DIR); }

std::vector<std::string> shipped_scene_names() {
  std::vector<std::string> names;
  std::error_code ec;
  for (const auto& entry : std::filesystem::directory_iterator(shipped_scene_dir(), ec))
    if (entry.path().extension() == ".gltf") names.push_back(entry.path().stem().string());
  std::sort(names.begin(), names.end());
  return names;
}

std::string shipped_scene_path(const std::string& name) { return shipped_scene_dir() + "/" + name + ".gltf"; }

}  // namespace rtdr
