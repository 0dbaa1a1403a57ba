// The files tinygltf reads for a scene: the scene file, and the buffers and images its URIs name.
//
// tinygltf reads them through callbacks (tinygltf::FsCallbacks); ours hold three rules.
// - Regular files only (core/regular_file.h): a FIFO would block the render forever, a folder or a device
//   (/dev/zero) cannot be a buffer. Each is refused at once, saying what the path is.
// - At most the memory budget (core/memory_budget.h): tinygltf reads a whole file before it compares its size
//   with the buffer's byteLength, so a URI naming a 50 GB file would be read whole first.
// - Images are PNG or JPEG (the formats of glTF 2.0 Sec. 3.8.2), and the size a header declares is checked against
//   the memory budget before the decoder allocates for it: a PNG of a few hundred bytes can declare 65535 x 65535
//   pixels, 32 GiB once decoded.
// - Below the scene file's folder. A URI is a path relative to the scene file (glTF 2.0 Sec. 3.3.3); one with
//   `../` that climbs out of the scene's folder is refused, since it could make the renderer read, and draw as
//   geometry or texture, any file the user can read: a scene passed around must not reach into ~/.ssh. A URI
//   such as `textures/../mesh.bin` that stays inside is fine. The test is on the path as written, made absolute
//   and normal (no symbolic link is resolved): a link inside the folder is followed wherever it points, which is
//   how a user who keeps shared assets in a sibling folder lets a scene use them, on purpose
//   (docs/reliability.md, "glTF URIs"). Absolute URIs are not read either: tinygltf joins every URI to the
//   scene's folder, so `/etc/passwd` names `<folder>/etc/passwd`.
//   tinygltf also looks for a URI it does not find beside the scene in the current folder; we never take a file
//   from there.
#include "scenes/gltf_parts.h"

#include "core/memory_budget.h"
#include "core/regular_file.h"

#include "core/error.h"

#include <algorithm>
#include <cstring>
#include <optional>
#include <utility>

