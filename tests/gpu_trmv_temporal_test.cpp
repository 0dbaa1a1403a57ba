// Tests of gpu/trmv_temporal_gpu.cpp: the Vulkan port (filters/trmv/temporal.comp) against the golden
// trmv_temporal_pass() (filters/trmv/temporal.cpp) on random planes and on a rendered frame pair of the pillars
// scene, for gamma 3 (TRMV), 1 (Salvi's clamp) and 0 (no clamp), with the validation layer on. Skipped, with a
// message, where no Vulkan device exists.
//
// Bound: alpha exact; per output, max |gpu - golden| over every pixel and channel, with e = 2^-23 (an ulp of a
// float x is at most e |x|) and C the largest |value| among c~, the history and the re-shaded history:
//   fetched  B_f = 3 e C
//   clamped  B_c = B_f + [3 e C + gamma (sqrt(12 e) + 5 e) C + (1 + 2 gamma) e C]   (the bracket only for gamma > 0)
//   colour   B_c + 2 e C
// About 1.4e-2 for gamma = 3 and C = 4, 4e-6 for gamma = 0.
// Derivation. Both sides do the same fp32 operations in the same order: the shader marks every result `precise`
// (no fma contraction, no reordering), and the C++ is built without fma (no -march, no -ffp-contract), so the
// previous position, the off-image test, floor, the bilinear weights (the same formula, (d ? f : 1 - f) products),
// the tap tests, sum_w and sum_wc, and the window sums of c~ and c~^2 are bit-identical; so is every decision
// (covered, valid, re-shaded, sum_w > 0), hence alpha is the same value on both sides. Only the divisions and the
// square root may differ: Vulkan allows 2.5 ulp for x / y and inherits sqrt's precision from 1 / inversesqrt (under
// 4.5 ulp), where C++ rounds correctly (0.5 ulp); two results within 2.5 + 0.5 = 3 ulp of each other differ by at
// most 3 e |value|.
//   fetched = sum_wc / sum_w, a weighted mean of history values (|.| <= C): 3 e C.
//   mu = sum / n: 3 e C. E[c^2] = sum_sq / n: 3 e E[c^2]. mu^2 from the two mu's: (1 + 3e)^2 - 1 <= 6.01 e mu^2,
//   and one rounding on each side, e mu^2; the subtraction E[c^2] - mu^2 rounds once on each side, e E[c^2]. With
//   mu^2 <= E[c^2] <= C^2 the variance differs by at most 12 e C^2. max(., 0) does not widen that, and
//   |sqrt(a) - sqrt(b)| <= sqrt(|a - b|): sigma differs by sqrt(12 e) C, plus the device's sqrt, 5 ulp of sigma <= C.
//   (sqrt amplifies: where the window is flat, var ~ 0, a rounding of E[c^2] becomes a sigma of ~sqrt(e) C. This
//   term dominates the bound; a device with correctly rounded divisions, lavapipe, shows none of it.)
//   mu -+ gamma sigma: the product and the sum round once each on each side: (1 + 2 gamma) e C in all.
//   clamp(h, lo, hi) moves by at most max(|dh|, |dlo|, |dhi|) <= the sum of the above.
//   colour = alpha c~ + (1 - alpha) clamped: (1 - alpha) <= 1 times the clamped history's difference, plus one
//   rounding of a product and one of a sum (each <= C) on each side: 2 e C.
// A device that flushes subnormal floats to zero (Vulkan allows it without DenormPreserve) moves each result by
// under 2^-126, far below e C for the inputs here (C >= 1e-3).
// On a CPU device (lavapipe) the divisions and the square root round correctly, as C++'s do, so every term above
// is 0 and the test asks for bit-identical outputs there: only that catches a small error in the variance, which
// the sqrt term of the bound would hide. Measured: 0 on every output, input and build on lavapipe.
#include "gpu/trmv_temporal_gpu.h"

#include "core/error.h"
#include "filters/trmv/footprint.h"
#include "filters/trmv/temporal.h"
#include "filters/trmv/trmv.h"
#include "scenes/gltf_loader.h"
#include "trace/render_frame.h"

#include "gpu_fixtures.h"

#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <random>
#include <string>

using namespace rtdr;
using namespace rtdr::gpu_test;

