// Tests of gpu/asvgf_atrous_gpu.cpp: the Vulkan port of the gradient's reconstruction (filters/asvgf/gradient_atrous.comp)
// against the golden gradient_atrous_level() (filters/asvgf/gradient_atrous.cpp) on random stratum grids (sizes that
// are multiples of no workgroup shape, zero variance, strata without a surface) for one iteration at each k = 0..4
// and for the five iterations in a row, and on the gradient image of a rendered pillars frame pair, with the
// validation layer on. Skipped, with a message, where no Vulkan device exists.
//
// Bound, per channel c of (delta^, Delta^, l^, Var(l^)), with M_c the largest |value| of that channel in the input
// grid: max |gpu - golden| <= B M_c, with B = kLevelBound = 5e-5 for one iteration on the same input (derived) and
// B = kChainBound = 2e-3 for five iterations in a row (a guard, not derived: see below).
// Derivation, one iteration. Both sides do the same fp32 operations in the same order (`precise` in the shader; the
// C++ is built without fma), the prefilter included, so the skip rules, g3x3(Var), the exponents of w_z and w_l and
// the cosine of w_n are bit-identical; only GLSL's exp and pow (edge_stopping.glsl, called as the golden code calls
// edge_stopping.cpp) and the divisions may differ. Vulkan allows exp(x) 3 + 2|x| ulp and pow the error of
// exp2(y log2 x); libm's are within 1 ulp. A tap weight w = w_z w_n w_l thus differs by a relative e_w of a few
// 2^-24 (|x| up to ~20 for the weights that matter: a few 1e-6), plus sigma_n times log2's error for w_n, as in
// tests/gpu_atrous_test.cpp. delta^, Delta^ and l^ are sum h w v / sum h w, a weighted mean of the values v
// (|v| <= M_c), so moving every weight by a relative e_w moves each by at most 2 e_w M_c; Var(l^) is
// sum h^2 w^2 Var / (sum h w)^2 <= M_c, with squared weights over a squared sum: 4 e_w M_c. The divisions add 3 ulp
// of the result (2.5 ulp on a GPU against C++'s 0.5), under 4e-7 M_c. 5e-5 is the SVGF a-trous port's bound for the
// same weights (gpu_atrous_test), with a margin over 4 e_w + 4e-7.
// Five iterations. Each iteration's input differs by what the ones before it left; a weighted mean of values within
// d of each other is within d too, so with the weights held fixed the errors add: 5 kLevelBound = 2.5e-4 (as
// tests/gpu_svgf_test.cpp's five levels). But the weights see the earlier errors as well, and w_l does not damp
// them: a luminance error E_l moves a_l = |l^(p) - l^(q)| / (sigma_l sqrt(g3x3(Var)(p)) + epsilon) by up to
// 2 E_l / scale, a relative change of w_l with no bound of its own as the scale falls to epsilon (zero or
// nearly zero variance, which the iterations approach: each divides Var by about 9) while l^(q) stays within a few
// scales of l^(p). delta^ and Delta^ are weighted by those w_l, so their chained error is not bounded a priori:
// measured on lavapipe, l^ and Var(l^) stay within 5e-6 M_c after five iterations, delta^ and Delta^ reach 4.3e-4
// M_c (random grids, zero variance included). kChainBound = 2e-3, 4.6x that, guards against a regression; it is
// not a derived bound.
// On a CPU device (lavapipe) the divisions round correctly; exp and pow are LLVM's, so the weights still differ.
// The last test case prints the largest errors over this file.
#include "gpu/asvgf_atrous_gpu.h"

#include "core/error.h"
#include "filters/asvgf/gradient_image.h"
#include "filters/image.h"
#include "filters/surface_planes.h"
#include "scenes/gltf_loader.h"
#include "trace/gradients.h"

#include "asvgf_fixtures.h"
#include "gpu_fixtures.h"

#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <random>
#include <string>

using namespace rtdr;
using namespace rtdr::gpu_test;

