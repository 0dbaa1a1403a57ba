// Tests of gpu/variance_gpu.cpp: the Vulkan port (filters/svgf/variance.comp) against the golden variance_pass()
// (filters/svgf/variance.cpp) on random planes and on real temporal outputs of a rendered scene, with the
// validation layer on. Skipped, with a message, where no Vulkan device exists.
//
// Bounds, per estimate:
// - Temporal estimate (n >= variance_min_history): exact. Both sides compute max(0, mu2' - mu1' * mu1') in
//   fp32 from the same inputs; the shader marks it `precise`, so no fma changes the rounding.
// - Spatial estimate (n < variance_min_history): |gpu - golden| <= kSpatialTolerance * scale, where scale is
//   the largest mu2'(q) over the 7x7 taps q that count. Derivation: the weights w = exp(-a_z) pow(c, sigma_n)
//   come from GLSL exp/pow, which Vulkan only asks to be within (3 + 2|x|) ulp (exp) and to inherit
//   exp2(sigma_n log2 c) (pow: log2 has absolute error 2^-21, so a relative error of sigma_n 2^-21 ~ 6.1e-5
//   at sigma_n = 128) of the true value, while libm is within 1 ulp. If every weight is off by a relative d,
//   the weighted mean of mu2' moves by at most 2 d max mu2', that of mu1' by 2 d max |mu1'|, so mu1^2 by
//   4 d max mu1'^2 <= 4 d max mu2' (mu2' >= mu1'^2): |d sigma^2| <= 6 d max mu2', plus the fp32 rounding of the
//   sums and the division (the same on both sides except the division, 2.5 ulp in Vulkan). A relative bound
//   on sigma^2 itself is no good: sigma^2 = mu2 - mu1^2 cancels (sigma^2 << mu2 where the signal is bright
//   and clean), and the relative error grows without bound as sigma^2 -> 0. With the spec's worst case
//   d = 6.1e-5, 6 d = 3.7e-4; kSpatialTolerance = 4e-4 is that bound. The measured errors (printed) are far below.
// - fp16 illumination records (the ports' _fp16 builds): the pass reads only the moments, which stay fp32, and
//   stores sigma^2 as the square of a half standard deviation (filters/svgf/planes_shared.h): each bound above
//   grows by that storage error, variance_storage_bound (gpu_fixtures.h): a relative (1 + 2^-10 + 2^-21)^2 - 1 of
//   sigma^2, plus what a subnormal standard deviation (below 2^-14) may lose. A 0 stays 0.
#include "gpu/variance_gpu.h"

#include "core/error.h"
#include "filters/svgf/temporal.h"
#include "filters/svgf/variance.h"
#include "scenes/gltf_loader.h"
#include "trace/render_frame.h"

#include "gpu_fixtures.h"

#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <memory>
#include <random>
#include <string>

using namespace rtdr;
using namespace rtdr::gpu_test;