namespace {

// The banner's bounds for inputs of largest magnitude C (`cmax`) and clamp factor gamma.
struct Bounds {
  double fetched = 0.0, clamped = 0.0, color = 0.0;
};

Bounds derived_bounds(double cmax, double gamma) {
  const double e = std::ldexp(1.0, -23);
  Bounds b;
  b.fetched = 3.0 * e * cmax;
  const double sigma = (std::sqrt(12.0 * e) + 5.0 * e) * cmax;
  const double window = 3.0 * e * cmax + gamma * sigma + (1.0 + 2.0 * gamma) * e * cmax;
  b.clamped = b.fetched + (gamma > 0.0 ? window : 0.0);
  b.color = b.clamped + 2.0 * e * cmax;
  return b;
}

double max_abs(const RgbPlane& p) {
  double m = 0.0;
  for (const glm::vec3& v : p.data)
    m = std::max({m, double(std::abs(v.r)), double(std::abs(v.g)), double(std::abs(v.b))});
  return m;
}

// C: the largest |value| the pass reads into a history or a window.
double largest_input(const RgbPlane& filtered, const TrmvMotion& motion, const TrmvHistory& prev) {
  return std::max({max_abs(filtered), max_abs(motion.reshaded), max_abs(prev.color)});
}

// Within `bound`, or bit-identical where `exact` (a CPU device: see the banner).
void check_within_bound(const TrmvTemporalOutput& gpu, const TrmvTemporalOutput& golden, const Bounds& bound,
                        bool exact) {
  REQUIRE(gpu.color.width == golden.color.width);
  REQUIRE(gpu.color.height == golden.color.height);
  const double color = max_difference(gpu.color, golden.color), fetched = max_difference(gpu.fetched, golden.fetched),
               clamped = max_difference(gpu.clamped, golden.clamped);
  size_t alpha_mismatches = 0;
  for (size_t i = 0; i < golden.alpha.data.size(); ++i) alpha_mismatches += gpu.alpha.data[i] != golden.alpha.data[i];
  WARN("measured max |gpu - golden|: colour " << color << " (bound " << bound.color << "), fetched " << fetched
                                              << " (bound " << bound.fetched << "), clamped " << clamped << " (bound "
                                              << bound.clamped << "); alpha mismatches " << alpha_mismatches);
  INFO((exact ? "CPU device: exact" : "within the derived bound"));
  CHECK(color <= (exact ? 0.0 : bound.color));
  CHECK(fetched <= (exact ? 0.0 : bound.fetched));
  CHECK(clamped <= (exact ? 0.0 : bound.clamped));
  CHECK(alpha_mismatches == 0);
}

// Port and golden pass on the same inputs, compared within the banner's bound for these inputs.
void check_port(VulkanContext& context, const RgbPlane& filtered, const SurfacePlanes& cur, const TrmvMotion& motion,
                const TrmvHistory& prev, const FloatPlane& alpha, const TrmvParams& params, double* ms = nullptr) {
  const SvgfParams svgf;
  const TrmvTemporalOutput golden = trmv_temporal_pass(filtered, cur, motion, prev, alpha, params, svgf);
  const TrmvTemporalOutput gpu = trmv_temporal_vulkan(context, filtered, cur, motion, prev, alpha, params, svgf, ms);
  check_within_bound(gpu, golden, derived_bounds(largest_input(filtered, motion, prev), params.clamp_gamma),
                     context.cpu_device());
}

// The previous G-buffer: `cur` with a fifth of its pixels on another mesh, a tilted normal or a farther depth, so
// that each history test keeps some taps and drops others.
SurfacePlanes changed_surface(std::mt19937& rng, const SurfacePlanes& cur) {
  std::uniform_real_distribution<float> u(0.0f, 1.0f);
  SurfacePlanes prev = cur;
  for (size_t i = 0; i < prev.mesh.data.size(); ++i) {
    const float r = u(rng);
    if (r < 0.07f) prev.mesh.data[i] = prev.mesh.data[i] == kInvalidId ? 0u : prev.mesh.data[i] + 1u;
    else if (r < 0.14f) prev.normal.data[i] = glm::normalize(prev.normal.data[i] + glm::vec3(2.0f, 0.0f, 0.0f));
    else if (r < 0.20f) prev.depth.data[i] *= 1.5f;
  }
  return prev;
}

// Motion within +-1.5 pixels (fractional), some vectors a few pixels off the image's far side, a few far off any
// screen (as kMotionBehindCamera); 10% invalid; 5% of the pixels with a re-shaded history.
TrmvMotion random_motion(std::mt19937& rng, int w, int h) {
  std::uniform_real_distribution<float> u(0.0f, 1.0f);
  TrmvMotion m{Vec2Plane(w, h), UIntPlane(w, h), UIntPlane(w, h), random_plane(rng, w, h, 0.0f, 4.0f),
               UIntPlane(w, h)};
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      glm::vec2 v = 3.0f * glm::vec2(u(rng), u(rng)) - 1.5f;
      const float r = u(rng);
      if (r < 0.05f) v += glm::vec2(float(w) + 2.0f * u(rng), 0.0f) * (x < w / 2 ? -1.0f : 1.0f);
      else if (r < 0.08f) v = glm::vec2(1e6f, 1e6f);
      m.motion.at(x, y) = v;
      m.valid.at(x, y) = u(rng) < 0.9f ? 1u : 0u;
      m.test.at(x, y) = uint32_t(3.0f * u(rng)) % 3u;  // kTrmvTestNone, kTrmvTestMesh or kTrmvTestSurface
      m.reshaded_valid.at(x, y) = u(rng) < 0.05f ? 1u : 0u;
    }
  return m;
}

