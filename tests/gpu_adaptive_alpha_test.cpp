// Tests of gpu/asvgf_alpha_gpu.cpp: the Vulkan port (filters/asvgf/adaptive_alpha.comp) against the golden
// adaptive_alpha_pass() (filters/asvgf/adaptive_alpha.cpp) on random stratum grids and on the gradients of a rendered
// frame pair of the pillars scene, with the validation layer on. Skipped, with a message, where no Vulkan device
// exists.
//
// Bound, for a base alpha in [0, 1], with e = 2^-23 (an ulp of a float x is at most e |x|):
//   lambda      3 e      lambda_max  3 e      alpha_i, alpha_mu_i  9 e  (about 1.1e-6)
// Derivation. Both sides do the same fp32 operations in the same order: the shader marks every result `precise`
// (no fma contraction, no reordering), and the C++ is built without fma (no -march, no -ffp-contract); the stratum
// of a pixel, the strata skipped at the grid's border and the test Delta^ > 0 are the same integer and comparison
// operations. Only the division may differ: Vulkan allows 2.5 ulp for x / y, where C++ rounds correctly (0.5 ulp);
// two results within 3 ulp of each other differ by at most 3 e |value|.
//   lambda = min(1, |delta^| / Delta^): the quotient differs by 3 e |quotient|, and min(1, .) keeps that under 3 e
//   (it is 1-Lipschitz, and where the quotient exceeds 1 the difference is 3 e of 1 at most past the clamp).
//   lambda_max, a maximum of such lambdas: max is 1-Lipschitz, 3 e.
//   alpha_i = (1 - lambda) alpha + lambda: 1 - lambda differs by 3 e plus one rounding on each side of a value
//   <= 1, e: 4 e; times alpha <= 1, plus the product's rounding: 5 e; plus lambda's 3 e and the sum's rounding
//   (a value <= 1): 9 e. alpha_mu_i is the same expression of alpha_mu. With p = 2 and k (the variants): the
//   quotient's 3 e becomes 2 (3 e) + e for the square and one more e for k <= 1, 8 e; lambda 8 e, alpha_i 14 e.
// A device that flushes subnormal floats to zero (Vulkan allows it without DenormPreserve) would read a subnormal
// Delta^ as 0 and give lambda 0 where the golden pass gives up to 1; the inputs here have Delta^ = 0 or >= 1e-6.
// On a CPU device (lavapipe) the division rounds correctly, as C++'s does, so every term above is 0 and the test
// asks for bit-identical outputs there. Measured: 0 on every output and input on lavapipe.
#include "gpu/asvgf_alpha_gpu.h"

#include "asvgf_fixtures.h"
#include "core/error.h"
#include "filters/asvgf/gradient_image.h"
#include "filters/image.h"
#include "filters/surface_planes.h"
#include "scenes/gltf_loader.h"
#include "trace/gradients.h"

#include "gpu_fixtures.h"

#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <random>
#include <string>

using namespace rtdr;
using namespace rtdr::gpu_test;

