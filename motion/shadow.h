// Shadow motion vectors [TRMV21 Eq. 3]: where the shadow a pixel lies in was in the previous frame.
//
// Pass: shadow_motion(geometry, frame) -> motion.shadow per pixel.
//   in:  per pixel the primary vertex's shadow ray as the path tracer recorded it (path.light, path.blocker and
//        their instances, trace/path_tracer.h), the visibility buffer (the receiver), the poses and Views of
//        this frame and the previous one
//   out: motion.shadow = x^V_{i-1} - x_i in pixels, and motion.shadow.valid (1 where Eq. 3 gives a point)
//
// A shadow moves with its light and its blocker, not with the surface it falls on: under a moving fence the
// floor is still, its back-projected motion is 0, and history fetched along it smears the slats' shadows over
// the frames (the ghosting of [TRMV21 Fig. 8]). TRMV21 Eq. 3 follows the shadow instead:
//
//   x^V_{i-1} = P_{i-1} intersect[ T^{-1} l_i -> T^{-1} b_i ; T^{-1} plane(s_i) ],   m^V = x^V_{i-1} - x_i
//
// The line from the light sample l_i through the blocker b_i, both carried back to the previous frame with
// their own instance's motion T^{-1} = M_k(t_{i-1}) M_k(t_i)^{-1}, meets the receiver's plane (the tangent plane of
// s_i, carried back with the receiver's motion) where the same shadow point was; P_{i-1} projects it with the
// previous camera.
//
// Which point is x_i (our choice, motion/README.md, "Shadow motion: the choices"). The shadow ray starts a
// little off the surface (trace/path_tracer.cpp, offset_origin), so the line l_i -> b_i meets the receiver's
// plane at s^_i, up to a millimetre or so from s_i (the pixel's `position`): a few tenths of a pixel. We use
// that point in both frames: x_i = P_i(s^_i) and x^V_{i-1} = P_{i-1}(s^_{i-1}), so that m^V is the motion of
// one point, the ray's own. Then a static scene gives m^V = the surface motion exactly (both are the jitter
// difference), and the closed form of a test is the ray's line s = l + t (b - l). Using the pixel centre for
// x_i, as the paper writes it, would add the offset's sub-pixel error to every vector.
//
// Valid where (else motion.shadow is (0, 0) and .valid is 0):
// - the pixel sees a surface and its shadow ray was blocked (a blocker instance is recorded);
// - the line is not parallel to the receiver's plane, in either frame: |n . (b - l)| > kShadowParallelCosine |b - l|;
// - the receiver lies beyond the blocker, seen from the light: t > 1 on the line l + t (b - l), in both frames;
// - the previous point is in front of the previous camera (depth >= znear).
// The receiver's plane is its geometric normal's (the triangle's face), not the interpolated shading normal: a
// shadow falls on the face, and the face is what Eq. 3 intersects.
//
// One light sample per pixel gives one m^V, from that sample's light (TRMV21 Sec. 6: several moving lights are
// a stated failure). Only pixels whose shadow ray was blocked have m^V; filters/trmv/splat.h spreads it.
#pragma once

#include "core/error.h"
#include "core/frame.h"
#include "core/parallel.h"
#include "motion/shadow_shared.h"  // kShadowParallelCosine, written once for the port (motion/shadow.comp)
#include "raster/gbuffer_frame.h"
#include "raster/view.h"
#include "scenes/scene.h"

#include <glm/glm.hpp>

#include <cstdint>
#include <string>
#include <vector>

