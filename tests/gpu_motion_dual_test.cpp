// Tests of gpu/motion_dual_gpu.cpp: the Vulkan port (motion/dual.comp) against the golden dual_motion()
// (motion/dual.cpp) on rendered frames (the occlusion scene's boxes uncovering the wall; the glossy scene's orbiting
// camera uncovering what its objects hid) and on the same frames with perturbed surface motion, with the validation
// layer on. Skipped, with a message, where no Vulkan device exists.
//
// Bound: every decision is exact, so the disoccluded flags are equal and every pixel that keeps its surface motion
// is bit-identical (x^O = y). Each decision is made from the same fp32 operations on both sides, in the same order:
// the host packs the golden object_point of every sample; the shader marks every result `precise` (no fma
// contraction, no reordering) and writes glm's mat4 * vec4 out ((c0 x + c1 y) + (c2 z + c3 w)); the C++ is built
// without fma (no -march, no -ffp-contract). So y = x_i + m, the range test, floor(y), the world points, the clip
// coordinates and the depth (clip w) are bit-identical, and so are the depth test and the near-plane test, which
// read depths only; 1 - kForwardProjectionDepthTolerance is the same float (gpu/motion_dual_gpu.cpp). No decision
// can sit within rounding of its threshold: none is counted or skipped.
// Only View::project's division ndc = clip.xy / clip.w differs: Vulkan allows 2.5 ulp, C++ rounds correctly
// (0.5), so |Delta ndc| <= 3 e |ndc| with e = 2^-23 (an ulp of a float a is at most e |a|). For a disoccluded
// pixel, per axis with W the image's size along it (width or height), s a screen coordinate (y' or z):
//   s = (ndc 0.5 + 0.5) W: the sum and the product each round once on each side, and W |ndc| <= 2 |s| + W, so
//   |Delta s| <= (W / 2) 3 e |ndc| + e |s| + e |s| <= 5 e |s| + 1.5 e W;
//   v = z - y', x^O - x_i = (y - v) - x_i: each difference rounds once more on each side, so
//   B = 1.01 (5 e (|z| + |y'|) + 3 e W + e (|v| + |y - v| + |x^O - x_i|))      (about 2e-4 px at 160 x 90)
// with 1.01 for the second-order terms; z, y' and v are the golden values (world_point and View::project).
// A simulated device whose divisions are 2 ulps off, either way, checks the derivation (no Vulkan needed): its
// worst on the occlusion frame here is 0.33 of the bound, every decision the golden one.
// On a CPU device (lavapipe) the division rounds correctly, so the port is bit-identical. Measured worst on
// lavapipe (llvmpipe, LLVM 15), over every frame and build here: 0 on every output.
#include "gpu/motion_dual_gpu.h"

#include "core/error.h"
#include "motion/backproject.h"
#include "motion/dual.h"
#include "motion/dual_shared.h"
#include "scenes/gltf_loader.h"

#include "gpu_fixtures.h"

#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <random>
#include <string>
#include <vector>

using namespace rtdr;
using namespace rtdr::gpu_test;

