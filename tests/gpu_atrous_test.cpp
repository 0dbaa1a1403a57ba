// Tests of gpu/atrous_gpu.cpp: the Vulkan port of one a-trous level (filters/svgf/atrous.comp, its variance
// prefilter included) against the golden atrous_level() (filters/svgf/atrous.cpp) on random planes of an
// odd size at levels 0..4 with both kernels, and on a rendered frame, with the validation layer on. Skipped, with
// a message, where no Vulkan device exists.
//
// Bound: per channel (colour R, G, B, variance, prefiltered variance), max |gpu - golden| / max(|golden|, 1e-3)
// <= 5e-5, and max |gpu - golden| <= 5e-5 * max(max |golden|, 1e-3) over the plane. Why (atrous_shared.h): both
// sides do the same fp32 operations in the same order (`precise` in the shaders), except the tap weight and exp,
// log and sqrt. The golden code multiplies exp(-a_z), cos^sigma_n and exp(-a_l) [SVGF17 Eq. 2-5]; the shader
// fuses them into exp(sigma_n ln cos - a_z - a_l), the same value up to a few roundings (a few 1e-7). GLSL's exp,
// log and sqrt may differ from libm by a few ulp. A tap weight exp(sigma_n ln cos - a_z - a_l) thus differs by a
// relative (3 + 2|x|) 2^-24 from exp (|x| up to ~20 for the weights that matter: 2.6e-6) plus sigma_n times log's
// error (a few ulp of ln cos, which is small near cos = 1); the colour is a ratio of two weighted sums (about 2x the
// weight error) and the variance squared weights over a squared sum (about 4x). Measured on llvmpipe (LLVM 15),
// when the golden code still fused the weights as the shader does: colour 8.4e-6, variance 1.4e-5 relative; 5e-5
// leaves a 3.5x margin, and the suite passes with the literal golden code too. (The Vulkan spec allows log an
// absolute 2^-21 near 1, i.e. sigma_n 2^-21 = 6e-5 in a weight's exponent: a driver that used all of it could
// exceed this.)
// The prefilter uses no transcendental and matches exactly (measured 0).
//
// fp16 illumination records (the ports' _fp16 builds): the level reads colour and variance as the records hold
// them, so the golden level runs on those (golden_level); the port's fp32 arithmetic is then within the bound
// above, and it stores its result as halves: the colour bound grows by 2^-10 and the variance bound by
// (1 + 2^-10 + 2^-21)^2 - 1, a rounded sqrt squared (gpu_fixtures.h). The prefiltered variance is written as fp32
// and keeps its bound.
#include "gpu/atrous_gpu.h"

#include "core/color.h"
#include "core/error.h"
#include "eval/frame_diff.h"
#include "filters/svgf/prefilter.h"
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

constexpr double kMaxRelError = 5e-5;
constexpr double kRelFloor = 1e-3;  // relative errors are taken against max(|golden|, 1e-3)

// Largest errors seen over the whole file, printed at the end.
struct Worst {
  double abs = 0.0, rel = 0.0;
};
Worst g_colour, g_variance, g_prefiltered;

struct Errors {
  double abs = 0.0, rel = 0.0, scale = kRelFloor;  // scale: max(max |golden|, 1e-3)
};

void add(Errors& e, float gpu, float golden) {
  const double diff = std::abs(double(gpu) - double(golden));
  e.abs = std::max(e.abs, diff);
  e.rel = std::max(e.rel, rel_difference(gpu, golden, kRelFloor));
  e.scale = std::max(e.scale, std::abs(double(golden)));
}

// Checks e within kMaxRelError plus `storage`, the relative error of storing the value in its record.
void check(const Errors& e, const std::string& what, double storage, Worst& worst) {
  const double bound = kMaxRelError + storage;
  INFO(what << ": max abs error " << e.abs << " (golden up to " << e.scale << "), max relative error " << e.rel
            << " (bound " << bound << ")");
  CHECK(e.rel <= bound);
  CHECK(e.abs <= bound * e.scale);
  worst.abs = std::max(worst.abs, e.abs);
  worst.rel = std::max(worst.rel, e.rel);
}

// atrous_level on what the context's port reads: colour and variance as its illumination records hold them.
AtrousOutput golden_level(const VulkanContext& context, const RgbPlane& colour, const FloatPlane& variance,
                          const SurfacePlanes& s, int level, const SvgfParams& p) {
  return atrous_level(stored_colour(context, colour), stored_variance(context, variance), s, level, p);
}

void check_within_bound(const VulkanContext& context, const AtrousOutput& gpu, const AtrousOutput& golden) {
  REQUIRE(gpu.color.width == golden.color.width);
  REQUIRE(gpu.color.height == golden.color.height);
  Errors colour[3], variance, prefiltered;
  for (size_t i = 0; i < golden.color.data.size(); ++i) {
    for (int c = 0; c < 3; ++c) add(colour[c], gpu.color.data[i][c], golden.color.data[i][c]);
    add(variance, gpu.variance.data[i], golden.variance.data[i]);
    add(prefiltered, gpu.prefiltered_variance.data[i], golden.prefiltered_variance.data[i]);
  }
  for (int c = 0; c < 3; ++c)
    check(colour[c], std::string("colour ") + "RGB"[c], colour_storage_error(context), g_colour);
  check(variance, "variance", variance_storage_error(context), g_variance);
  check(prefiltered, "prefiltered variance", 0.0, g_prefiltered);
}

