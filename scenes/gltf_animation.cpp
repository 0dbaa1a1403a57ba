// glTF animations -> the nodes' tracks (glTF spec Sec. 3.11 "Animations").
//
// An animation is a list of channels; each channel points one sampler (key times `input`, values `output`,
// an interpolation) at one node property: translation, rotation or scale. All animations of the file play
// together from t = 0, so their channels are merged onto the nodes; two channels driving the same property
// of the same node are an error. Not supported, each with a clear error: CUBICSPLINE interpolation, morph
// target "weights", and channels without a target node (KHR_animation_pointer; see scenes/README.md).
#include "scenes/gltf_parts.h"

#include <glm/gtc/quaternion.hpp>

namespace rtdr::gltf {
namespace {

Interpolation interpolation_of(const Source& src, const std::string& mode, const std::string& what) {
  if (mode == "LINEAR") return Interpolation::Linear;
  if (mode == "STEP") return Interpolation::Step;
  if (mode == "CUBICSPLINE") src.fail(what + " uses CUBICSPLINE interpolation; only LINEAR and STEP are supported");
  src.fail(what + " has unknown interpolation \"" + mode + "\"");
}

// Fills `track` from a sampler: key times, then `components` floats per key made into T by `make`.
template <class T, class Make>
void read_track(const Source& src, const tinygltf::AnimationSampler& sampler, int components, Make make,
                Track<T>& track, const std::string& what) {
  if (!track.empty()) src.fail(what + ": this property is already animated by another channel");
  track.interpolation = interpolation_of(src, sampler.interpolation, what);
  const std::vector<float> times = read_floats(src, sampler.input, 1, what + " input");
  const std::vector<float> flat = read_floats(src, sampler.output, components, what + " output");
  check_keys(src, times, flat.size() / size_t(components), what);
  track.times = times;
  track.values.clear();
  for (size_t k = 0; k < times.size(); ++k) track.values.push_back(make(&flat[k * size_t(components)], k));
}

void load_channel(const Source& src, const tinygltf::Animation& animation, size_t channel_index,
                  const std::string& animation_name, const std::vector<int>& node_of_gltf, Scene& scene) {
  const tinygltf::AnimationChannel& channel = animation.channels[channel_index];
  const std::string what = animation_name + " channel " + std::to_string(channel_index);
  if (channel.target_node < 0)
    src.fail(what + " has no target node (KHR_animation_pointer is not supported; see scenes/README.md)");
  if (size_t(channel.target_node) >= node_of_gltf.size())
    src.fail(what + " targets node " + std::to_string(channel.target_node) + ", out of range");
  if (channel.sampler < 0 || size_t(channel.sampler) >= animation.samplers.size())
    src.fail(what + " refers to sampler " + std::to_string(channel.sampler) + ", out of range");
  const tinygltf::AnimationSampler& sampler = animation.samplers[size_t(channel.sampler)];
  const std::string& path = channel.target_path;
  if (path == "weights") src.fail(what + " animates morph target weights, which are not supported");
  if (path != "translation" && path != "rotation" && path != "scale")
    src.fail(what + " has unknown target path \"" + path + "\"");

  const int node_index = node_of_gltf[size_t(channel.target_node)];
  if (node_index < 0) return;  // the node is not part of the loaded scene
  Node& node = scene.nodes[size_t(node_index)];
  const std::string target = what + " (" + path + " of node '" + node.name + "')";
  auto make_vec3 = [](const float* v, size_t) { return glm::vec3(v[0], v[1], v[2]); };
  if (path == "translation") read_track(src, sampler, 3, make_vec3, node.translation_track, target);
  if (path == "scale") read_track(src, sampler, 3, make_vec3, node.scale_track, target);
  if (path == "rotation") {
    // glTF stores (x, y, z, w); glm::quat's constructor takes (w, x, y, z). Keys must be unit quaternions
    // (spec Sec. 3.11); they are renormalised here, since slerp assumes it.
    auto make_quat = [&](const float* v, size_t k) {
      const glm::quat q(v[3], v[0], v[1], v[2]);
      const float length = glm::length(q);
      if (!(length > 1e-6f)) src.fail(target + " key " + std::to_string(k) + " is not a rotation (zero quaternion)");
      return q / length;
    };
    read_track(src, sampler, 4, make_quat, node.rotation_track, target);
  }
}

}  // namespace

void load_animations(const Source& src, const std::vector<int>& node_of_gltf, Scene& scene) {
  for (size_t a = 0; a < src.model.animations.size(); ++a) {
    const tinygltf::Animation& animation = src.model.animations[a];
    const std::string name = "animation " + label(animation.name, a);
    for (size_t c = 0; c < animation.channels.size(); ++c) load_channel(src, animation, c, name, node_of_gltf, scene);
  }
}

}  // namespace rtdr::gltf
