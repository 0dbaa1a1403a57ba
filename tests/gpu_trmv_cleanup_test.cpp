// Tests of gpu/trmv_spatial_gpu.cpp's trmv_cleanup_vulkan: the Vulkan port (filters/trmv/cleanup.comp for w_A, w_C
// and the std, then filters/trmv/spatial.comp twice with the std plane) against the golden trmv_cleanup_pass()
// (filters/trmv/cleanup.cpp) on random planes and on the temporal blend of a rendered frame pair of the pillars
// scene, for the paper's 9x9 and a 3x3, with and without alpha^V, with the validation layer on. Skipped, with a
// message, where no Vulkan device exists.
//
// Bounds, with e = 2^-23 (an ulp of a float x is at most e |x|):
// - w_A [TRMV21 Eq. 7]: exact on every device (a subtraction and a product, `precise`, in the C++'s order).
// - w_C [TRMV21 Eq. 8]: 3 e w_C. The luminances and the sum with epsilon are bit-identical (`precise`, the same
//   order); only the division differs (Vulkan allows 2.5 ulp, C++ rounds correctly).
// - std = min(w_A + w_C, sigma_max): 5 e (w_A + w_C) (w_C's 3 e, then the sum's rounding on each side).
// - the colour: the spatial port's bound (tests/gpu_trmv_spatial_test.cpp) for radius r = (size - 1) / 2,
//   2 (2r D + (4n + 4) e) C with D = ln 2 sigma_n 2^-21 + 24 e: the 4 e more than there is the std's difference,
//   whose relative 5 e moves G = exp(-k^2 / (2 std^2)) by at most 2 (5 e) x e^-x <= 3.7 e.
// On a CPU device (lavapipe) the divisions round correctly, as C++'s do, so the test asks for bit-identical w_C
// and std there. The pixels without a surface, and those whose std is 0 along with every tap's (nothing clamped,
// alpha^V = alpha), pass through: exact on every device.
#include "gpu/trmv_spatial_gpu.h"

#include "core/error.h"
#include "filters/trmv/cleanup.h"
#include "filters/trmv/temporal.h"
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

constexpr double kE = 0x1p-23;

// The banner's colour bound for radius r and inputs of largest value C (`cmax`): the spatial pass's, with the
// std's own error (4e more) in D.
double colour_bound(int radius, double sigma_n, double cmax) { return bilateral_bound(radius, sigma_n, cmax, 24.0); }

// Max |a - b| - bound(golden) over the pixels (<= 0: within), and the max |a - b| itself.
template <class Bound>
std::pair<double, double> excess(const FloatPlane& gpu, const FloatPlane& golden, Bound bound) {
  double over = -1.0, worst = 0.0;
  for (size_t i = 0; i < golden.data.size(); ++i) {
    const double d = std::abs(double(gpu.data[i]) - double(golden.data[i]));
    worst = std::max(worst, std::isnan(d) ? INFINITY : d);
    over = std::max(over, (std::isnan(d) ? INFINITY : d) - bound(i));
  }
  return {over, worst};
}

void check_port(VulkanContext& context, const TrmvTemporalOutput& temporal, const FloatPlane& alpha_v,
                const SurfacePlanes& s, const TrmvParams& params, const SvgfParams& edges, double* ms = nullptr) {
  const TrmvCleanupOutput golden = trmv_cleanup_pass(temporal, alpha_v, s, params, edges);
  const TrmvCleanupOutput gpu = trmv_cleanup_vulkan(context, temporal, alpha_v, s, params, edges, ms);
  REQUIRE(gpu.color.width == golden.color.width);
  REQUIRE(gpu.color.height == golden.color.height);
  const bool exact = context.cpu_device();
  const auto [w_a_over, w_a_worst] = excess(gpu.w_a, golden.w_a, [](size_t) { return 0.0; });
  const auto [w_c_over, w_c_worst] = excess(gpu.w_c, golden.w_c, [&](size_t i) {
    return exact ? 0.0 : 3.0 * kE * golden.w_c.data[i];
  });
  const auto [sigma_over, sigma_worst] = excess(gpu.sigma, golden.sigma, [&](size_t i) {
    return exact ? 0.0 : 5.0 * kE * (golden.w_a.data[i] + golden.w_c.data[i]);
  });
  const int radius = (params.cleanup_size - 1) / 2;
  const double bound = colour_bound(radius, edges.sigma_n, max_value(temporal.color));
  const double colour = max_difference(gpu.color, golden.color);
  size_t filtered = 0, passed = 0, capped = 0, mismatched = 0;
  for (size_t i = 0; i < golden.sigma.data.size(); ++i) {
    capped += golden.sigma.data[i] == params.cleanup_sigma_max;
    if (golden.color.data[i] != temporal.color.data[i]) ++filtered;
    else ++passed;
    // Passed through: no surface, or std 0.
    if ((s.mesh.data[i] == kInvalidId || golden.sigma.data[i] == 0.0f) && gpu.color.data[i] != temporal.color.data[i])
      ++mismatched;
  }
  WARN(params.cleanup_size << "x" << params.cleanup_size << ": " << filtered << " pixels filtered, " << passed
                           << " unchanged, " << capped << " at the std's cap; measured max |gpu - golden|: colour "
                           << colour << " (bound " << bound << "), w_A " << w_a_worst << ", w_C " << w_c_worst
                           << ", std " << sigma_worst << " (" << (exact ? "exact" : "within 3 e w_C, 5 e (w_A + w_C)")
                           << ") on " << context.device_name());
  CHECK(colour <= bound);
  CHECK(w_a_over <= 0.0);
  CHECK(w_c_over <= 0.0);
  CHECK(sigma_over <= 0.0);
  CHECK(mismatched == 0);
}