namespace rtdr {

// T^{-1} of [TRMV21 Eq. 3] for one instance k: M_k(t_{i-1}) M_k(t_i)^{-1}, which carries a world point on it at
// this frame's time to where it was in the previous frame, and the matrix that carries its normals (the inverse
// transpose of the linear part), computed once per instance and frame rather than once per pixel.
struct InstanceMotion {
  glm::mat4 to_previous{1.0f};
  glm::mat3 normal_to_previous{1.0f};
};
InstanceMotion instance_motion(const glm::mat4& to_previous);
// Every instance's, from the two frames' poses.
std::vector<InstanceMotion> instance_to_previous(const ScenePose& pose, const ScenePose& prev_pose);

// One pixel's shadow ray as the path tracer recorded it (the path.* layers), and its receiver.
struct ShadowRay {
  glm::vec3 light{0.0f};    // l_i, the light sample
  glm::vec3 blocker{0.0f};  // b_i, the nearest occluder of the shadow ray
  glm::vec3 receiver{0.0f}; // s_i, the pixel's surface point
  glm::vec3 receiver_normal{0.0f};  // n(s_i), the receiver's face normal (unit; its sign does not matter)
  uint32_t light_instance = kInvalidId, blocker_instance = kInvalidId, receiver_instance = kInvalidId;
};

struct ShadowMotion {
  glm::vec2 motion{0.0f};  // m^V = x^V_{i-1} - x_i, pixels; (0, 0) when not valid
  bool valid = false;
};

// The golden per-pixel function [TRMV21 Eq. 3]. `to_previous` is instance_to_previous(pose, prev_pose).
ShadowMotion shadow_motion_pixel(const ShadowRay& ray, const std::vector<InstanceMotion>& to_previous,
                                 const View& view, const View& prev_view);

// The channels of a frame that hold every pixel's shadow ray: its path.* layers and its G-buffer (`position`,
// `geonormal`, `id.instance`). Read in place, not copied: at 1080p a copy costs more than Eq. 3 itself.
class ShadowRayLayers {
 public:
  explicit ShadowRayLayers(const Frame& frame);  // throws rtdr::Error naming a missing channel
  // Pixel i's shadow ray; a pixel whose ray was not blocked (or that sees no surface) gets one with no receiver.
  ShadowRay at(size_t i) const;

 private:
  const FloatPlane *light_[3], *blocker_[3], *position_[3], *normal_[3];
  const UIntPlane *light_id_, *blocker_id_, *receiver_id_;
};

// The loop of a per-pixel motion pass over a rendered frame (the shadow and the glossy vector): out[i] = pixel(i)
// at every pixel, row-major, rows in parallel; each pixel writes only its own entry, so any thread count gives the
// same bits. Throws rtdr::Error naming `pass` when the frame is not the geometry's size.
template <class T, class PixelFn>
std::vector<T> motion_per_pixel(const char* pass, const FrameGeometry& g, const Frame& frame, const PixelFn& pixel) {
  if (frame.width() != g.vis.width || frame.height() != g.vis.height)
    throw Error(std::string(pass) + ": a " + std::to_string(frame.width()) + "x" + std::to_string(frame.height()) +
                " frame for a " + std::to_string(g.vis.width) + "x" + std::to_string(g.vis.height) + " geometry");
  std::vector<T> out(size_t(frame.width()) * size_t(frame.height()));
  parallel_rows(g.vis.height, [&](int y) {
    for (int x = 0; x < g.vis.width; ++x) {
      const size_t i = g.vis.index(x, y);
      out[i] = pixel(i);
    }
  });
  return out;
}

// Adds `layer`.X, `layer`.Y (each result's .motion) and `layer`.valid (uint 0/1, its .valid) to `frame`.
template <class T>
void write_motion_and_validity(Frame& frame, const std::string& layer, const std::vector<T>& results) {
  std::vector<glm::vec2> motion(results.size());
  UIntPlane& valid = frame.add_uint(layer + ".valid");
  for (size_t i = 0; i < results.size(); ++i) motion[i] = results[i].motion, valid.data[i] = results[i].valid ? 1u : 0u;
  frame.set_vec2(layer, motion);
}

// Every pixel's shadow motion, row-major.
std::vector<ShadowMotion> shadow_motion(const FrameGeometry& geometry, const Frame& frame);

// Adds motion.shadow.X, motion.shadow.Y and motion.shadow.valid (uint 0/1) to a frame that holds the path.*
// layers (trace_layers). The splat that spreads it to the pixels around each shadow (filters/trmv/splat.h) is the
// filter's: its window is the shadow filter's (filters/trmv/footprint.h).
void write_shadow_motion_layers(const FrameGeometry& geometry, Frame& frame);

}  // namespace rtdr
