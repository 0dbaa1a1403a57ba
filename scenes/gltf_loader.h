// Loading a glTF 2.0 file into the Scene model (scenes/scene.h), with tinygltf.
//
// What is loaded, what is ignored and the conventions (metres, +Y up, the camera looks down -Z, frame f at
// t = f / fps) are in scenes/README.md. Everything is validated: any problem with the file throws
// rtdr::Error with one line "<file>: <problem>", never a crash.
#pragma once

#include "scenes/scene.h"

#include <string>

namespace rtdr {

// A bare name such as "cornell" is a shipped scene, shipped_scene_path("cornell") (scenes/catalog.h); anything
// containing a '/' or ending in .gltf or .glb is a path.
std::string resolve_scene_path(const std::string& name_or_path);

// Loads the scene from a .gltf (JSON, buffers embedded or beside it) or .glb (binary) file.
Scene load_scene(const std::string& name_or_path);

}  // namespace rtdr