namespace {

const double kE = std::ldexp(1.0, -23);

// The banner's bound at one disoccluded pixel (x, y), per axis, from the golden terms.
glm::dvec2 dual_bound(const Scene& scene, const FrameGeometry& g, const VisibilityBuffer& prev_vis, int x, int y,
                      glm::vec2 surface_motion, glm::vec2 dual) {
  const glm::vec2 x_i = glm::vec2(float(x), float(y)) + 0.5f;
  const glm::vec2 y_prev = x_i + surface_motion;
  const SurfaceSample occluder = prev_vis.sample(int(std::floor(y_prev.x)), int(std::floor(y_prev.y)));
  const glm::vec2 y_occluder = glm::vec2(g.prev_view.project(world_point(scene, g.prev_pose, occluder)));
  const glm::vec2 z = glm::vec2(g.view.project(world_point(scene, g.pose, occluder)));
  const glm::vec2 v = z - y_occluder;
  const glm::dvec2 size(g.vis.width, g.vis.height);
  return 1.01 * (5.0 * kE * (glm::abs(glm::dvec2(z)) + glm::abs(glm::dvec2(y_occluder))) + 3.0 * kE * size +
                 kE * (glm::abs(glm::dvec2(v)) + glm::abs(glm::dvec2(y_prev - v)) + glm::abs(glm::dvec2(dual))));
}

struct Counts {
  int disoccluded = 0, kept = 0;
};

// Port and golden pass on the same inputs: equal flags, the kept pixels exact, the disoccluded within the bound.
Counts check_port(VulkanContext& context, const Scene& scene, const FrameGeometry& g,
                  const std::vector<glm::vec2>& motion, double* ms = nullptr) {
  const std::vector<DualMotion> golden = dual_motion(scene, g, motion);
  const std::vector<DualMotion> gpu = dual_motion_vulkan(context, scene, g, motion, ms);
  REQUIRE(gpu.size() == golden.size());
  const VisibilityBuffer prev_vis = previous_visibility(scene, g);
  Counts c;
  size_t flag_mismatches = 0, kept_mismatches = 0, over_bound = 0;
  double worst = 0.0, worst_ratio = 0.0;
  for (int y = 0; y < g.vis.height; ++y)
    for (int x = 0; x < g.vis.width; ++x) {
      const size_t i = g.vis.index(x, y);
      if (gpu[i].disoccluded != golden[i].disoccluded) {
        ++flag_mismatches;
        continue;
      }
      if (!golden[i].disoccluded) {
        ++c.kept;
        // Bit for bit, NaN included (the golden passes the surface motion through).
        kept_mismatches += std::memcmp(&gpu[i].motion, &golden[i].motion, sizeof(glm::vec2)) != 0;
        continue;
      }
      ++c.disoccluded;
      const glm::dvec2 bound = dual_bound(scene, g, prev_vis, x, y, motion[i], golden[i].motion);
      for (int a = 0; a < 2; ++a) {
        const double diff = abs_difference(gpu[i].motion[a], golden[i].motion[a]);  // NaN: infinite
        worst = std::max(worst, diff);
        worst_ratio = std::max(worst_ratio, diff / bound[a]);
        over_bound += diff > bound[a];
      }
    }
  WARN("measured max |gpu - golden| on " << context.device_name() << ": " << worst << " px (at most "
                                         << worst_ratio << " of the bound) over " << c.disoccluded
                                         << " disoccluded pixels; " << c.kept << " keep the surface motion ("
                                         << kept_mismatches << " not exact); " << flag_mismatches
                                         << " flags differ");
  CHECK(flag_mismatches == 0);
  CHECK(kept_mismatches == 0);
  CHECK(over_bound == 0);
  return c;
}

// One frame's geometry and back-projected motion, as `rtdr render` makes them (no path tracing needed).
struct MotionFrame {
  FrameGeometry geometry;
  std::vector<glm::vec2> motion;
};

MotionFrame motion_frame(const Scene& scene, int index, int width, int height) {
  MotionFrame f{rasterize_frame(scene, index, width, height), {}};
  f.motion = backproject_motion(scene, f.geometry.prev_pose, f.geometry.prev_view, f.geometry.vis);
  return f;
}

// The surface motion perturbed: fractional offsets (y lands on other pixels, other occluders), vectors off the
// image on either side, kMotionBehindCamera (far off any screen).
std::vector<glm::vec2> perturbed(std::vector<glm::vec2> motion, int width, uint32_t seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> u(0.0f, 1.0f);
  for (glm::vec2& m : motion) {
    const float r = u(rng);
    if (r < 0.05f) m += glm::vec2(float(width) * (u(rng) < 0.5f ? -1.0f : 1.0f), 0.0f);
    else if (r < 0.08f) m = glm::vec2(kMotionBehindCamera);
    else m += 6.0f * glm::vec2(u(rng), u(rng)) - 3.0f;  // within +-3 pixels
  }
  return motion;
}

// A device as far from C++ as Vulkan lets it be, simulated: dual_motion_pixel's operations in the golden order,
// View::project's division rounded up to 2 ulps off the correctly rounded result, either way (Vulkan allows 2.5).
class SkewedDevice : public UlpSkew {
 public:
  explicit SkewedDevice(unsigned seed) : UlpSkew(seed) {}

  DualMotion pixel(const Scene& scene, const FrameGeometry& g, const VisibilityBuffer& prev_vis, int x, int y,
                   glm::vec2 surface_motion) {
    DualMotion out;
    out.motion = surface_motion;
    const SurfaceSample s = g.vis.sample(x, y);
    if (!s.valid()) return out;
    const glm::vec2 x_i = glm::vec2(float(x), float(y)) + 0.5f;
    const glm::vec2 y_prev = x_i + surface_motion;
    if (!(y_prev.x >= 0.0f && y_prev.y >= 0.0f && y_prev.x < float(prev_vis.width) &&
          y_prev.y < float(prev_vis.height)))
      return out;
    const int qx = int(std::floor(y_prev.x)), qy = int(std::floor(y_prev.y));
    const float depth_prev = project(g.prev_view, world_point(scene, g.prev_pose, s)).z;
    const float visible_depth = prev_vis.depth[prev_vis.index(qx, qy)];
    if (!(visible_depth > 0.0f && visible_depth < depth_prev * (1.0f - kForwardProjectionDepthTolerance))) return out;
    const SurfaceSample occluder = prev_vis.sample(qx, qy);
    const glm::vec2 y_occluder = glm::vec2(project(g.prev_view, world_point(scene, g.prev_pose, occluder)));
    const glm::vec3 z = project(g.view, world_point(scene, g.pose, occluder));
    if (z.z < g.view.znear) return out;
    const glm::vec2 v = glm::vec2(z) - y_occluder;
    out.motion = (y_prev - v) - x_i;
    out.disoccluded = true;
    return out;
  }
};

}  // namespace

