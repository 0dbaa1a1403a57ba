// Evaluating the Scene at time t: node transforms through the hierarchy, and animated light strength.
#include "scenes/scene.h"

#include <glm/gtc/matrix_inverse.hpp>
#include <glm/gtc/matrix_transform.hpp>

#include <cmath>

namespace rtdr {

glm::vec4 Texture::sample(glm::vec2 uv) const {
  // Continuous texel coordinates with texel centres at +0.5, wrapped (REPEAT) per lookup.
  const float fx = uv.x * float(width) - 0.5f;
  const float fy = uv.y * float(height) - 0.5f;
  const float x0f = std::floor(fx), y0f = std::floor(fy);
  const float ax = fx - x0f, ay = fy - y0f;
  auto wrap = [](int i, int n) { return ((i % n) + n) % n; };
  auto texel = [&](int x, int y) { return texels[size_t(wrap(y, height)) * size_t(width) + size_t(wrap(x, width))]; };
  const int x0 = int(x0f), y0 = int(y0f);
  const glm::vec4 top = glm::mix(texel(x0, y0), texel(x0 + 1, y0), ax);
  const glm::vec4 bottom = glm::mix(texel(x0, y0 + 1), texel(x0 + 1, y0 + 1), ax);
  return glm::mix(top, bottom, ay);
}

glm::mat4 Node::local_matrix(double t) const {
  const glm::vec3 T = translation_track.empty() ? translation : translation_track.sample(t);
  const glm::quat R = rotation_track.empty() ? rotation : rotation_track.sample(t);
  const glm::vec3 S = scale_track.empty() ? scale : scale_track.sample(t);
  // glTF spec Sec. 3.5.3: the local transform is T * R * S.
  return glm::translate(glm::mat4(1.0f), T) * glm::mat4_cast(glm::normalize(R)) * glm::scale(glm::mat4(1.0f), S);
}

glm::mat4 Scene::node_to_world(int node, double t) const {
  glm::mat4 m(1.0f);
  for (int n = node; n >= 0; n = nodes[size_t(n)].parent) m = nodes[size_t(n)].local_matrix(t) * m;
  return m;
}

ScenePose Scene::pose(double t) const {
  ScenePose p;
  p.t = t;
  // Parents precede children, so one pass in order evaluates every node's world matrix once.
  std::vector<glm::mat4> world(nodes.size());
  for (size_t n = 0; n < nodes.size(); ++n) {
    const glm::mat4 local = nodes[n].local_matrix(t);
    world[n] = nodes[n].parent >= 0 ? world[size_t(nodes[n].parent)] * local : local;
  }
  p.instance_to_world.reserve(instances.size());
  p.normal_to_world.reserve(instances.size());
  for (const Instance& inst : instances) {
    const glm::mat4& m = world[size_t(inst.node)];
    p.instance_to_world.push_back(m);
    p.normal_to_world.push_back(glm::inverseTranspose(glm::mat3(m)));
  }
  if (camera.node >= 0) p.camera_to_world = world[size_t(camera.node)];
  return p;
}

const Material& Scene::material_of_mesh(int mesh) const {
  static const Material kDefault{};  // glTF spec Sec. 3.9.6 "Default Material"
  const int m = meshes[size_t(mesh)].material;
  return m >= 0 ? materials[size_t(m)] : kDefault;
}

float Scene::emissive_strength(const Material& m, double t) const {
  return m.emissive_strength_track.empty() ? m.emissive_strength : m.emissive_strength_track.sample(t);
}

}  // namespace rtdr
