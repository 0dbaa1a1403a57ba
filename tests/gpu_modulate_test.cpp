// Tests of gpu/modulate_gpu.cpp: the Vulkan port (filters/svgf/modulate.comp) against the golden remodulate()
// (filters/svgf/modulate.cpp) on random and rendered planes, with the validation layer on. Skipped, with a
// message, where no Vulkan device exists.
//
// Bound: per channel, max |gpu - golden| <= 1e-6 and max |gpu - golden| / |golden| <= 1e-6. Both sides do the
// same fp32 operations in the same order (max, add, multiply, add); the shader marks the last two `precise`
// so no fma contraction changes the rounding, but a driver that still fused them would differ by at most
// 1 ulp of the colour (relative 2^-23, about 1.2e-7). With fp16 illumination records (the ports' _fp16 builds)
// the port reads direct and indirect as the records hold them, and the golden pass runs on those (golden_colour):
// the same bound, the colour written being fp32.
#include "gpu/modulate_gpu.h"

#include "core/error.h"
#include "filters/svgf/modulate.h"
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

// remodulate on what the context's port reads: direct and indirect as its illumination records hold them.
RgbPlane golden_colour(const VulkanContext& context, const RgbPlane& direct, const RgbPlane& indirect,
                       const RgbPlane& albedo, const RgbPlane& emission) {
  return remodulate(stored_colour(context, direct), stored_colour(context, indirect), albedo, emission);
}

}  // namespace

TEST_CASE("available() gives a reason exactly when there is no Vulkan device") {
  std::string reason;
  const bool available = VulkanContext::available(&reason);
  CHECK(available == reason.empty());
}

TEST_CASE("the port matches remodulate on random planes of an odd size, black albedo included") {
  const auto context = validated_context();
  INFO("device: " << context->device_name());
  std::mt19937 rng(11);
  const int w = 37, h = 23;  // a multiple of neither workgroup shape (8x8, 32x2): the last tiles overhang
  const RgbPlane direct = random_plane(rng, w, h, 0.0f, 50.0f), indirect = random_plane(rng, w, h, 0.0f, 50.0f);
  const RgbPlane emission = random_plane(rng, w, h, 0.0f, 5.0f);
  RgbPlane albedo = random_plane(rng, w, h, 0.0f, 1.0f);
  for (size_t i = 0; i < albedo.data.size(); i += 5) albedo.data[i][i % 3] = 0.0f;  // black channels: floor 0.001
  for (size_t i = 0; i < albedo.data.size(); i += 7) albedo.data[i] = glm::vec3(0.0f);
  for (size_t i = 0; i < albedo.data.size(); i += 11) albedo.data[i] = glm::vec3(0.0005f);  // below the floor

  const RgbPlane golden = golden_colour(*context, direct, indirect, albedo, emission);
  remodulate_vulkan(*context, direct, indirect, albedo, emission);  // warm-up: lavapipe compiles on first use
  double ms = 0.0;
  const RgbPlane gpu = remodulate_vulkan(*context, direct, indirect, albedo, emission, &ms);
  check_rgb_within(gpu, golden, kMaxAbsError, kMaxRelError);
  INFO("dispatch " << ms << " ms on " << context->device_name());
  CHECK(ms > 0.0);
  check_no_validation_messages(*context);
}

TEST_CASE("the port matches remodulate on a rendered cornell frame") {
  const auto context = validated_context();
  const Frame frame = render_frame(load_scene("cornell"), 0, 64, 36, {});
  const RgbPlane direct = rgb_plane(frame, "direct"), indirect = rgb_plane(frame, "indirect");
  const RgbPlane albedo = rgb_plane(frame, "albedo"), emission = rgb_plane(frame, "emission");
  const RgbPlane golden = golden_colour(*context, direct, indirect, albedo, emission);
  double ms = 0.0;
  const RgbPlane gpu = remodulate_vulkan(*context, direct, indirect, albedo, emission, &ms);
  check_rgb_within(gpu, golden, kMaxAbsError, kMaxRelError);
  CHECK(ms > 0.0);
  check_no_validation_messages(*context);
}

TEST_CASE("the port rejects planes of different sizes") {
  const auto context = validated_context();
  const RgbPlane a(4, 4), b(4, 5);
  CHECK_THROWS_AS(remodulate_vulkan(*context, a, a, b, a), Error);
}