// Random G-buffer: depth in [1, 3] with gradients that sometimes match it, unit normals spread around +z (some
// facing away), a few meshes and about 1 pixel in 8 without a surface.
SurfacePlanes random_surface(std::mt19937& rng, int w, int h) {
  std::uniform_real_distribution<float> u(0.0f, 1.0f);
  SurfacePlanes s = blank_surface(w, h);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      s.depth.at(x, y) = 2.0f + 0.02f * float(x) + 0.05f * u(rng);
      s.depth_grad.at(x, y) = u(rng) < 0.5f ? glm::vec2(0.02f, 0.0f) : glm::vec2(0.1f * u(rng) - 0.05f, 0.01f * u(rng));
      const float spread = u(rng) < 0.05f ? 3.0f : 0.3f;  // a few normals turn away
      s.normal.at(x, y) = glm::normalize(glm::vec3(spread * (u(rng) - 0.5f), spread * (u(rng) - 0.5f), 1.0f));
      s.mesh.at(x, y) = u(rng) < 0.125f ? kInvalidId : uint32_t(3.0f * u(rng));
      if (s.mesh.at(x, y) == kInvalidId) s.depth.at(x, y) = 0.0f;
    }
  return s;
}

FloatPlane random_variance(std::mt19937& rng, int w, int h) {
  std::uniform_real_distribution<float> u(0.0f, 2.0f);
  FloatPlane p(w, h);
  for (float& v : p.data) v = u(rng);
  return p;
}

}  // namespace

TEST_CASE("the luminance weights the shader reads are luminance()'s") {
  CHECK(luminance(glm::vec3(1, 0, 0)) == RTDR_LUMINANCE_R);
  CHECK(luminance(glm::vec3(0, 1, 0)) == RTDR_LUMINANCE_G);
  CHECK(luminance(glm::vec3(0, 0, 1)) == RTDR_LUMINANCE_B);
}

TEST_CASE("the port matches atrous_level on random planes of an odd size, levels 0..4, both kernels") {
  const auto context = validated_context();
  INFO("device: " << context->device_name());
  std::mt19937 rng(7);
  const int w = 41, h = 29;  // a multiple of neither workgroup shape (8x8, 32x2): the last tiles overhang
  const SurfacePlanes s = random_surface(rng, w, h);
  const RgbPlane colour = random_plane(rng, w, h, 0.0f, 4.0f);
  const FloatPlane variance = random_variance(rng, w, h);
  for (const int kernel_size : {5, 3})
    for (int level = 0; level <= 4; ++level) {
      INFO("kernel " << kernel_size << ", level " << level);
      SvgfParams p;
      p.kernel_size = kernel_size;
      const AtrousOutput golden = golden_level(*context, colour, variance, s, level, p);
      double ms = 0.0;
      const AtrousOutput gpu = atrous_level_vulkan(*context, colour, variance, s, level, p, &ms);
      check_within_bound(*context, gpu, golden);
      CHECK(ms > 0.0);
    }
  check_no_validation_messages(*context);
}

TEST_CASE("the port matches atrous_level on a rendered pillars frame") {
  const auto context = validated_context();
  const Frame frame = render_frame(load_scene("pillars"), 5, 64, 36, {});
  const SurfacePlanes s = SurfacePlanes::from_frame(frame);
  const RgbPlane colour = rgb_plane(frame, "direct");
  std::mt19937 rng(3);
  const FloatPlane variance = random_variance(rng, 64, 36);  // positive, as the variance pass gives
  for (const int kernel_size : {5, 3})
    for (int level = 0; level <= 4; ++level) {
      INFO("kernel " << kernel_size << ", level " << level);
      SvgfParams p;
      p.kernel_size = kernel_size;
      const AtrousOutput golden = golden_level(*context, colour, variance, s, level, p);
      const AtrousOutput gpu = atrous_level_vulkan(*context, colour, variance, s, level, p);
      check_within_bound(*context, gpu, golden);
    }
  check_no_validation_messages(*context);
}

TEST_CASE("dispatch time at 64x36 and 320x180") {
  const auto context = validated_context();
  std::mt19937 rng(5);
  for (const auto& [w, h] : {std::pair{64, 36}, std::pair{320, 180}}) {
    const SurfacePlanes s = random_surface(rng, w, h);
    const RgbPlane colour = random_plane(rng, w, h, 0.0f, 4.0f);
    const FloatPlane variance = random_variance(rng, w, h);
    const SvgfParams p;
    atrous_level_vulkan(*context, colour, variance, s, 0, p);  // warm-up: lavapipe compiles on first use
    double ms = 0.0;
    atrous_level_vulkan(*context, colour, variance, s, 0, p, &ms);
    WARN("atrous level 0 (prefilter + level, 5x5) at " << w << "x" << h << ": " << ms << " ms on "
                                                       << context->device_name());
    CHECK(ms > 0.0);
  }
  check_no_validation_messages(*context);
}

TEST_CASE("largest errors over this file") {
  WARN("max errors: colour abs " << g_colour.abs << " rel " << g_colour.rel << "; variance abs " << g_variance.abs
                                 << " rel " << g_variance.rel << "; prefiltered abs " << g_prefiltered.abs << " rel "
                                 << g_prefiltered.rel);
}

TEST_CASE("the port rejects planes of different sizes and a bad kernel size") {
  const auto context = validated_context();
  std::mt19937 rng(1);
  const SurfacePlanes s = random_surface(rng, 4, 4);
  CHECK_THROWS_AS(atrous_level_vulkan(*context, RgbPlane(4, 5), FloatPlane(4, 5), s, 0, SvgfParams{}), Error);
  SvgfParams bad;
  bad.kernel_size = 4;
  CHECK_THROWS_AS(atrous_level_vulkan(*context, RgbPlane(4, 4), FloatPlane(4, 4), s, 0, bad), Error);
}
