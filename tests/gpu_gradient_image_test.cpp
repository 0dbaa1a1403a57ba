// Tests of gpu/asvgf_gradient_gpu.cpp: the Vulkan port (filters/asvgf/gradient_image.comp) against the golden
// gradient_image() (filters/asvgf/gradient_image.cpp) on random frames and on a rendered frame pair of the pillars
// scene with gradient samples, with the validation layer on. Skipped, with a message, where no Vulkan device exists.
//
// Bound, with e = 2^-23 (an ulp of a float x is at most e |x|) and L the largest luminance of a covered pixel:
//   delta, Delta, the geometry (n, z, depth gradient, id.mesh)   exact (0) on every device
//   l^(0)   3 e L          Var(l^(0))   12 e L^2
// Derivation. Both sides do the same fp32 operations in the same order: the shader marks every result `precise`
// (no fma contraction, no reordering; core/color.glsl's luminance too), and the C++ is built without fma (no -march,
// no -ffp-contract), so every pixel's luminance, the difference and the maximum of Eq. 3 and Eq. 13, the sums of
// l and l^2, the covered test and the representative pixel are bit-identical; the geometry is copied. Only the
// divisions may differ: Vulkan allows 2.5 ulp for x / y, where C++ rounds correctly (0.5 ulp); two results within
// 3 ulp of each other differ by at most 3 e |value|.
//   l^(0) = sum / n, a mean of luminances <= L: 3 e L.
//   Var = max(0, sum_sq / n - l^(0)^2): E[l^2] = sum_sq / n differs by 3 e E[l^2]; l^(0)^2 from the two means by
//   (1 + 3e)^2 - 1 <= 6.01 e l^(0)^2, and one rounding on each side, e l^(0)^2; the subtraction rounds once on each
//   side, e E[l^2]. With l^(0)^2 <= E[l^2] <= L^2: at most 12 e L^2; max(0, .) does not widen it.
// The variants (GradientForm): abs(delta) is exact too. The per-sample ratio r = min(1, k (|delta| / Delta)^p) of
// gradient_normalize = before divides once: 3 e relative for the quotient q <= ... (q may exceed 1 before the
// clamp, which is 1-Lipschitz), squared (p = 2) 2 (3 e) + e, times k <= 1 plus a rounding: r within 8 e of the
// golden r, since r <= 1 where it is not clamped; the sample-present weight 1 is exact.
// A device that flushes subnormal floats to zero (Vulkan allows it without DenormPreserve) moves each result by
// under 2^-126 (a subnormal luminance of the inputs here is 0 already).
// On a CPU device (lavapipe) the divisions round correctly, as C++'s do, so every term above is 0 and the test asks
// for bit-identical outputs there. Measured: 0 on every output and input on lavapipe.
#include "gpu/asvgf_gradient_gpu.h"

#include "core/color.h"
#include "core/error.h"
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

// L: the largest |luminance| of a covered pixel.
double largest_luminance(const RgbPlane& noisy, const SurfacePlanes& surface) {
  double m = 0.0;
  for (size_t i = 0; i < noisy.data.size(); ++i)
    if (surface.mesh.data[i] != kInvalidId) m = std::max(m, double(std::abs(luminance(noisy.data[i]))));
  return m;
}

