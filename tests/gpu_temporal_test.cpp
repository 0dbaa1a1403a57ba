// Tests of gpu/temporal_gpu.cpp: the Vulkan port (filters/svgf/temporal.comp) against the golden temporal_pass()
// (filters/svgf/temporal.cpp) on random planes and on rendered frames of the pillars scene, with the validation
// layer on. Skipped, with a message, where no Vulkan device exists.
//
// Bound: history length n exact; colour and moments max |gpu - golden| / max(|golden|, 1e-3) <= 1e-5 per value.
// Derivation: both sides do the same fp32 operations in the same order (the shader marks them `precise`, so no
// fma contraction), and every consistency decision is then the same; the only operations Vulkan lets differ are
// the two divisions (1 / sum of weights, 1 / n; 2.5 ulp allowed against IEEE's 0.5), each feeding a product and
// a sum: a few ulp of the result, i.e. about 2^-23 * 8 ~ 1e-6 relative; 1e-5 leaves room for the EMA's
// cancellation-free sums of up to 4 such terms. Values below 1e-3 are compared absolutely.
//
// fp16 illumination records (the ports' _fp16 builds): the noisy colour and the history colour are read as the
// records hold them, so the golden pass runs on those (golden_temporal); the moments are fp32 and match as above.
// The colour C' is then stored as a half: the bound grows by that rounding, 2^-10 relative (gpu_fixtures.h).
//
// A-SVGF's per-pixel weights (TemporalAdaptive, the `adaptive` push constant) replace alpha and alpha_mu by the
// given alpha_i and alpha_mu_i [ASVGF18 Eq. 15] and, with restart_history, add n_{i-1} (1 - lambda): a product
// without a division, the same fp32 operations on both sides, so the bound above holds unchanged and n stays exact.
#include "gpu/temporal_gpu.h"

#include "core/error.h"
#include "eval/frame_diff.h"
#include "filters/asvgf/adaptive_alpha.h"
#include "filters/svgf/temporal.h"
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

constexpr double kMaxRelError = 1e-5;

struct Errors {
  double color = 0.0, moment1 = 0.0, moment2 = 0.0, length = 0.0;  // max |d| / max(|golden|, 1e-3)
  double length_abs = 0.0;
};

// |gpu - golden| / max(|golden|, 1e-3) (eval/frame_diff.h, as rtdr compare measures it).
double scaled_diff(float gpu, float golden) { return rel_difference(gpu, golden, 1e-3); }

// temporal_pass on what the context's port reads: the noisy and history colours as its records hold them.
TemporalOutput golden_temporal(const VulkanContext& context, const RgbPlane& noisy, const SurfacePlanes& cur,
                               TemporalHistory prev, const SvgfParams& params,
                               const TemporalAdaptive* adaptive = nullptr) {
  prev.color = stored_colour(context, prev.color);
  return temporal_pass(stored_colour(context, noisy), cur, prev, params, adaptive);
}

void check_within_bound(const VulkanContext& context, const TemporalOutput& gpu, const TemporalOutput& golden) {
  REQUIRE(gpu.color.width == golden.color.width);
  REQUIRE(gpu.color.height == golden.color.height);
  Errors e;
  for (size_t i = 0; i < golden.moment1.data.size(); ++i) {
    for (int c = 0; c < 3; ++c) e.color = std::max(e.color, scaled_diff(gpu.color.data[i][c], golden.color.data[i][c]));
    e.moment1 = std::max(e.moment1, scaled_diff(gpu.moment1.data[i], golden.moment1.data[i]));
    e.moment2 = std::max(e.moment2, scaled_diff(gpu.moment2.data[i], golden.moment2.data[i]));
    e.length_abs = std::max(e.length_abs, std::abs(double(gpu.length.data[i]) - double(golden.length.data[i])));
  }
  WARN("measured max relative error: colour " << e.color << ", mu1' " << e.moment1 << ", mu2' " << e.moment2
                                              << "; n max abs error " << e.length_abs);
  CHECK(e.color <= kMaxRelError + colour_storage_error(context));
  CHECK(e.moment1 <= kMaxRelError);
  CHECK(e.moment2 <= kMaxRelError);
  CHECK(e.length_abs == 0.0);
}

