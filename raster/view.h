// The camera of one frame: everything needed to go between world space and pixels.
//
// Conventions, used by every stage and by docs/buffers.md:
// - Pixel (x, y) covers [x, x+1) x [y, y+1); its centre is (x + 0.5, y + 0.5). x grows right, y grows down.
// - "Screen position" is a continuous position in those pixel units.
// - "Depth" is linear view depth: distance along the camera's viewing axis (-Z of the camera node), > 0.
// - Clip space is OpenGL's (w_clip = depth), with an optional sub-pixel jitter (TAA) added in screen space.
#pragma once

#include "scenes/scene.h"

#include <glm/glm.hpp>

namespace rtdr {

struct Ray {
  glm::vec3 origin;
  glm::vec3 direction;  // normalised
};

struct View {
  int width = 0;
  int height = 0;
  glm::mat4 world_to_view{1.0f};  // the inverse of the camera node's world transform
  glm::mat4 view_to_world{1.0f};
  glm::mat4 view_to_clip{1.0f};   // perspective, jitter included
  glm::mat4 world_to_clip{1.0f};
  glm::vec3 eye{0.0f};            // camera position, world space
  float tan_half_fov_x = 1.0f;    // half-extent of the image plane at depth 1
  float tan_half_fov_y = 1.0f;
  float znear = 0.05f;
  glm::vec2 jitter{0.0f};         // sub-pixel offset of the projection, pixels

  // World point -> (screen x, screen y, depth). Only meaningful when depth > 0.
  glm::vec3 project(const glm::vec3& world) const;
  // The world-space ray through a screen position (pixel centres at +0.5), jitter included.
  Ray ray_through(glm::vec2 screen) const;
  // View-space direction (z = -1 plane) through a screen position: the point at depth d is d * dir.
  glm::vec3 view_dir_at_unit_depth(glm::vec2 screen) const;
};

// The camera of `scene` at pose time, for a width x height image.
View make_view(const Scene& scene, const ScenePose& pose, int width, int height, glm::vec2 jitter = {0.0f, 0.0f});

}  // namespace rtdr