namespace {

constexpr double kLevelBound = 5e-5;  // one iteration on the same input, relative to M_c (see the banner)
constexpr double kChainBound = 2e-3;  // five iterations in a row: a guard, not derived (see the banner)

// The largest error seen over the file, relative to M_c, per channel: printed by the last test case.
double g_worst_level[4] = {0, 0, 0, 0}, g_worst_chain[4] = {0, 0, 0, 0};

const FloatPlane& channel(const GradientValues& v, int c) {
  return c == 0 ? v.delta : c == 1 ? v.norm : c == 2 ? v.luminance : v.variance;
}
const char* const kChannelNames[4] = {"delta^", "Delta^", "l^", "Var(l^)"};

// gpu against golden, channel by channel, within bound M_c (M_c from `in`, the first iteration's input).
void check_values(const GradientValues& in, const GradientValues& gpu, const GradientValues& golden, double bound,
                  double* worst) {
  for (int c = 0; c < 4; ++c) {
    const FloatPlane &a = channel(gpu, c), &b = channel(golden, c);
    REQUIRE(a.width == b.width);
    REQUIRE(a.height == b.height);
    double m = 0.0, diff = 0.0;
    for (const float v : channel(in, c).data) m = std::max(m, double(std::abs(v)));
    for (size_t i = 0; i < b.data.size(); ++i) diff = std::max(diff, abs_difference(a.data[i], b.data[i]));
    const double relative = m > 0.0 ? diff / m : diff;
    worst[c] = std::max(worst[c], relative);
    INFO(kChannelNames[c] << ": max |gpu - golden| " << diff << ", M " << m << " (bound " << bound * m << ")");
    CHECK(diff <= bound * m);
  }
}

// A random w x h stratum grid of s: a smooth luminance with noise (so w_l is neither 0 nor 1), variance in [0, 0.05]
// (0 in the top third of the rows, or everywhere with zero_variance), a gradient sample in 60% of the strata
// (delta in [-1, 1], Delta >= |delta|), 15% of the strata and the column x = 2 without a surface; depth on a tilted
// plane with noise, normals spread around +z (a few facing away).
GradientImage random_grid(std::mt19937& rng, int w, int h, int s, bool zero_variance) {
  std::uniform_real_distribution<float> u(0.0f, 1.0f);
  GradientImage g;
  g.stratum_size = s;
  g.values = {FloatPlane(w, h), FloatPlane(w, h), FloatPlane(w, h), FloatPlane(w, h)};
  g.surface = blank_surface(w, h);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      g.values.luminance.at(x, y) = 1.0f + 0.1f * float(x) / float(w) + 0.02f * u(rng);
      g.values.variance.at(x, y) = zero_variance || y < h / 3 ? 0.0f : 0.05f * u(rng);
      if (u(rng) < 0.6f) {
        const float d = 2.0f * u(rng) - 1.0f;
        g.values.delta.at(x, y) = d;
        g.values.norm.at(x, y) = std::abs(d) + u(rng);
      }
      const bool none = u(rng) < 0.15f || x == 2;
      g.surface.mesh.at(x, y) = none ? kInvalidId : 0u;
      g.surface.depth.at(x, y) = none ? 0.0f : 2.0f + 0.01f * float(x * s) + 0.002f * u(rng);
      g.surface.depth_grad.at(x, y) = glm::vec2(0.01f, 0.0f) + 0.002f * glm::vec2(u(rng) - 0.5f, u(rng) - 0.5f);
      const float spread = u(rng) < 0.05f ? 3.0f : 0.1f;
      g.surface.normal.at(x, y) = glm::normalize(glm::vec3(spread * (u(rng) - 0.5f), spread * (u(rng) - 0.5f), 1.0f));
    }
  return g;
}

// One iteration at each k = 0..4 on the golden input of that iteration (at k = 0 only, unless every_level: each
// call builds the pipelines, slow on lavapipe), then the five in a row.
void check_grid(VulkanContext& context, const GradientImage& g, bool every_level = true) {
  const SvgfParams p;
  GradientValues level_in = g.values;
  for (int k = 0; k < 5; ++k) {
    if (k > 0 && !every_level) {
      level_in = gradient_atrous_level(level_in, g, k, p);
      continue;
    }
    INFO("iteration k = " << k);
    const GradientValues golden = gradient_atrous_level(level_in, g, k, p);
    double ms = 0.0;
    const GradientValues gpu = gradient_atrous_vulkan(context, level_in, g, p, 1, k, &ms);
    check_values(level_in, gpu, golden, kLevelBound, g_worst_level);
    CHECK(ms > 0.0);
    level_in = golden;
  }
  INFO("five iterations in a row");
  const GradientValues gpu = gradient_atrous_vulkan(context, g.values, g, p, 5);
  check_values(g.values, gpu, level_in, kChainBound, g_worst_chain);
}

}  // namespace