// A random surface: a tilted plane of depth with noise, normals scattered around one direction, 3 meshes,
// about 10% of pixels on no surface, motion within +-1.5 pixels and a few far off screen.
SurfacePlanes random_surface(std::mt19937& rng, int w, int h) {
  std::uniform_real_distribution<float> u(0.0f, 1.0f);
  SurfacePlanes s = blank_surface(w, h);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      const bool none = u(rng) < 0.1f;
      s.mesh.at(x, y) = none ? kInvalidId : uint32_t(x > w / 2) + uint32_t(u(rng) < 0.1f);
      s.depth.at(x, y) = none ? 0.0f : 5.0f + 0.02f * x + 0.03f * y + (u(rng) < 0.1f ? 2.0f : 0.05f) * u(rng);
      s.depth_grad.at(x, y) = none ? glm::vec2(0.0f) : glm::vec2(0.02f, 0.03f) + 0.01f * glm::vec2(u(rng), u(rng));
      const glm::vec3 n = glm::vec3(0.2f, 0.3f, 1.0f) + 0.6f * (glm::vec3(u(rng), u(rng), u(rng)) - 0.5f);
      s.normal.at(x, y) = none ? glm::vec3(0.0f) : glm::normalize(n);
      s.motion.at(x, y) = 3.0f * glm::vec2(u(rng), u(rng)) - 1.5f;
      if (u(rng) < 0.03f) s.motion.at(x, y) = glm::vec2(1e6f, -1e6f);
    }
  return s;
}

// A random history on `s`: moments with mu2 >= mu1^2, lengths mixing short and long histories.
TemporalHistory random_history(std::mt19937& rng, const SurfacePlanes& s) {
  std::uniform_real_distribution<float> u(0.0f, 1.0f);
  const int w = s.width(), h = s.height();
  const float lengths[] = {1.0f, 2.0f, 3.0f, 4.0f, 5.0f, 12.0f, 32.0f, 200.0f};
  TemporalHistory prev{random_plane(rng, w, h, 0.0f, 4.0f), FloatPlane(w, h), FloatPlane(w, h), FloatPlane(w, h), s};
  for (size_t i = 0; i < prev.moment1.data.size(); ++i) {
    const float mu1 = 4.0f * u(rng);
    prev.moment1.data[i] = mu1;
    prev.moment2.data[i] = mu1 * mu1 + 2.0f * u(rng);
    prev.length.data[i] = lengths[std::min(7, int(8.0f * u(rng)))];
  }
  return prev;
}

}  // namespace

TEST_CASE("the temporal port matches temporal_pass on random planes of an odd size") {
  const auto context = validated_context();
  std::mt19937 rng(77);
  const int w = 41, h = 29;
  // The previous surface: the current one, perturbed, so some taps pass and some fail each test.
  const SurfacePlanes cur = random_surface(rng, w, h);
  SurfacePlanes prev_surface = cur;
  std::uniform_real_distribution<float> u(0.0f, 1.0f);
  for (size_t i = 0; i < prev_surface.depth.data.size(); ++i) {
    if (u(rng) < 0.1f) prev_surface.depth.data[i] *= 1.0f + 0.3f * u(rng);
    if (u(rng) < 0.05f) prev_surface.mesh.data[i] = kInvalidId;
  }
  const TemporalHistory prev = random_history(rng, prev_surface);
  const RgbPlane noisy = random_plane(rng, w, h, 0.0f, 10.0f);

  // Every path of temporal_pixel is taken somewhere: bilinear, the 3x3 fallback, disocclusion (the golden
  // probe says which ran).
  int bilinear = 0, fallback = 0, disoccluded = 0;
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      if (!cur.covered(x, y)) continue;
      Probe probe;
      temporal_pixel(noisy, cur, prev, SvgfParams{}, x, y, &probe);
      if (probe.find("found", "history").value[0] == 0.0f) ++disoccluded;
      else if (probe.find("ran", "3x3 fallback").value[0] != 0.0f) ++fallback;
      else ++bilinear;
    }
  INFO("pixels: " << bilinear << " bilinear, " << fallback << " 3x3 fallback, " << disoccluded << " disoccluded");
  CHECK(bilinear > 0);
  CHECK(fallback > 0);
  CHECK(disoccluded > 0);
  WARN("random planes: " << bilinear << " bilinear, " << fallback << " 3x3 fallback, " << disoccluded
                         << " disoccluded pixels");

  for (const int max_history : {0, 8}) {
    INFO("max_history " << max_history);
    SvgfParams params;
    params.max_history = max_history;
    const TemporalOutput golden = golden_temporal(*context, noisy, cur, prev, params);
    temporal_vulkan(*context, noisy, cur, prev, params);  // warm-up: lavapipe compiles on first use
    double ms = 0.0;
    const TemporalOutput gpu = temporal_vulkan(*context, noisy, cur, prev, params, &ms);
    check_within_bound(*context, gpu, golden);
    WARN("temporal dispatch " << ms << " ms (" << w << "x" << h << ") on " << context->device_name());
    CHECK(ms > 0.0);
  }
  // First frame (empty history) and a history of another size.
  check_within_bound(*context, temporal_vulkan(*context, noisy, cur, TemporalHistory{}, SvgfParams{}),
                     golden_temporal(*context, noisy, cur, TemporalHistory{}, SvgfParams{}));
  std::mt19937 rng2(5);
  const TemporalHistory other = random_history(rng2, random_surface(rng2, 37, 31));
  check_within_bound(*context, temporal_vulkan(*context, noisy, cur, other, SvgfParams{}),
                     golden_temporal(*context, noisy, cur, other, SvgfParams{}));
  check_no_validation_messages(*context);
}