FloatPlane random_alpha(std::mt19937& rng, int w, int h) {
  std::uniform_real_distribution<float> u(0.05f, 0.95f);
  FloatPlane a(w, h);
  for (float& v : a.data) v = u(rng);
  return a;
}

// The sum of the kept bilinear weights the golden fetch noted at (x, y), or -1 where it fetched nothing.
float kept_weight(const Probe& probe) {
  for (const Probe::Term& t : probe.terms())
    if (t.group == "fetch" && t.name == "sum of kept bilinear weights") return t.value[0];
  return -1.0f;
}

TrmvParams params_with(float gamma, int radius) {
  TrmvParams p;
  p.clamp_gamma = gamma;
  p.clamp_radius = radius;
  return p;
}

}  // namespace

TEST_CASE("the TRMV temporal port matches trmv_temporal_pass on random planes of an odd size") {
  const auto context = validated_context();
  std::mt19937 rng(21);
  const int w = 41, h = 29;
  const RgbPlane filtered = random_plane(rng, w, h, 0.0f, 4.0f);
  const SurfacePlanes cur = random_bilateral_surface(rng, w, h, true);
  const TrmvMotion motion = random_motion(rng, w, h);
  const TrmvHistory prev{random_plane(rng, w, h, 0.0f, 4.0f), changed_surface(rng, cur)};
  const FloatPlane alpha = random_alpha(rng, w, h);

  // Every path of trmv_temporal_pixel is taken somewhere (the golden probe says which ran): no history, a
  // re-shaded history, a fetch with all four taps, one with some dropped and renormalised; and the clamp moves
  // some histories and not others.
  int none = 0, reshaded = 0, full = 0, renormalised = 0, moved = 0, kept = 0;
  const TrmvParams trmv = params_with(3.0f, 1);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      Probe probe;
      const TrmvTemporalPixel p =
          trmv_temporal_pixel(filtered, cur, motion, prev, alpha, trmv, SvgfParams{}, x, y, &probe);
      const float sum_w = kept_weight(probe);
      if (p.alpha == 1.0f) ++none;
      else if (sum_w < 0.0f) ++reshaded;
      else if (sum_w > 1.0f - 1e-6f) ++full;
      else ++renormalised;
      if (p.alpha != 1.0f) (p.clamped == p.fetched ? kept : moved) += 1;
    }
  WARN("random planes: " << none << " without history, " << reshaded << " re-shaded, " << full << " with 4 taps, "
                         << renormalised << " renormalised; clamp (gamma 3) moved " << moved << ", kept " << kept);
  CHECK(none > 0);
  CHECK(reshaded > 0);
  CHECK(full > 0);
  CHECK(renormalised > 0);
  CHECK(moved > 0);
  CHECK(kept > 0);

  for (const float gamma : {3.0f, 1.0f, 0.0f})
    for (const int radius : {1, 2}) {
      INFO("gamma " << gamma << ", radius " << radius);
      const TrmvParams params = params_with(gamma, radius);
      // Warm-up: lavapipe compiles.
      trmv_temporal_vulkan(*context, filtered, cur, motion, prev, alpha, params, SvgfParams{});
      double ms = 0.0;
      check_port(*context, filtered, cur, motion, prev, alpha, params, &ms);
      WARN("trmv_temporal dispatch " << ms << " ms (" << w << "x" << h << ") on " << context->device_name());
      CHECK(ms > 0.0);
      // The optional planes empty: constant alpha, every vector valid, no history test, no re-shaded history.
      check_port(*context, filtered, cur, {motion.motion, {}, {}, {}, {}}, prev, FloatPlane{}, params);
    }
  // First frame (empty history), and a history of another size.
  check_port(*context, filtered, cur, motion, TrmvHistory{}, alpha, trmv);
  std::mt19937 rng2(5);
  const TrmvHistory other{random_plane(rng2, 37, 31, 0.0f, 4.0f), random_bilateral_surface(rng2, 37, 31, false)};
  check_port(*context, filtered, cur, motion, other, alpha, trmv);
  check_no_validation_messages(*context);
}