TEST_CASE("the gradient reconstruction port matches gradient_atrous_level on random stratum grids") {
  const auto context = validated_context();
  std::mt19937 rng(17);
  struct Case {
    int w, h, s;
    bool zero_variance;
  };
  for (const Case c : {Case{37, 23, 3, false}, Case{37, 23, 3, true}, Case{13, 7, 1, false}, Case{50, 19, 4, false}}) {
    INFO("grid " << c.w << "x" << c.h << ", s " << c.s << (c.zero_variance ? ", zero variance" : ""));
    const GradientImage g = random_grid(rng, c.w, c.h, c.s, c.zero_variance);
    // The weights are not trivial: some taps of the first iteration get 0 < w < 1 (w_l included).
    int partial = 0;
    const FloatPlane pre = g.values.variance;  // g3x3 of it is what w_l reads; a rough count suffices here
    for (int y = 0; y < c.h; ++y)
      for (int x = 1; x < c.w; ++x)
        if (g.surface.covered(x, y) && g.surface.covered(x - 1, y) && pre.at(x, y) > 0.0f &&
            std::abs(g.values.luminance.at(x, y) - g.values.luminance.at(x - 1, y)) < 0.02f)
          ++partial;
    if (!c.zero_variance) CHECK(partial > 0);
    check_grid(*context, g, c.w == 37);
  }
  // Zero iterations return the input; one iteration on a grid of one stratum.
  const GradientImage one = random_grid(rng, 1, 1, 2, false);
  const GradientValues same = gradient_atrous_vulkan(*context, one.values, one, SvgfParams{}, 0);
  CHECK(same.luminance.data == one.values.luminance.data);
  check_grid(*context, one, false);
  check_no_validation_messages(*context);
}

TEST_CASE("the gradient reconstruction port matches gradient_atrous_level on a rendered frame pair's gradient") {
  const auto context = validated_context();
  const test::GradientFrame pair = test::pillars_gradient_frame();  // pillars frame 4 at 50x29 (asvgf_fixtures.h)
  const Frame& current = pair.frame;
  const int s = pair.stratum_size;
  const SurfacePlanes& surface = pair.surface;
  const UIntPlane& source = current.uint_channel("gradient.source");
  for (const std::string stream : {"direct", "indirect"}) {
    INFO("stream " << stream);
    const GradientImage g =
        gradient_image(rgb_plane(current, stream), source, current.float_channel("gradient.prev_" + stream), surface, s);
    size_t sampled = 0;
    for (const float d : g.values.norm.data) sampled += d > 0.0f;
    CHECK(sampled > 0);
    check_grid(*context, g, stream == "direct");
  }
  check_no_validation_messages(*context);
}

TEST_CASE("the gradient reconstruction port rejects planes of different sizes, s < 1 and k > 30") {
  const auto context = validated_context();
  std::mt19937 rng(3);
  GradientImage g = random_grid(rng, 6, 5, 3, false);
  GradientValues bad = g.values;
  bad.norm = FloatPlane(6, 4);
  CHECK_THROWS_AS(gradient_atrous_vulkan(*context, bad, g, SvgfParams{}, 1), Error);
  CHECK_THROWS_AS(gradient_atrous_vulkan(*context, g.values, g, SvgfParams{}, 5, 27), Error);
  g.stratum_size = 0;
  CHECK_THROWS_AS(gradient_atrous_vulkan(*context, g.values, g, SvgfParams{}, 1), Error);
}

TEST_CASE("largest gradient reconstruction errors over this file") {
  for (int c = 0; c < 4; ++c)
    WARN(kChannelNames[c] << ": max |gpu - golden| / M, one iteration " << g_worst_level[c] << " (bound "
                          << kLevelBound << "), five in a row " << g_worst_chain[c] << " (bound " << kChainBound
                          << ")");
}
