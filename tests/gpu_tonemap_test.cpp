// Tests of gpu/tonemap_gpu.cpp: the Vulkan port (filters/svgf/tonemap.comp) against the golden tonemap()
// (filters/svgf/tonemap.cpp) on random HDR planes and a rendered frame, with the validation layer on. Skipped,
// with a message, where no Vulkan device exists.
//
// Bound: per channel, max |gpu - golden| <= 1e-6 and max |gpu - golden| / |golden| <= 1e-6. Derivation: both
// sides do the same fp32 operations in the same order (3 products and 2 sums for L_w, a product, a sum, two
// divisions, a product, a clamp); the shader marks them `precise`, so no fma contraction changes the rounding.
// The only allowed difference is the division: Vulkan lets x / y be off by 2.5 ulp (Vulkan spec, "Precision and
// Operation of SPIR-V Instructions"), C++ rounds it correctly. L_d = L / (1 + L) may then be off by 2.5 ulp,
// scale = L_d / L_w by 2.5 + 2.5 ulp, and scale * colour by 5 ulp plus the one rounding both sides share:
// relative 5 * 2^-23 ~ 6e-7 < 1e-6. The display values are in [0, 1], so the absolute error is at most the
// relative one; the clamp only removes error.
#include "gpu/tonemap_gpu.h"

#include "core/error.h"
#include "filters/svgf/modulate.h"
#include "filters/svgf/tonemap.h"
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

constexpr double kMaxAbsError = 1e-6;
constexpr double kMaxRelError = 1e-6;

}  // namespace

TEST_CASE("the port matches tonemap on random HDR planes of an odd size, black and saturated included") {
  const auto context = validated_context();
  INFO("device: " << context->device_name());
  std::mt19937 rng(17);
  const int w = 41, h = 29;  // a multiple of neither workgroup shape (8x8, 32x2): the last tiles overhang
  RgbPlane colour = random_plane(rng, w, h, 0.0f, 10.0f);
  for (size_t i = 0; i < colour.data.size(); i += 7) colour.data[i] = glm::vec3(0.0f);           // black: L_w = 0
  for (size_t i = 3; i < colour.data.size(); i += 11) colour.data[i] = glm::vec3(0.0f, 0.0f, 10.0f);  // saturated
  for (size_t i = 5; i < colour.data.size(); i += 13) colour.data[i] = glm::vec3(-1.0f, 0.5f, 0.0f);  // L_w < 0
  for (size_t i = 6; i < colour.data.size(); i += 17) colour.data[i] *= 1e-4f;                         // dim

  tonemap_vulkan(*context, colour, TonemapParams{});  // warm-up: lavapipe compiles on first use
  for (const float exposure : {1.0f, 0.18f, 4.0f, 0.0f}) {
    INFO("exposure " << exposure);
    const TonemapParams params{.exposure = exposure};
    const RgbPlane golden = tonemap(colour, params);
    double ms = 0.0;
    const RgbPlane gpu = tonemap_vulkan(*context, colour, params, &ms);
    check_rgb_within(gpu, golden, kMaxAbsError, kMaxRelError);
    INFO("dispatch " << ms << " ms on " << context->device_name());
    CHECK(ms > 0.0);
  }
  check_no_validation_messages(*context);
}

TEST_CASE("the port matches tonemap on a rendered cornell frame") {
  const auto context = validated_context();
  const Frame frame = render_frame(load_scene("cornell"), 0, 64, 36, {});
  const RgbPlane colour = remodulate(rgb_plane(frame, "direct"), rgb_plane(frame, "indirect"),
                                     rgb_plane(frame, "albedo"), rgb_plane(frame, "emission"));
  const RgbPlane golden = tonemap(colour, TonemapParams{});
  double ms = 0.0;
  const RgbPlane gpu = tonemap_vulkan(*context, colour, TonemapParams{}, &ms);
  check_rgb_within(gpu, golden, kMaxAbsError, kMaxRelError);
  CHECK(ms > 0.0);
  check_no_validation_messages(*context);
}

TEST_CASE("the port rejects an exposure outside its range, as tonemap does") {
  const auto context = validated_context();
  const RgbPlane a(4, 4);
  CHECK_THROWS_AS(tonemap_vulkan(*context, a, TonemapParams{.exposure = -1.0f}), Error);
}
