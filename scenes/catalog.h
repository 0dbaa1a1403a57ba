// The scenes that ship with RTDR: every scenes/*.gltf, by name (file stem), sorted.
#pragma once

#include <string>
#include <vector>

namespace rtdr {

std::vector<std::string> shipped_scene_names();
// scenes/<name>.gltf in the source tree the binary was built from.
std::string shipped_scene_path(const std::string& name);

}  // namespace rtdr
