// libFuzzer harness for the glTF loader (scenes/gltf_loader.h). Each input is one scene file: binary glTF
// (.glb) when it starts with the GLB magic "glTF", JSON glTF (.gltf) otherwise. The seeds
// (fuzz/corpus/gltf_loader_fuzz/) embed their buffers and images, so one input is a whole scene.
//
// The loader promises a one-line rtdr::Error for every bad file. A finding is anything else: a crash, a
// sanitizer report, a hang, or any other exception escaping (libFuzzer reports the abort it causes).
// A scene that loads is then used the way the renderer uses it (poses, emissive strengths, texture
// lookups), so values the loader accepted but cannot be used also show up.
#include "fuzz/harness.h"

#include "core/error.h"
#include "scenes/gltf_loader.h"

#include <cstring>

namespace {

// Everything the renderer asks of a Scene, at the times of frames 0 and 1 and at a time past any key.
void use_scene(const rtdr::Scene& scene) {
  for (const double t : {scene.time_of_frame(0), scene.time_of_frame(1), 1e6}) {
    const rtdr::ScenePose pose = scene.pose(t);
    for (const rtdr::Instance& instance : scene.instances) {
      const rtdr::Material& m = scene.material_of_mesh(instance.mesh);
      static_cast<void>(scene.emissive_strength(m, t));
      if (m.base_color_texture >= 0)
        static_cast<void>(scene.textures[size_t(m.base_color_texture)].sample({0.3f, 0.7f}));
    }
    static_cast<void>(pose);
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  static rtdr::fuzz::InputFile gltf_file("scene.gltf"), glb_file("scene.glb");
  const bool glb = size >= 4 && std::memcmp(data, "glTF", 4) == 0;
  const std::string& path = (glb ? glb_file : gltf_file).write(data, size);
  try {
    use_scene(rtdr::load_scene(path));
  } catch (const rtdr::Error& e) {  // the promised outcome for a bad file
    rtdr::fuzz::expected_error(e);
  }
  return 0;
}