TEST_CASE("the TRMV temporal port matches trmv_temporal_pass on a rendered frame pair of the pillars scene") {
  const auto context = validated_context();
  const Scene scene = load_scene("pillars");
  const int w = 64, h = 36;
  const Frame previous = render_frame(scene, 3, w, h, {}), current = render_frame(scene, 4, w, h, {});
  // One component as the pipeline feeds it (filters/trmv/trmv.cpp), the noisy indirect diffuse light standing in
  // for c~: the history is the previous frame's, with its G-buffer.
  const RgbPlane filtered = rgb_plane(current, "indirect.diffuse");
  const SurfacePlanes cur = SurfacePlanes::from_frame(current);
  const TrmvHistory prev{rgb_plane(previous, "indirect.diffuse"), SurfacePlanes::from_frame(previous)};
  // Along the surface motion with the constant alpha; and along the splatted shadow motion with its validity, a
  // per-pixel alpha and, at the dual vector's disoccluded pixels, a re-shaded history (c~ itself stands in).
  // The surface motion's history test is SVGF's; the shadow vector's none (temporal.h).
  const TrmvMotion surface{cur.motion, {}, UIntPlane(w, h, kTrmvTestSurface), {}, {}};
  const TrmvSplatOutput splat =
      trmv_splat_pass(trmv_splat_planes(current, cur, FloatPlane()), trmv_windows(TrmvParams{}, h).splat_size);
  const TrmvMotion shadow{splat.motion, splat.landed, {}, filtered, current.uint_channel("motion.dual.valid")};
  std::mt19937 rng(3);
  const FloatPlane alpha = random_alpha(rng, w, h);
  size_t shadow_valid = 0, disoccluded = 0;
  for (const uint32_t v : shadow.valid.data) shadow_valid += v != 0;
  for (const uint32_t v : shadow.reshaded_valid.data) disoccluded += v != 0;
  WARN("pillars frames 3-4: " << shadow_valid << " valid shadow vectors, " << disoccluded << " re-shaded pixels");
  for (const float gamma : {3.0f, 1.0f, 0.0f}) {
    INFO("gamma " << gamma);
    const TrmvParams params = params_with(gamma, 1);
    double ms = 0.0;
    check_port(*context, filtered, cur, surface, prev, FloatPlane{}, params, &ms);
    WARN("trmv_temporal dispatch " << ms << " ms (" << w << "x" << h << ") on " << context->device_name());
    CHECK(ms > 0.0);
    check_port(*context, filtered, cur, shadow, prev, alpha, params);
  }
  check_no_validation_messages(*context);
}

TEST_CASE("the TRMV temporal port rejects planes of different sizes and a negative clamp radius") {
  const auto context = validated_context();
  const TrmvMotion motion{Vec2Plane(12, 12), {}, {}, {}, {}};
  const SvgfParams svgf;
  CHECK_THROWS_AS(trmv_temporal_vulkan(*context, RgbPlane(12, 12), blank_surface(12, 11), motion, TrmvHistory{},
                                       FloatPlane{}, TrmvParams{}, svgf),
                  Error);
  CHECK_THROWS_AS(trmv_temporal_vulkan(*context, RgbPlane(12, 12), blank_surface(12, 12), motion,
                                       TrmvHistory{RgbPlane(12, 12), blank_surface(11, 12)}, FloatPlane{},
                                       TrmvParams{}, svgf),
                  Error);
  CHECK_THROWS_AS(trmv_temporal_vulkan(*context, RgbPlane(12, 12), blank_surface(12, 12), motion, TrmvHistory{},
                                       FloatPlane{}, params_with(3.0f, -1), svgf),
                  Error);
}