namespace {

// The banner's bounds.
struct Bounds {
  double lambda = 0.0, lambda_max = 0.0, alpha = 0.0;
};

Bounds derived_bounds(int exponent, float scale) {
  const double e = std::ldexp(1.0, -23);
  if (exponent == 1 && scale == 1.0f) return Bounds{3.0 * e, 3.0 * e, 9.0 * e};
  return Bounds{8.0 * e, 8.0 * e, 14.0 * e};
}

// Port and golden pass on the same inputs: within the banner's bound, or bit-identical on a CPU device.
// The moments' base weight is another than the colour's, (1 + alpha) / 2, so that a swap of the two shows.
void check_port(VulkanContext& context, const GradientValues& g, int s, int w, int h, float alpha, int radius,
                double* ms = nullptr, int exponent = 1, float scale = 1.0f) {
  INFO("grid " << g.norm.width << "x" << g.norm.height << ", s " << s << ", frame " << w << "x" << h << ", alpha "
               << alpha << ", radius " << radius << ", p " << exponent << ", k " << scale);
  const AdaptiveAlphaParams params{alpha, 0.5f * (1.0f + alpha), radius, exponent, scale};
  const AdaptiveAlpha golden = adaptive_alpha_pass(g, s, w, h, params);
  const AdaptiveAlpha gpu = adaptive_alpha_vulkan(context, g, s, w, h, params, ms);
  REQUIRE(gpu.lambda.width == golden.lambda.width);
  REQUIRE(gpu.lambda.height == golden.lambda.height);
  REQUIRE(gpu.alpha.width == golden.alpha.width);
  REQUIRE(gpu.alpha.height == golden.alpha.height);
  const Bounds bound = derived_bounds(exponent, scale);
  const bool exact = context.cpu_device();
  const double lambda = max_difference(gpu.lambda, golden.lambda),
               lambda_max = max_difference(gpu.lambda_max, golden.lambda_max),
               alpha_i = max_difference(gpu.alpha, golden.alpha),
               alpha_mu_i = max_difference(gpu.alpha_moments, golden.alpha_moments);
  WARN("measured max |gpu - golden|: lambda " << lambda << " (bound " << bound.lambda << "), lambda_max "
                                              << lambda_max << " (bound " << bound.lambda_max << "), alpha_i "
                                              << alpha_i << ", alpha_mu_i " << alpha_mu_i << " (bound "
                                              << bound.alpha << ")");
  INFO((exact ? "CPU device: exact" : "within the derived bound"));
  CHECK(lambda <= (exact ? 0.0 : bound.lambda));
  CHECK(lambda_max <= (exact ? 0.0 : bound.lambda_max));
  CHECK(alpha_i <= (exact ? 0.0 : bound.alpha));
  CHECK(alpha_mu_i <= (exact ? 0.0 : bound.alpha));
}

// A random reconstructed gradient on a gw x gh grid: delta^ in [-2, 2] and Delta^ in [1e-6, 2], with a share of
// strata at Delta^ = 0 (no sample in reach), a share at delta^ = 0, and some |delta^| > Delta^ (lambda clamped to 1).
GradientValues random_gradient(std::mt19937& rng, int gw, int gh) {
  std::uniform_real_distribution<float> u(0.0f, 1.0f);
  GradientValues g{FloatPlane(gw, gh), FloatPlane(gw, gh), FloatPlane(gw, gh), FloatPlane(gw, gh)};
  for (size_t i = 0; i < g.norm.data.size(); ++i) {
    const float r = u(rng);
    g.delta.data[i] = r < 0.15f ? 0.0f : 4.0f * u(rng) - 2.0f;
    g.norm.data[i] = r > 0.85f ? 0.0f : std::max(1e-6f, 2.0f * u(rng));
  }
  return g;
}

}  // namespace

