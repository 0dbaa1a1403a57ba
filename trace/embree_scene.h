// The Embree 3 scene of one frame: every instance's triangles in world space at the pose's time t, for the
// secondary and shadow rays of [SVGF17 Sec. 3].
//
// Geometry ids equal instance indices, so an Embree hit names the same (instance, triangle) as the
// visibility buffer. The scene is rebuilt per pose (our scenes are small); the device is shared.
#pragma once

#include "core/frame.h"
#include "raster/view.h"
#include "scenes/scene.h"

#include <embree3/rtcore.h>

#include <cstdint>

namespace rtdr {

// One Embree device per process, created with an error callback that turns Embree errors into
// rtdr::Error. Thread-safe to call.
RTCDevice embree_device();

// The far end of a ray that may go anywhere.
inline constexpr float kRayInfinity = 1e30f;

struct Hit {
  uint32_t instance = kInvalidId;  // when the ray escapes
  uint32_t triangle = kInvalidId;
  glm::vec2 bary{0.0f};             // Embree's (u, v): weights of vertices 1 and 2
  float t = 0.0f;                   // distance along the (normalised) ray
};

class EmbreeScene {
 public:
  EmbreeScene(const Scene& scene, const ScenePose& pose);
  ~EmbreeScene();
  EmbreeScene(const EmbreeScene&) = delete;
  EmbreeScene& operator=(const EmbreeScene&) = delete;

  // Closest hit along the ray in [tnear, tfar].
  Hit intersect(const Ray& ray, float tnear = 0.0f, float tfar = kRayInfinity) const;
  // True when anything blocks the segment (tnear, tfar) (rtcOccluded1).
  bool occluded(const Ray& ray, float tnear, float tfar) const;

  RTCScene handle() const { return scene_; }

 private:
  RTCScene scene_ = nullptr;
};

}  // namespace rtdr
