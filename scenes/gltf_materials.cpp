// glTF materials -> Scene::materials and Scene::textures (glTF spec Sec. 3.9 "Materials").
//
// Read: baseColorFactor, baseColorTexture (its image decoded from sRGB to linear), metallicFactor,
// roughnessFactor, emissiveFactor, KHR_materials_emissive_strength, doubleSided (which faces emit; nothing
// else: both faces are drawn and shaded regardless), and our animated emissive strength in
// the material's extras "rtdr_emissive_strength" (format and reason in scenes/README.md). The other
// textures (normal, occlusion, metallic-roughness, emissive) are ignored.
#include "scenes/gltf_parts.h"

#include "core/color.h"

#include <cmath>
#include <cstring>
#include <map>

namespace rtdr::gltf {
namespace {

// A decoded image as a linear RGBA texture. tinygltf decodes PNG and JPEG with stb_image, expanded to
// 4 channels of 8 or 16 bits, row 0 at the top (which is v = 0 in glTF). Colour is stored sRGB-encoded
// (glTF spec Sec. 3.9.2: "baseColorTexture ... MUST be encoded with the sRGB transfer function"); alpha
// is linear.
Texture decode_image(const Source& src, int image_index) {
  const tinygltf::Image& image = src.model.images[size_t(image_index)];
  const std::string what = "image " + label(image.name, size_t(image_index));
  if (image.width <= 0 || image.height <= 0 || image.component < 1 || image.component > 4)
    src.fail(what + " was not decoded (only PNG and JPEG images are supported)");
  if (image.bits != 8 && image.bits != 16) src.fail(what + " has " + std::to_string(image.bits) + "-bit channels");
  const size_t bytes = size_t(image.bits / 8);
  const size_t channels = size_t(image.component);
  const size_t texel_count = size_t(image.width) * size_t(image.height);
  if (image.image.size() != texel_count * channels * bytes) src.fail(what + " has the wrong number of bytes");

  // Channel c of texel i as a value in [0, 1].
  auto channel = [&](size_t i, size_t c) {
    const unsigned char* p = image.image.data() + (i * channels + c) * bytes;
    if (bytes == 1) return float(*p) / 255.0f;
    uint16_t v;
    std::memcpy(&v, p, sizeof v);
    return float(v) / 65535.0f;
  };

  Texture texture;
  texture.width = image.width;
  texture.height = image.height;
  texture.texels.resize(texel_count);
  for (size_t i = 0; i < texel_count; ++i) {
    // 1 channel is grey, 2 are grey + alpha, 3 are RGB, 4 are RGBA.
    const bool grey = channels <= 2;
    const float r = channel(i, 0);
    const float g = grey ? r : channel(i, 1);
    const float b = grey ? r : channel(i, 2);
    const float a = channels == 2 ? channel(i, 1) : channels == 4 ? channel(i, 3) : 1.0f;
    texture.texels[i] = glm::vec4(srgb_decode(r), srgb_decode(g), srgb_decode(b), a);
  }
  return texture;
}

// A number from the file that must be within [lo, hi] and finite as the float it is stored as (1e39 is a
// finite double but an infinite float).
float checked(const Source& src, double value, double lo, double hi, const std::string& what) {
  const float f = float(value);
  if (!std::isfinite(f) || value < lo || value > hi)
    src.fail(what + " is " + std::to_string(value) + ", outside [" + std::to_string(lo) + ", " + std::to_string(hi) +
             "] or beyond the largest float");
  return f;
}

// Material extras {"rtdr_emissive_strength": {"times": [...], "values": [...], "interpolation": ...}}.
Track<float> emissive_strength_track(const Source& src, const tinygltf::Value& extras, const std::string& what) {
  Track<float> track;
  if (!extras.IsObject() || !extras.Has("rtdr_emissive_strength")) return track;
  const std::string name = what + " extras rtdr_emissive_strength";
  const tinygltf::Value& spec = extras.Get("rtdr_emissive_strength");
  if (!spec.IsObject() || !spec.Get("times").IsArray() || !spec.Get("values").IsArray())
    src.fail(name + " must be an object with arrays \"times\" and \"values\"");

  // Both arrays as numbers, each finite; strengths are also non-negative.
  auto numbers = [&](const char* key, double lo) {
    std::vector<float> out;
    const tinygltf::Value& array = spec.Get(key);
    for (size_t k = 0; k < array.ArrayLen(); ++k) {
      const tinygltf::Value& v = array.Get(int(k));
      if (!v.IsNumber()) src.fail(name + " " + key + "[" + std::to_string(k) + "] is not a number");
      out.push_back(
          checked(src, v.GetNumberAsDouble(), lo, HUGE_VAL, name + " " + key + "[" + std::to_string(k) + "]"));
    }
    return out;
  };
  track.times = numbers("times", -HUGE_VAL);
  track.values = numbers("values", 0.0);
  check_keys(src, track.times, track.values.size(), name);

  const tinygltf::Value& interpolation = spec.Get("interpolation");
  const std::string mode = interpolation.IsString() ? interpolation.Get<std::string>() : "LINEAR";
  if (mode != "LINEAR" && mode != "STEP") src.fail(name + " interpolation is \"" + mode + "\"; use LINEAR or STEP");
  track.interpolation = mode == "STEP" ? Interpolation::Step : Interpolation::Linear;
  return track;
}

// glTF's textures point at images through `source`; each image is decoded once, however many use it.
int base_color_texture(const Source& src, const tinygltf::TextureInfo& info, std::map<int, int>& texture_of_image,
                       Scene& scene, const std::string& what) {
  const tinygltf::Model& m = src.model;
  if (info.texCoord != 0)
    src.fail(what + " baseColorTexture uses TEXCOORD_" + std::to_string(info.texCoord) + "; only TEXCOORD_0 is read");
  if (size_t(info.index) >= m.textures.size())
    src.fail(what + " refers to texture " + std::to_string(info.index) + ", out of range");
  const int image = m.textures[size_t(info.index)].source;
  if (image < 0 || size_t(image) >= m.images.size())
    src.fail(what + " texture " + std::to_string(info.index) + " refers to image " + std::to_string(image) +
             ", out of range");
  auto [it, inserted] = texture_of_image.try_emplace(image, int(scene.textures.size()));
  if (inserted) scene.textures.push_back(decode_image(src, image));
  return it->second;
}

}  // namespace

void load_materials(const Source& src, Scene& scene) {
  std::map<int, int> texture_of_image;
  for (size_t i = 0; i < src.model.materials.size(); ++i) {
    const tinygltf::Material& gm = src.model.materials[i];
    const tinygltf::PbrMetallicRoughness& pbr = gm.pbrMetallicRoughness;
    const std::string what = "material " + label(gm.name, i);
    Material m;
    m.name = gm.name.empty() ? "material" + std::to_string(i) : gm.name;

    // Factors; the glTF spec bounds each to [0, 1] (Sec. 5.19, 5.22).
    if (pbr.baseColorFactor.size() != 4) src.fail(what + " baseColorFactor does not have 4 numbers");
    for (int c = 0; c < 4; ++c)
      m.base_color[c] = checked(src, pbr.baseColorFactor[size_t(c)], 0, 1, what + " baseColorFactor");
    m.metallic = checked(src, pbr.metallicFactor, 0, 1, what + " metallicFactor");
    m.roughness = checked(src, pbr.roughnessFactor, 0, 1, what + " roughnessFactor");
    if (gm.emissiveFactor.size() != 3) src.fail(what + " emissiveFactor does not have 3 numbers");
    for (int c = 0; c < 3; ++c)
      m.emissive[c] = checked(src, gm.emissiveFactor[size_t(c)], 0, 1, what + " emissiveFactor");
    if (pbr.baseColorTexture.index >= 0)
      m.base_color_texture = base_color_texture(src, pbr.baseColorTexture, texture_of_image, scene, what);

    // KHR_materials_emissive_strength: {"emissiveStrength": s}, s >= 0, default 1.
    const auto ext = gm.extensions.find("KHR_materials_emissive_strength");
    if (ext != gm.extensions.end() && ext->second.IsObject() && ext->second.Has("emissiveStrength")) {
      const tinygltf::Value& s = ext->second.Get("emissiveStrength");
      if (!s.IsNumber()) src.fail(what + " emissiveStrength is not a number");
      m.emissive_strength = checked(src, s.GetNumberAsDouble(), 0, HUGE_VAL, what + " emissiveStrength");
    }
    m.emissive_strength_track = emissive_strength_track(src, gm.extras, what);
    // doubleSided (glTF spec Sec. 3.9.5, default false): a double-sided emitter emits from both faces.
    m.double_sided = gm.doubleSided;
    scene.materials.push_back(std::move(m));
  }
}

}  // namespace rtdr::gltf