TEST_CASE("the temporal port matches temporal_pass with A-SVGF's per-pixel lambda, under both history rules") {
  const auto context = validated_context();
  std::mt19937 rng(31);
  const int w = 37, h = 23;
  const SurfacePlanes cur = random_surface(rng, w, h);
  const TemporalHistory prev = random_history(rng, cur);
  const RgbPlane noisy = random_plane(rng, w, h, 0.0f, 10.0f);
  // lambda: 0 (history kept), 1 (dropped) and values between, and the weights Eq. 15 makes of it, as
  // adaptive_alpha_pass does (the moments' from another base weight).
  std::uniform_real_distribution<float> u(0.0f, 1.0f);
  FloatPlane lambda(w, h), alpha(w, h), alpha_moments(w, h);
  for (size_t i = 0; i < lambda.data.size(); ++i) {
    const float r = u(rng);
    lambda.data[i] = r < 0.3f ? 0.0f : r < 0.5f ? 1.0f : u(rng);
    alpha.data[i] = adaptive_alpha(0.1f, lambda.data[i]);
    alpha_moments.data[i] = adaptive_alpha(0.15f, lambda.data[i]);
  }
  SvgfParams params;
  params.alpha = 0.1f;
  params.alpha_moments = 0.1f;
  for (const bool restart : {true, false}) {
    INFO("restart_history " << restart);
    const TemporalAdaptive adaptive{&lambda, &alpha, &alpha_moments, restart};
    const TemporalOutput golden = golden_temporal(*context, noisy, cur, prev, params, &adaptive);
    const TemporalOutput gpu = temporal_vulkan(*context, noisy, cur, prev, params, nullptr, &adaptive);
    check_within_bound(*context, gpu, golden);
    // The adaptive weight changed the result: the same frame with SVGF's constant alpha differs.
    const TemporalOutput constant = golden_temporal(*context, noisy, cur, prev, params);
    double moved = 0.0;
    for (size_t i = 0; i < golden.moment1.data.size(); ++i)
      moved = std::max(moved, double(std::abs(golden.moment1.data[i] - constant.moment1.data[i])));
    CHECK(moved > 0.1);
  }
  const FloatPlane wrong_size(w - 1, h);
  const TemporalAdaptive misfit{&lambda, &wrong_size, &alpha_moments, true};
  CHECK_THROWS_AS(temporal_vulkan(*context, noisy, cur, prev, params, nullptr, &misfit), Error);
  check_no_validation_messages(*context);
}

TEST_CASE("the temporal port matches temporal_pass on rendered frames of the pillars scene") {
  const auto context = validated_context();
  const Scene scene = load_scene("pillars");
  const SvgfParams params;
  TemporalHistory prev;
  for (int f = 0; f < 6; ++f) {
    INFO("frame " << f);
    const Frame frame = render_frame(scene, f, 64, 36, {});
    const SurfacePlanes s = SurfacePlanes::from_frame(frame);
    const RgbPlane noisy = rgb_plane(frame, "direct");
    const TemporalOutput golden = golden_temporal(*context, noisy, s, prev, params);
    double ms = 0.0;
    const TemporalOutput gpu = temporal_vulkan(*context, noisy, s, prev, params, &ms);
    check_within_bound(*context, gpu, golden);
    WARN("temporal dispatch " << ms << " ms (64x36) on " << context->device_name());
    CHECK(ms > 0.0);
    prev = {golden.color, golden.moment1, golden.moment2, golden.length, s};  // both continue from the golden history
  }
  check_no_validation_messages(*context);
}

TEST_CASE("the temporal port rejects planes of different sizes") {
  const auto context = validated_context();
  std::mt19937 rng(1);
  const SurfacePlanes s = random_surface(rng, 12, 12);
  CHECK_THROWS_AS(temporal_vulkan(*context, RgbPlane(12, 11), s, TemporalHistory{}, SvgfParams{}), Error);
}