namespace rtdr::gltf {
namespace {

namespace fs = std::filesystem;

fs::path absolute_normal(const fs::path& p) {
  std::error_code ec;
  const fs::path a = fs::absolute(p, ec);
  return (ec ? p : a).lexically_normal();
}

bool file_exists(const std::string& path, void* user) {
  auto& files = *static_cast<SceneFiles*>(user);
  return files.allowed(path) && describe_path_kind(path) != "missing";
}

std::string expand_file_path(const std::string& path, void*) { return path; }  // no "~" or variables

bool read_whole_file(std::vector<unsigned char>* out, std::string* err, const std::string& path, void* user) {
  auto& files = *static_cast<SceneFiles*>(user);
  try {
    if (!files.allowed(path)) throw Error(files.refusal());
    RegularFile file(path, files.scene() + ": '" + path + "'");
    *out = file.read_all(memory_budget().bytes, "bytes of memory available (core/memory_budget.h)");
    if (path == files.scene()) files.keep_scene_bytes(*out);  // Scene::content_hash hashes what was parsed
    return true;
  } catch (const Error& e) {
    files.refuse(e.what());
    if (err) *err += e.what();
    return false;
  }
}

// The size an image declares, read from its header before anything is decoded: a PNG's IHDR (width and height,
// big-endian, at bytes 16 to 23), or a JPEG's first start-of-frame segment (markers C0 to CF but C4, C8 and CC:
// precision, height, width). Empty for anything else, or a header cut short.
std::optional<std::pair<uint32_t, uint32_t>> declared_image_size(const unsigned char* b, size_t n) {
  const auto be16 = [&](size_t at) { return uint32_t(b[at]) << 8 | b[at + 1]; };
  const auto be32 = [&](size_t at) { return be16(at) << 16 | be16(at + 2); };
  if (n >= 24 && std::memcmp(b, "\x89PNG\r\n\x1a\n", 8) == 0 && std::memcmp(b + 12, "IHDR", 4) == 0)
    return std::pair{be32(16), be32(20)};
  if (n < 4 || b[0] != 0xFF || b[1] != 0xD8) return std::nullopt;
  for (size_t at = 2; at + 9 <= n && b[at] == 0xFF;) {  // segments: FF, marker, 2-byte length (itself included)
    const unsigned marker = b[at + 1];
    if (marker == 0xFF) {  // a fill byte before the marker
      ++at;
      continue;
    }
    if (marker >= 0xC0 && marker <= 0xCF && marker != 0xC4 && marker != 0xC8 && marker != 0xCC)
      return std::pair{be16(at + 7), be16(at + 5)};
    at += 2 + be16(at + 2);
  }
  return std::nullopt;
}

// tinygltf's image decoder, after the two checks above; tinygltf calls it with SceneFiles as user data.
bool load_image(tinygltf::Image* image, int index, std::string* err, std::string* warn, int width, int height,
                const unsigned char* bytes, int size, void* user) {
  auto& files = *static_cast<SceneFiles*>(user);
  try {
    const std::string what = files.scene() + ": image " + label(image->name, size_t(std::max(index, 0)));
    const auto declared = declared_image_size(bytes, size_t(std::max(size, 0)));
    if (!declared) throw Error(what + " is neither PNG nor JPEG (the formats of glTF 2.0)");
    // Decoding holds up to 8 bytes a pixel (4 channels of 16 bits), tinygltf's copy of them, and our texture of 4
    // floats (gltf_materials.cpp): 32 bytes a pixel.
    const uint64_t pixels = uint64_t(declared->first) * declared->second;
    require_within_budget(saturating_product(pixels, 32),
                          what + " declares " + std::to_string(declared->first) + "x" +
                              std::to_string(declared->second) + " pixels, whose decoding",
                          memory_budget());
  } catch (const Error& e) {
    files.refuse(e.what());
    if (err) *err += e.what();
    return false;
  }
  return tinygltf::LoadImageData(image, index, err, warn, width, height, bytes, size, nullptr);
}

bool write_whole_file(std::string* err, const std::string&, const std::vector<unsigned char>&, void*) {
  if (err) *err += "the loader writes no files";
  return false;
}

}  // namespace

SceneFiles::SceneFiles(const std::string& scene_path)
    : scene_(scene_path),
      // tinygltf's base folder: the scene path up to its last '/', "" for a bare file name.
      base_(scene_path.find_last_of('/') == std::string::npos ? std::string()
                                                              : scene_path.substr(0, scene_path.find_last_of('/'))),
      folder_(absolute_normal(base_.empty() ? fs::path(".") : fs::path(base_))) {}

void SceneFiles::attach(tinygltf::TinyGLTF& reader) {
  reader.SetFsCallbacks({&file_exists, &expand_file_path, &read_whole_file, &write_whole_file, this});
  reader.SetImageLoader(&load_image, this);
}

bool SceneFiles::allowed(const std::string& path) {
  if (path == scene_) return true;
  // The candidates beside the scene start with its folder as tinygltf joined it; the others are tinygltf's
  // second place to look, the current folder, never used.
  const bool beside_scene = base_.empty() || path.rfind(base_ + "/", 0) == 0;
  if (!beside_scene) return false;
  const fs::path relative = absolute_normal(path).lexically_relative(folder_);
  if (!relative.empty() && *relative.begin() != "..") return true;
  refuse("'" + path + "' is outside the scene's folder '" + folder_.string() +
         "': a URI may not climb out of it with ../ (docs/reliability.md, \"glTF URIs\")");
  return false;
}

void SceneFiles::refuse(const std::string& why) {
  if (refusal_.empty()) refusal_ = why.rfind(scene_ + ": ", 0) == 0 ? why : scene_ + ": " + why;
}

}  // namespace rtdr::gltf