// Port and golden pass on the same inputs: within the banner's bound, or bit-identical on a CPU device.
void check_port(VulkanContext& context, const RgbPlane& noisy, const UIntPlane& source, const FloatPlane& prev,
                const SurfacePlanes& surface, int s, double* ms = nullptr, const GradientForm& form = {}) {
  INFO("frame " << noisy.width << "x" << noisy.height << ", s " << s << ", form: before " << form.before
                << ", abs " << form.absolute << ", p " << form.exponent << ", k " << form.scale);
  const GradientImage golden = gradient_image(noisy, source, prev, surface, s, form);
  const GradientImage gpu = gradient_image_vulkan(context, noisy, source, prev, surface, s, form, ms);
  REQUIRE(gpu.stratum_size == golden.stratum_size);
  REQUIRE(gpu.values.delta.width == golden.values.delta.width);
  REQUIRE(gpu.values.delta.height == golden.values.delta.height);
  const double e = std::ldexp(1.0, -23), L = largest_luminance(noisy, surface);
  const double luminance_bound = 3.0 * e * L, variance_bound = 12.0 * e * L * L;
  const bool exact = context.cpu_device();
  const double delta = max_difference(gpu.values.delta, golden.values.delta),
               norm = max_difference(gpu.values.norm, golden.values.norm),
               lum = max_difference(gpu.values.luminance, golden.values.luminance),
               var = max_difference(gpu.values.variance, golden.values.variance),
               depth = max_difference(gpu.surface.depth, golden.surface.depth);
  const RgbErrors normal = compare_rgb(gpu.surface.normal, golden.surface.normal);
  double depth_grad = 0.0;
  size_t mesh_mismatches = 0;
  for (size_t i = 0; i < golden.surface.mesh.data.size(); ++i) {
    const glm::vec2 a = gpu.surface.depth_grad.data[i], b = golden.surface.depth_grad.data[i];
    depth_grad = std::max({depth_grad, abs_difference(a.x, b.x), abs_difference(a.y, b.y)});
    mesh_mismatches += gpu.surface.mesh.data[i] != golden.surface.mesh.data[i];
  }
  const double normals = std::max({normal.abs.x, normal.abs.y, normal.abs.z});
  WARN("measured max |gpu - golden|: delta " << delta << ", Delta " << norm << " (bound 0), l^(0) " << lum
                                             << " (bound " << luminance_bound << "), Var " << var << " (bound "
                                             << variance_bound << "); geometry: depth " << depth << ", normal "
                                             << normals << ", depth gradient " << depth_grad << ", mesh mismatches "
                                             << mesh_mismatches << " (bound 0)");
  INFO((exact ? "CPU device: exact" : "within the derived bound"));
  CHECK(delta <= (exact || !form.before ? 0.0 : 8.0 * e));  // the ratio divides (banner)
  CHECK(norm == 0.0);
  CHECK(lum <= (exact ? 0.0 : luminance_bound));
  CHECK(var <= (exact ? 0.0 : variance_bound));
  CHECK(depth == 0.0);
  CHECK(normals == 0.0);
  CHECK(depth_grad == 0.0);
  CHECK(mesh_mismatches == 0);
}

// A random frame for strata of s: colour in [0, 4] (a tenth of the pixels black), 20% of the pixels without a
// surface and one stratum column with none at all, the previous luminance in [0, 4] (some 0), and in 70% of the
// strata one gradient sample at a random pixel (covered or not: an uncovered one is not read).
struct RandomFrame {
  RgbPlane noisy;
  UIntPlane source;
  FloatPlane prev;
  SurfacePlanes surface;
};

RandomFrame random_frame(std::mt19937& rng, int w, int h, int s) {
  std::uniform_real_distribution<float> u(0.0f, 1.0f);
  RandomFrame f{random_plane(rng, w, h, 0.0f, 4.0f), UIntPlane(w, h, kInvalidId), FloatPlane(w, h),
                blank_surface(w, h)};
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      if (u(rng) < 0.1f) f.noisy.at(x, y) = glm::vec3(0.0f);
      f.prev.at(x, y) = u(rng) < 0.1f ? 0.0f : 4.0f * u(rng);
      const bool none = u(rng) < 0.2f || x / s == 1;
      f.surface.mesh.at(x, y) = none ? kInvalidId : uint32_t(x > w / 2);
      f.surface.depth.at(x, y) = 1.0f + 10.0f * u(rng);
      f.surface.depth_grad.at(x, y) = glm::vec2(u(rng) - 0.5f, u(rng) - 0.5f);
      f.surface.normal.at(x, y) = glm::normalize(glm::vec3(u(rng) - 0.5f, u(rng) - 0.5f, 1.0f));
    }
  for (int sy = 0; sy * s < h; ++sy)
    for (int sx = 0; sx * s < w; ++sx) {
      if (u(rng) >= 0.7f) continue;
      const int x = std::min(sx * s + int(u(rng) * float(s)), w - 1),
                y = std::min(sy * s + int(u(rng) * float(s)), h - 1);
      f.source.at(x, y) = uint32_t(y * w + x);
    }
  return f;
}

}  // namespace