// A temporal output: cbar_i and the fetched history random in [0, 4]; the clamp moved 30% of the histories (w_C > 0,
// large where the history is dark: some stds reach the cap), the rest unchanged (w_C = 0).
TrmvTemporalOutput random_temporal(std::mt19937& rng, int w, int h) {
  std::uniform_real_distribution<float> u(0.0f, 1.0f);
  TrmvTemporalOutput t{random_plane(rng, w, h, 0.0f, 4.0f), random_plane(rng, w, h, 0.0f, 4.0f), RgbPlane(w, h),
                       FloatPlane(w, h)};
  t.clamped = t.fetched;
  for (size_t i = 0; i < t.clamped.data.size(); ++i)
    if (u(rng) < 0.3f) t.clamped.data[i] = glm::vec3(4.0f * u(rng), 4.0f * u(rng), 4.0f * u(rng));
  for (size_t i = 0; i < t.fetched.data.size(); ++i)
    if (u(rng) < 0.1f) t.fetched.data[i] *= 0.01f;  // dark histories: large w_C
  return t;
}

// alpha^V: alpha at half the pixels (w_A = 0), else random in [0.1, 1] (falloff.h's range).
FloatPlane random_alpha_v(std::mt19937& rng, int w, int h, float alpha) {
  std::uniform_real_distribution<float> u(0.0f, 1.0f);
  FloatPlane a(w, h);
  for (float& v : a.data) v = u(rng) < 0.5f ? alpha : 0.1f + 0.9f * u(rng);
  return a;
}

TrmvParams params_with(int size) {
  TrmvParams p;
  p.cleanup_size = size;
  return p;
}

}  // namespace

TEST_CASE("the TRMV clean-up port matches trmv_cleanup_pass on random planes of an odd size") {
  const auto context = validated_context();
  std::mt19937 rng(78);
  const int w = 41, h = 29;  // a multiple of neither workgroup shape: the last tiles overhang
  const SurfacePlanes s = random_bilateral_surface(rng, w, h, false);
  const TrmvTemporalOutput temporal = random_temporal(rng, w, h);
  const FloatPlane alpha_v = random_alpha_v(rng, w, h, TrmvParams{}.alpha);
  const SvgfParams edges;
  for (const int size : {9, 3}) {
    INFO("size " << size);
    double ms = 0.0;
    check_port(*context, temporal, alpha_v, s, params_with(size), edges, &ms);
    WARN("trmv_cleanup, three dispatches " << ms << " ms (" << w << "x" << h << ") on " << context->device_name());
    CHECK(ms > 0.0);
    check_port(*context, temporal, FloatPlane{}, s, params_with(size), edges);  // alpha everywhere: w_A = 0
  }
  // Nothing clamped, alpha^V = alpha: std 0 everywhere, the identity.
  TrmvTemporalOutput unclamped = temporal;
  unclamped.clamped = unclamped.fetched;
  check_port(*context, unclamped, FloatPlane{}, s, params_with(9), edges);
  check_no_validation_messages(*context);
}

TEST_CASE("the TRMV clean-up port matches trmv_cleanup_pass after the temporal blend of a rendered pillars pair") {
  const auto context = validated_context();
  const int w = 64, h = 36;
  const Scene scene = load_scene("pillars");
  const Frame previous = render_frame(scene, 3, w, h, {}), current = render_frame(scene, 4, w, h, {});
  const SurfacePlanes s = SurfacePlanes::from_frame(current);
  // The golden temporal blend of the indirect diffuse light along the surface motion, clamped with gamma 3.
  const TrmvParams params;
  const TrmvMotion surface{xy_plane(current, "motion"), {}, {}, {}, {}};
  const TrmvHistory prev{rgb_plane(previous, "indirect.diffuse"), SurfacePlanes::from_frame(previous)};
  const TrmvTemporalOutput temporal =
      trmv_temporal_pass(rgb_plane(current, "indirect.diffuse"), s, surface, prev, FloatPlane{}, params, SvgfParams{});
  std::mt19937 rng(4);
  const FloatPlane alpha_v = random_alpha_v(rng, w, h, params.alpha);
  check_port(*context, temporal, alpha_v, s, params, SvgfParams{});
  check_port(*context, temporal, FloatPlane{}, s, params, SvgfParams{});
  check_no_validation_messages(*context);
}

TEST_CASE("the TRMV clean-up port rejects planes of different sizes") {
  const auto context = validated_context();
  const SurfacePlanes s = blank_surface(12, 12);
  const TrmvTemporalOutput t{RgbPlane(12, 12), RgbPlane(12, 12), RgbPlane(12, 12), FloatPlane(12, 12)};
  CHECK_THROWS_AS(trmv_cleanup_vulkan(*context, t, FloatPlane(12, 11), s, TrmvParams{}, SvgfParams{}), Error);
  CHECK_THROWS_AS(trmv_cleanup_vulkan(*context, t, FloatPlane{}, blank_surface(12, 11), TrmvParams{}, SvgfParams{}),
                  Error);
  TrmvTemporalOutput short_history = t;
  short_history.fetched = RgbPlane(11, 12);
  CHECK_THROWS_AS(trmv_cleanup_vulkan(*context, short_history, FloatPlane{}, s, TrmvParams{}, SvgfParams{}), Error);
}
