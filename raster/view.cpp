// The camera of one frame: projection to pixels and rays through pixels. Conventions in view.h.
#include "raster/view.h"

#include <glm/gtc/matrix_transform.hpp>

#include <cmath>

namespace rtdr {

View make_view(const Scene& scene, const ScenePose& pose, int width, int height, glm::vec2 jitter) {
  View v;
  v.width = width;
  v.height = height;
  v.jitter = jitter;
  v.view_to_world = pose.camera_to_world;
  v.world_to_view = glm::inverse(pose.camera_to_world);
  v.eye = glm::vec3(pose.camera_to_world[3]);
  v.znear = scene.camera.znear;
  v.tan_half_fov_y = std::tan(0.5f * scene.camera.yfov);
  v.tan_half_fov_x = v.tan_half_fov_y * float(width) / float(height);
  // OpenGL perspective; the image's aspect ratio replaces the file's aspectRatio.
  const float aspect = float(width) / float(height);
  glm::mat4 proj = scene.camera.zfar > 0.0f
                       ? glm::perspective(scene.camera.yfov, aspect, scene.camera.znear, scene.camera.zfar)
                       : glm::infinitePerspective(scene.camera.yfov, aspect, scene.camera.znear);
  // Jitter moves the image by (jx, jy) pixels: in NDC that is 2*j/size, and y flips (screen y is down).
  proj[2][0] -= 2.0f * jitter.x / float(width);
  proj[2][1] += 2.0f * jitter.y / float(height);
  v.view_to_clip = proj;
  v.world_to_clip = proj * v.world_to_view;
  return v;
}

glm::vec3 View::project(const glm::vec3& world) const {
  const glm::vec4 clip = world_to_clip * glm::vec4(world, 1.0f);
  const float depth = clip.w;  // w_clip = -z_view = linear depth for a perspective projection
  const glm::vec2 ndc = glm::vec2(clip) / clip.w;
  return {(ndc.x * 0.5f + 0.5f) * float(width), (0.5f - ndc.y * 0.5f) * float(height), depth};
}

glm::vec3 View::view_dir_at_unit_depth(glm::vec2 screen) const {
  // Undo the jitter, then map the screen position to the image plane at depth 1 (view space, -Z forward).
  const glm::vec2 s = screen - jitter;
  const float ndc_x = 2.0f * s.x / float(width) - 1.0f;
  const float ndc_y = 1.0f - 2.0f * s.y / float(height);
  return {ndc_x * tan_half_fov_x, ndc_y * tan_half_fov_y, -1.0f};
}

Ray View::ray_through(glm::vec2 screen) const {
  const glm::vec3 dir_view = view_dir_at_unit_depth(screen);
  const glm::vec3 dir_world = glm::vec3(view_to_world * glm::vec4(dir_view, 0.0f));
  return {eye, glm::normalize(dir_world)};
}

}  // namespace rtdr