TEST_CASE("the adaptive alpha port matches adaptive_alpha_pass on random stratum grids") {
  const auto context = validated_context();
  std::mt19937 rng(14);
  // Frames whose sizes are and are not multiples of s (partial strata at the right and bottom border), a grid
  // larger than the frame's strata (strata no pixel reads: lambda only), and radius 0 to 2: the maximum clipped at
  // every border of the grid.
  struct Case {
    int gw, gh, s, w, h;
  };
  for (const Case c : {Case{14, 10, 3, 41, 29}, Case{12, 9, 3, 36, 27}, Case{7, 5, 4, 25, 18}, Case{9, 8, 1, 9, 8},
                       Case{20, 15, 3, 41, 29}, Case{1, 1, 5, 5, 3}}) {
    const GradientValues g = random_gradient(rng, c.gw, c.gh);
    for (const int radius : {0, 1, 2})
      for (const float alpha : {0.1f, 0.37f, 1.0f}) {
        double ms = 0.0;
        check_port(*context, g, c.s, c.w, c.h, alpha, radius, &ms);
        CHECK(ms > 0.0);
      }
  }
  // lambda = min(1, k (|delta^| / Delta^)^p) with the peers' p = 2 and k = 0.1 (the variants' lambda after the
  // reconstruction).
  const GradientValues variants = random_gradient(rng, 14, 10);
  check_port(*context, variants, 3, 41, 29, 0.1f, 1, nullptr, 2, 1.0f);
  check_port(*context, variants, 3, 41, 29, 0.1f, 1, nullptr, 1, 0.1f);
  // No gradient anywhere (delta^ = Delta^ = 0): lambda 0, alpha_i = alpha.
  const GradientValues zero{FloatPlane(14, 10), FloatPlane(14, 10), FloatPlane(14, 10), FloatPlane(14, 10)};
  check_port(*context, zero, 3, 41, 29, 0.1f, 1);
  // One dropped stratum at each corner and one inside: alpha = 1 on the clipped 3x3 strata around each.
  GradientValues corners = rtdr::test::flat_grid(14, 10).values;
  for (const glm::ivec2 q :
       {glm::ivec2(0, 0), glm::ivec2(13, 0), glm::ivec2(0, 9), glm::ivec2(13, 9), glm::ivec2(6, 4)}) {
    corners.delta.at(q.x, q.y) = -2.0f;
    corners.norm.at(q.x, q.y) = 2.0f;
  }
  check_port(*context, corners, 3, 41, 29, 0.1f, 1);
  const AdaptiveAlpha a = adaptive_alpha_vulkan(*context, corners, 3, 41, 29, {0.1f, 0.1f, 1});
  CHECK(a.alpha.at(40, 28) == 1.0f);
  CHECK(a.alpha.at(0, 0) == 1.0f);
  CHECK(a.alpha.at(20, 28) == 0.1f);
  double ms = 0.0;
  const GradientValues big = random_gradient(rng, 107, 60);
  adaptive_alpha_vulkan(*context, big, 3, 320, 180, {0.1f, 0.1f, 1});  // warm-up: lavapipe compiles
  check_port(*context, big, 3, 320, 180, 0.1f, 1, &ms);
  WARN("asvgf_adaptive_alpha dispatch " << ms << " ms (320x180) on " << context->device_name());
  check_no_validation_messages(*context);
}

TEST_CASE("the adaptive alpha port matches adaptive_alpha_pass on the gradients of a rendered frame pair") {
  const auto context = validated_context();
  const test::GradientFrame pair = test::pillars_gradient_frame();  // pillars frame 4 at 50x29 (asvgf_fixtures.h)
  const Frame& current = pair.frame;
  const int s = pair.stratum_size, w = current.width(), h = current.height();
  const SurfacePlanes& surface = pair.surface;
  for (const std::string stream : {"direct", "indirect"}) {
    INFO("stream " << stream);
    // As the asvgf method feeds the pass (filters/svgf/svgf.cpp): the gradient image of the stream, reconstructed
    // by 5 a-trous iterations; and the sparse gradient image itself (no reconstruction), mostly Delta = 0.
    const GradientImage g = gradient_image(rgb_plane(current, stream), current.uint_channel("gradient.source"),
                                           current.float_channel("gradient.prev_" + stream), surface, s);
    const GradientValues reconstructed = rtdr::test::reconstruct(g);
    size_t reached = 0;
    for (const float n : reconstructed.norm.data) reached += n > 0.0f;
    WARN("pillars frames 3-4, " << stream << ": " << reached << " of " << reconstructed.norm.data.size()
                                << " strata with Delta^ > 0");
    CHECK(reached > 0);
    for (const int radius : {1, 0}) {
      double ms = 0.0;
      check_port(*context, reconstructed, s, w, h, 0.1f, radius, &ms);
      CHECK(ms > 0.0);
      check_port(*context, g.values, s, w, h, 0.1f, radius);
    }
  }
  check_no_validation_messages(*context);
}

TEST_CASE("the adaptive alpha port rejects planes of different sizes, s < 1 and a negative radius") {
  const auto context = validated_context();
  const GradientValues g{FloatPlane(4, 3), FloatPlane(4, 3), {}, {}};
  const GradientValues mismatched{FloatPlane(4, 3), FloatPlane(3, 3), {}, {}};
  CHECK_THROWS_AS(adaptive_alpha_vulkan(*context, mismatched, 3, 12, 9, {0.1f, 0.1f, 1}), Error);
  CHECK_THROWS_AS(adaptive_alpha_vulkan(*context, g, 0, 12, 9, {0.1f, 0.1f, 1}), Error);
  CHECK_THROWS_AS(adaptive_alpha_vulkan(*context, g, 3, 12, 9, {0.1f, 0.1f, -1}), Error);
}
