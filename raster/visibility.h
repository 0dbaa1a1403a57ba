// The visibility buffer: which point of which triangle each pixel sees [ASVGF18 Sec. 3.1].
//
// Pass: rasterize(scene, pose, view) -> VisibilityBuffer.
//   in:  the Scene, its pose at time t, the View of that frame (jitter included)
//   out: per pixel the nearest surface sample at the pixel centre: instance, triangle, perspective-correct
//        barycentrics (b1, b2) of the ORIGINAL triangle, and linear view depth.
//
// Conventions (raster/README.md has the full story):
// - Pixel (x, y) is sampled at its centre (x + 0.5, y + 0.5); x grows right, y grows down (raster/view.h).
// - bary = (b1, b2), Embree's (u, v): the weights of the triangle's vertices 1 and 2; b0 = 1 - b1 - b2.
// - depth = linear view depth (clip w). Background: ids kInvalidId, bary (0, 0), depth 0.
// - Both faces are drawn (no back-face culling). Nearest depth wins; on equal depth the earlier triangle in
//   (instance, triangle) order wins, so the buffer is the same for any thread count.
// - Vertices are snapped to 1/256 pixel and covered by exact integer edge functions with the top-left fill
//   rule: a pixel centre on an edge shared by two triangles is covered by exactly one of them.
// - Triangles are clipped to the near plane (w >= znear) and to a guard band (kGuardBandPixels). There is
//   no far plane: everything beyond znear is drawn.
#pragma once

#include "core/frame.h"
#include "raster/view.h"
#include "scenes/scene.h"

#include <glm/glm.hpp>

#include <array>
#include <cstdint>
#include <vector>

namespace rtdr {

// Sub-pixel precision of snapped vertices: 8 bits, 1/256 pixel (as Direct3D's 8-bit sub-pixel grid).
inline constexpr int kSubpixelBits = 8;
inline constexpr int64_t kSubpixels = int64_t(1) << kSubpixelBits;

// Guard band: triangles are clipped to the screen rectangle grown by this many pixels on every side.
// Inside it (and with images of at most kMaxImageSize) a screen coordinate lies in [-2^14, 2^15] pixels,
// so a snapped coordinate is below 2^23 sub-pixels in magnitude, a coordinate difference below 2^24, and an
// edge function (a difference of two products of such differences) below 2^49: exact in int64 with 14 bits
// to spare. Only triangles that reach beyond the band are clipped against it; the band is off-screen, so
// where it cuts a triangle no pixel is affected.
inline constexpr int kGuardBandPixels = 16384;
inline constexpr int kMaxImageSize = 16384;

// What one pixel of a visibility buffer names: a point on one triangle of one instance.
struct SurfaceSample {
  uint32_t instance = kInvalidId;
  uint32_t triangle = kInvalidId;
  glm::vec2 bary{0.0f};  // (b1, b2); b0 = 1 - b1 - b2

  bool valid() const { return instance != kInvalidId; }
};

struct VisibilityBuffer {
  int width = 0;
  int height = 0;
  std::vector<uint32_t> instance;  // kInvalidId where no surface
  std::vector<uint32_t> triangle;  // index into the instance's Mesh::triangles
  std::vector<glm::vec2> bary;     // (b1, b2) of the original triangle at the pixel centre
  std::vector<float> depth;        // linear view depth; 0 where no surface

  VisibilityBuffer() = default;
  VisibilityBuffer(int w, int h);  // all background

  size_t index(int x, int y) const { return size_t(y) * size_t(width) + size_t(x); }
  SurfaceSample sample(int x, int y) const {
    const size_t i = index(x, y);
    return {instance[i], triangle[i], bary[i]};
  }
};

// One triangle for the low-level rasterizer: OpenGL clip-space vertices (w = linear view depth), in the
// order of the original triangle's vertices 0, 1, 2, and the ids to store where it is visible.
struct ClipTriangle {
  std::array<glm::vec4, 3> clip;
  uint32_t instance = 0;
  uint32_t triangle = 0;
};

// Rasterizes clip-space triangles into a width x height visibility buffer. Screen position of a clip
// point: ((x/w + 1) / 2 * width, (1 - y/w) / 2 * height), as View::project. Triangles must come in
// (instance, triangle) order for the tie rule above to mean that order.
VisibilityBuffer rasterize_clip_triangles(const std::vector<ClipTriangle>& triangles, int width, int height,
                                          float znear);

// Every triangle of every instance of the scene at `pose`, seen through `view`.
VisibilityBuffer rasterize(const Scene& scene, const ScenePose& pose, const View& view);

// The same, reusing the storage of `out` (every pixel is rewritten; reallocated only if the size differs).
// For frame loops: a fresh 720p buffer costs more in page faults than the rasterization itself.
void rasterize_into(const Scene& scene, const ScenePose& pose, const View& view, VisibilityBuffer& out);
void rasterize_clip_triangles_into(const std::vector<ClipTriangle>& triangles, int width, int height, float znear,
                                   VisibilityBuffer& out);

// The point a surface sample names, in the mesh's object space: b0 p0 + b1 p1 + b2 p2. It does not depend
// on time, which is what makes back- and forward projection exact [TRMV21 Eq. 1, ASVGF18 Sec. 3.1].
// Inline: every resolve, back- and forward projection of a pixel starts here.
inline glm::vec3 object_point(const Scene& scene, const SurfaceSample& sample) {
  const Mesh& mesh = scene.meshes[size_t(scene.instances[sample.instance].mesh)];
  const glm::uvec3& tri = mesh.triangles[sample.triangle];
  const float b1 = sample.bary.x, b2 = sample.bary.y, b0 = 1.0f - b1 - b2;
  return b0 * mesh.positions[tri[0]] + b1 * mesh.positions[tri[1]] + b2 * mesh.positions[tri[2]];
}

// The same point in world space at `pose`: instance_to_world * object_point.
inline glm::vec3 world_point(const Scene& scene, const ScenePose& pose, const SurfaceSample& sample) {
  return glm::vec3(pose.instance_to_world[sample.instance] * glm::vec4(object_point(scene, sample), 1.0f));
}

}  // namespace rtdr