TEST_CASE("the gradient image port matches gradient_image on random frames") {
  const auto context = validated_context();
  std::mt19937 rng(13);
  // Sizes that are and are not multiples of s: partial strata at the right and bottom border, a partial stratum
  // whose centre is clipped; s = 1 (every pixel a stratum).
  struct Case {
    int w, h, s;
  };
  for (const Case c : {Case{41, 29, 3}, Case{36, 27, 3}, Case{25, 18, 4}, Case{13, 7, 1}, Case{22, 17, 5}}) {
    const RandomFrame f = random_frame(rng, c.w, c.h, c.s);
    if (c.s == 3 && c.w == 41) {
      // Every path of gradient_stratum is taken somewhere: the centre as representative, another pixel, none; a
      // stratum with a sample and one without.
      int centre = 0, other = 0, none = 0, sampled = 0, unsampled = 0;
      for (int sy = 0; sy * c.s < c.h; ++sy)
        for (int sx = 0; sx * c.s < c.w; ++sx) {
          const GradientStratum r = gradient_stratum(f.noisy, f.source, f.prev, f.surface, c.s, sx, sy);
          const glm::ivec2 mid(std::min(sx * c.s + 1, c.w - 1), std::min(sy * c.s + 1, c.h - 1));
          (r.representative.x < 0 ? none : r.representative == mid ? centre : other) += 1;
          (r.norm > 0.0f ? sampled : unsampled) += 1;
        }
      WARN("random strata: representative the centre " << centre << ", another pixel " << other << ", none " << none
                                                        << "; with a sample " << sampled << ", without " << unsampled);
      CHECK(centre > 0);
      CHECK(other > 0);
      CHECK(none > 0);
      CHECK(sampled > 0);
      CHECK(unsampled > 0);
    }
    double ms = 0.0;
    check_port(*context, f.noisy, f.source, f.prev, f.surface, c.s, &ms);
    CHECK(ms > 0.0);
  }
  // The variants: abs(delta), and the per-sample ratio with the peers' square and scale.
  const RandomFrame v = random_frame(rng, 41, 29, 3);
  for (const GradientForm form : {GradientForm{.absolute = true}, GradientForm{.before = true},
                                  GradientForm{.before = true, .exponent = 2},
                                  GradientForm{.before = true, .scale = 0.1f}})
    check_port(*context, v.noisy, v.source, v.prev, v.surface, 3, nullptr, form);
  // No gradient sample anywhere: delta = Delta = 0 everywhere.
  RandomFrame f = random_frame(rng, 41, 29, 3);
  check_port(*context, f.noisy, UIntPlane(41, 29, kInvalidId), f.prev, f.surface, 3);
  // A larger frame, timed.
  const RandomFrame big = random_frame(rng, 320, 180, 3);
  gradient_image_vulkan(*context, big.noisy, big.source, big.prev, big.surface, 3);  // warm-up: lavapipe compiles
  double ms = 0.0;
  check_port(*context, big.noisy, big.source, big.prev, big.surface, 3, &ms);
  WARN("asvgf_gradient_image dispatch " << ms << " ms (320x180) on " << context->device_name());
  check_no_validation_messages(*context);
}

TEST_CASE("the gradient image port matches gradient_image on a rendered frame pair with gradient samples") {
  const auto context = validated_context();
  const test::GradientFrame pair = test::pillars_gradient_frame();  // pillars frame 4 at 50x29 (asvgf_fixtures.h)
  const Frame& current = pair.frame;
  const int s = pair.stratum_size;
  const SurfacePlanes& surface = pair.surface;
  const UIntPlane& source = current.uint_channel("gradient.source");
  size_t samples = 0;
  for (const uint32_t j : source.data) samples += j != kInvalidId;
  WARN("pillars frames 3-4: " << samples << " gradient samples, strata of " << s);
  CHECK(samples > 0);
  for (const std::string stream : {"direct", "indirect"}) {
    INFO("stream " << stream);
    double ms = 0.0;
    check_port(*context, rgb_plane(current, stream), source, current.float_channel("gradient.prev_" + stream),
               surface, s, &ms);
    CHECK(ms > 0.0);
  }
  check_no_validation_messages(*context);
}

TEST_CASE("the gradient image port rejects two samples in a stratum, planes of different sizes and s < 1") {
  const auto context = validated_context();
  std::mt19937 rng(2);
  RandomFrame f = random_frame(rng, 12, 9, 3);
  f.surface.mesh = UIntPlane(12, 9, 0u);
  f.source = UIntPlane(12, 9, kInvalidId);
  f.source.at(3, 3) = 1u;
  f.source.at(5, 5) = 2u;  // both in stratum (1, 1)
  CHECK_THROWS_WITH(gradient_image_vulkan(*context, f.noisy, f.source, f.prev, f.surface, 3),
                    "stratum (1, 1) holds two gradient samples");
  CHECK_THROWS_AS(gradient_image_vulkan(*context, f.noisy, UIntPlane(12, 8), f.prev, f.surface, 3), Error);
  CHECK_THROWS_AS(gradient_image_vulkan(*context, f.noisy, f.source, f.prev, f.surface, 0), Error);
}
