// The scenes that ship with RTDR: every scenes/*.gltf, by name (file stem), sorted.
#pragma once

#include <string>
#include <vector>

namespace rtdr {

// Where they are (core/data_path.h): <prefix>/share/rtdr/scenes for an installed RTDR, else the scenes/ folder of
// the source tree the binary was built from.
std::string shipped_scene_dir();
std::vector<std::string> shipped_scene_names();
// <shipped_scene_dir()>/<name>.gltf.
std::string shipped_scene_path(const std::string& name);

}  // namespace rtdr