namespace {

constexpr double kSpatialTolerance = 4e-4;

struct Errors {
  int temporal_pixels = 0, spatial_pixels = 0, uncovered_pixels = 0;
  double temporal_max_abs = 0.0;        // max |gpu - golden|
  double temporal_beyond = 0.0;         // max |gpu - golden| - variance_storage_bound(golden): must be <= 0
  double spatial_max_abs = 0.0;         // max |gpu - golden|
  double spatial_max_scaled = 0.0;      // max (|gpu - golden| - storage bound) / scale (the bounded quantity)
  double spatial_max_rel = 0.0;         // max |gpu - golden| / golden where golden > 1e-3 scale (for the report)
  double uncovered_max_abs = 0.0;       // must be 0
};

// The largest mu2'(q) over the 7x7 taps that variance_spatial_pixel counts at (x, y).
double spatial_scale(const TemporalOutput& t, const SurfacePlanes& s, int x, int y) {
  double scale = 0.0;
  for (int dy = -kVarianceSpatialRadius; dy <= kVarianceSpatialRadius; ++dy)
    for (int dx = -kVarianceSpatialRadius; dx <= kVarianceSpatialRadius; ++dx) {
      const int qx = x + dx, qy = y + dy;
      if (inside(s.depth, qx, qy) && s.covered(qx, qy)) scale = std::max(scale, double(t.moment2.at(qx, qy)));
    }
  return scale;
}

Errors compare(const VulkanContext& context, const FloatPlane& gpu, const FloatPlane& golden,
               const TemporalOutput& t, const SurfacePlanes& s, const SvgfParams& params) {
  Errors e;
  for (int y = 0; y < s.height(); ++y)
    for (int x = 0; x < s.width(); ++x) {
      const double diff = std::abs(double(gpu.at(x, y)) - double(golden.at(x, y)));
      // What storing the port's sigma^2 may add (0 with fp32 records).
      const double storage = variance_storage_bound(context, std::max(gpu.at(x, y), golden.at(x, y)));
      if (!s.covered(x, y)) {
        ++e.uncovered_pixels;
        e.uncovered_max_abs = std::max(e.uncovered_max_abs, diff);
      } else if (t.length.at(x, y) >= float(params.variance_min_history)) {
        ++e.temporal_pixels;
        e.temporal_max_abs = std::max(e.temporal_max_abs, diff);
        e.temporal_beyond = std::max(e.temporal_beyond, diff - storage);
      } else {
        ++e.spatial_pixels;
        const double scale = spatial_scale(t, s, x, y);
        e.spatial_max_abs = std::max(e.spatial_max_abs, diff);
        const double computed = std::max(0.0, diff - storage);  // the error of the computation itself
        if (scale > 0.0) e.spatial_max_scaled = std::max(e.spatial_max_scaled, computed / scale);
        else e.spatial_max_scaled = std::max(e.spatial_max_scaled, computed > 0.0 ? 1.0 : 0.0);
        if (golden.at(x, y) > 1e-3 * scale)
          e.spatial_max_rel = std::max(e.spatial_max_rel, diff / double(golden.at(x, y)));
      }
    }
  return e;
}

void check_within_bound(const VulkanContext& context, const FloatPlane& gpu, const FloatPlane& golden,
                        const TemporalOutput& t, const SurfacePlanes& s, const SvgfParams& params) {
  REQUIRE(gpu.width == golden.width);
  REQUIRE(gpu.height == golden.height);
  const Errors e = compare(context, gpu, golden, t, s, params);
  INFO("pixels: " << e.temporal_pixels << " temporal, " << e.spatial_pixels << " spatial, " << e.uncovered_pixels
                  << " uncovered");
  INFO("temporal estimate: max abs error " << e.temporal_max_abs << ", beyond the storage bound by "
                                          << e.temporal_beyond);
  INFO("spatial estimate: max abs error " << e.spatial_max_abs << ", max abs error / max mu2' "
                                          << e.spatial_max_scaled << " (bound " << kSpatialTolerance
                                          << "), max relative error " << e.spatial_max_rel);
  INFO("uncovered: max abs error " << e.uncovered_max_abs);
  CHECK(e.temporal_beyond <= 0.0);
  CHECK(e.spatial_max_scaled <= kSpatialTolerance);
  CHECK(e.uncovered_max_abs == 0.0);
  // Report the measured errors even when the checks pass.
  WARN("measured: temporal max abs " << e.temporal_max_abs << " (" << e.temporal_pixels
                                     << " px); spatial max abs " << e.spatial_max_abs << ", max abs/max mu2' "
                                     << e.spatial_max_scaled << ", max rel " << e.spatial_max_rel << " ("
                                     << e.spatial_pixels << " px); uncovered " << e.uncovered_pixels << " px");
}

// A random surface: a tilted plane of depth with noise (so w_z spans (0, 1]), normals scattered a few degrees
// around one direction (so w_n = cos^128 spans (0, 1]), a few meshes, and about 10% of pixels on no surface.
SurfacePlanes random_surface(std::mt19937& rng, int w, int h) {
  std::uniform_real_distribution<float> u(0.0f, 1.0f);
  SurfacePlanes s = blank_surface(w, h);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      const bool none = u(rng) < 0.1f;
      s.mesh.at(x, y) = none ? kInvalidId : uint32_t(3.0f * u(rng));
      s.depth.at(x, y) = none ? 0.0f : 5.0f + 0.02f * x + 0.03f * y + 0.05f * u(rng);
      s.depth_grad.at(x, y) = none ? glm::vec2(0.0f) : glm::vec2(0.02f, 0.03f) + 0.01f * glm::vec2(u(rng), u(rng));
      const glm::vec3 n = glm::vec3(0.2f, 0.3f, 1.0f) + 0.15f * (glm::vec3(u(rng), u(rng), u(rng)) - 0.5f);
      s.normal.at(x, y) = none ? glm::vec3(0.0f) : glm::normalize(n);
    }
  // A few back-facing and degenerate normals: w_n = 0 taps, and a pixel whose own sum of weights is 0.
  s.normal.at(5, 5) = -s.normal.at(5, 5);
  s.normal.at(6, 5) = -s.normal.at(6, 5);
  s.mesh.at(10, 10) = 1u;
  s.normal.at(10, 10) = glm::vec3(0.0f);
  return s;
}