TEST_CASE("the dual motion bound holds for a simulated device whose divisions are ulps off") {
  // No Vulkan needed: this checks the banner's derivation, where lavapipe (exact) cannot.
  const Scene scene = load_scene("occlusion");
  const int w = 160, h = 90;
  const MotionFrame f = motion_frame(scene, 40, w, h);
  const FrameGeometry& g = f.geometry;
  const VisibilityBuffer prev_vis = previous_visibility(scene, g);
  double worst_ratio = 0.0;
  size_t compared = 0, differ = 0;
  for (const std::vector<glm::vec2>& motion : {f.motion, perturbed(f.motion, w, 3u)}) {
    const std::vector<DualMotion> golden = dual_motion(scene, g, motion);
    for (unsigned seed = 0; seed < 4; ++seed) {
      SkewedDevice device(seed);
      for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
          const size_t i = g.vis.index(x, y);
          const DualMotion m = device.pixel(scene, g, prev_vis, x, y, motion[i]);
          REQUIRE(m.disoccluded == golden[i].disoccluded);  // every decision exact (banner)
          if (!m.disoccluded) {
            CHECK(m.motion == golden[i].motion);
            continue;
          }
          ++compared;
          const glm::dvec2 bound = dual_bound(scene, g, prev_vis, x, y, motion[i], golden[i].motion);
          bool moved = false;
          for (int a = 0; a < 2; ++a) {
            const double d = abs_difference(m.motion[a], golden[i].motion[a]);
            CHECK(d <= bound[a]);
            moved = moved || d > 0.0;
            worst_ratio = std::max(worst_ratio, d / bound[a]);
          }
          differ += moved;
        }
    }
  }
  WARN("simulated device: " << differ << " of " << compared << " vectors differ, at most " << worst_ratio
                            << " of their bound");
  CHECK(differ > compared / 2);  // the simulation does move the vectors
}

TEST_CASE("the dual motion port matches dual_motion on the occlusion scene's boxes uncovering the wall") {
  const auto context = validated_context();
  const Scene scene = load_scene("occlusion");
  const int w = 160, h = 90;
  for (const int index : {40, 41}) {
    INFO("frame " << index);
    const MotionFrame f = motion_frame(scene, index, w, h);
    dual_motion_vulkan(*context, scene, f.geometry, f.motion);  // warm-up: lavapipe compiles
    double ms = 0.0;
    const Counts c = check_port(*context, scene, f.geometry, f.motion, &ms);
    WARN("motion_dual dispatch " << ms << " ms (" << w << "x" << h << ") on " << context->device_name());
    CHECK(ms > 0.0);
    CHECK(c.disoccluded > 20);  // the band behind the moving boxes (tests/motion_dual_test.cpp)
    CHECK(c.kept > 0);
    // Other vectors on the same buffers: other occluders, y off the image, far off any screen.
    const Counts p = check_port(*context, scene, f.geometry, perturbed(f.motion, w, uint32_t(index)));
    CHECK(p.disoccluded > 0);
  }
  check_no_validation_messages(*context);
}

TEST_CASE("the dual motion port matches dual_motion under the glossy scene's orbiting camera") {
  const auto context = validated_context();
  const Scene scene = load_scene("glossy");
  const int w = 100, h = 57;  // the last tiles overhang on either workgroup shape (32 x 2, 8 x 8)
  const MotionFrame f = motion_frame(scene, 30, w, h);
  const Counts c = check_port(*context, scene, f.geometry, f.motion);
  CHECK(c.kept > 0);
  const Counts p = check_port(*context, scene, f.geometry, perturbed(f.motion, w, 7u));
  CHECK(p.disoccluded > 0);
  check_no_validation_messages(*context);
}

TEST_CASE("the dual motion port refuses a wrong-sized motion, as dual_motion does") {
  const auto context = validated_context();
  const Scene scene = load_scene("occlusion");
  const FrameGeometry g = rasterize_frame(scene, 40, 64, 36);
  CHECK_THROWS_WITH(dual_motion_vulkan(*context, scene, g, std::vector<glm::vec2>(10)),
                    "dual_motion: 10 motion vectors for a 64x36 frame");
}