// Random moments with mu2 >= mu1^2 (mu2 = mu1^2 + variance) and history lengths mixing n < 4 and n >= 4.
// Uncovered pixels get junk moments: the port must still write 0 there and never read them as taps.
TemporalOutput random_temporal(std::mt19937& rng, int w, int h) {
  std::uniform_real_distribution<float> u(0.0f, 1.0f);
  const float lengths[] = {1.0f, 2.0f, 3.0f, 3.5f, 4.0f, 5.0f, 12.0f, 32.0f};
  TemporalOutput t;
  t.color = RgbPlane(w, h);
  t.moment1 = FloatPlane(w, h);
  t.moment2 = FloatPlane(w, h);
  t.length = FloatPlane(w, h);
  for (size_t i = 0; i < t.moment1.data.size(); ++i) {
    const float mu1 = 5.0f * u(rng);
    const float variance = u(rng) < 0.2f ? 0.0f : 2.0f * u(rng);
    t.moment1.data[i] = mu1;
    t.moment2.data[i] = mu1 * mu1 + variance;
    t.length.data[i] = lengths[std::min(7, int(8.0f * u(rng)))];
  }
  return t;
}

}  // namespace

TEST_CASE("the variance port matches variance_pass on random planes of an odd size") {
  const auto context = validated_context();
  INFO("device: " << context->device_name());
  std::mt19937 rng(4242);
  const int w = 41, h = 29;  // a multiple of neither workgroup shape (8x8, 32x2): the last tiles overhang
  const SurfacePlanes s = random_surface(rng, w, h);
  const TemporalOutput t = random_temporal(rng, w, h);
  const SvgfParams params;
  REQUIRE(params.variance_min_history == 4);

  const FloatPlane golden = variance_pass(t, s, params);
  variance_vulkan(*context, t, s, params);  // warm-up: lavapipe compiles on first use
  double ms = 0.0;
  const FloatPlane gpu = variance_vulkan(*context, t, s, params, &ms);
  check_within_bound(*context, gpu, golden, t, s, params);
  WARN("variance dispatch " << ms << " ms (" << w << "x" << h << ") on " << context->device_name());
  CHECK(ms > 0.0);

  // Other parameters: a wider depth lobe, a narrower normal lobe, every pixel spatial / every pixel temporal.
  SvgfParams other;
  other.sigma_z = 4.0f;
  other.sigma_n = 16.0f;
  other.epsilon = 1e-2f;
  for (const int min_history : {0, 1000}) {
    other.variance_min_history = min_history;
    INFO("variance_min_history " << min_history);
    check_within_bound(*context, variance_vulkan(*context, t, s, other), variance_pass(t, s, other), t, s, other);
  }
  check_no_validation_messages(*context);
}

TEST_CASE("the variance port matches variance_pass on real temporal outputs of the pillars scene") {
  const auto context = validated_context();
  const Scene scene = load_scene("pillars");
  const SvgfParams params;
  TemporalHistory prev;
  int spatial_frames = 0, temporal_frames = 0;
  for (int f = 0; f < 6; ++f) {
    INFO("frame " << f);
    const Frame frame = render_frame(scene, f, 64, 36, {});
    const SurfacePlanes s = SurfacePlanes::from_frame(frame);
    const TemporalOutput t = temporal_pass(rgb_plane(frame, "direct"), s, prev, params);
    prev = {t.color, t.moment1, t.moment2, t.length, s};
    const FloatPlane golden = variance_pass(t, s, params);
    double ms = 0.0;
    const FloatPlane gpu = variance_vulkan(*context, t, s, params, &ms);
    check_within_bound(*context, gpu, golden, t, s, params);
    WARN("variance dispatch " << ms << " ms (64x36) on " << context->device_name());
    CHECK(ms > 0.0);
    const Errors e = compare(*context, gpu, golden, t, s, params);
    spatial_frames += e.spatial_pixels > 0;
    temporal_frames += e.temporal_pixels > 0;
  }
  CHECK(spatial_frames > 0);   // frame 0 at least: every pixel a disocclusion
  CHECK(temporal_frames > 0);  // frames 4 and 5: n >= 4 where the history held
  check_no_validation_messages(*context);
}

TEST_CASE("the variance port rejects planes of different sizes") {
  const auto context = validated_context();
  std::mt19937 rng(1);
  const SurfacePlanes s = random_surface(rng, 12, 12);
  TemporalOutput t = random_temporal(rng, 12, 12);
  t.length = FloatPlane(12, 11);
  CHECK_THROWS_AS(variance_vulkan(*context, t, s, SvgfParams{}), Error);
}
