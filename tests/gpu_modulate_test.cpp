// Tests of gpu/modulate_gpu.cpp: the Vulkan port (filters/svgf/modulate.comp) against the golden remodulate()
// (filters/svgf/modulate.cpp) on random and rendered planes, with the validation layer on. Skipped, with a
// message, where no Vulkan device exists.
//
// Bound: per channel, max |gpu - golden| <= 1e-6 and max |gpu - golden| / |golden| <= 1e-6. Both sides do the
// same fp32 operations in the same order (max, add, multiply, add); the shader marks the last two `precise`
// so no fma contraction changes the rounding, but a driver that still fused them would differ by at most
// 1 ulp of the colour (relative 2^-23, about 1.2e-7).
#include "gpu/modulate_gpu.h"

#include "core/error.h"
#include "filters/svgf/modulate.h"
#include "scenes/gltf_loader.h"
#include "trace/render_frame.h"

#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <memory>
#include <random>
#include <string>

using namespace rtdr;

namespace {

constexpr double kMaxAbsError = 1e-6;
constexpr double kMaxRelError = 1e-6;

// Per channel, the largest absolute and relative (to the golden value) difference.
struct Errors {
  glm::dvec3 abs{0.0}, rel{0.0};
};

Errors compare(const RgbPlane& gpu, const RgbPlane& golden) {
  Errors e;
  for (size_t i = 0; i < golden.data.size(); ++i)
    for (int c = 0; c < 3; ++c) {
      const double diff = std::abs(double(gpu.data[i][c]) - double(golden.data[i][c]));
      e.abs[c] = std::max(e.abs[c], diff);
      if (golden.data[i][c] != 0.0f) e.rel[c] = std::max(e.rel[c], diff / std::abs(double(golden.data[i][c])));
    }
  return e;
}

void check_within_bound(const RgbPlane& gpu, const RgbPlane& golden) {
  REQUIRE(gpu.width == golden.width);
  REQUIRE(gpu.height == golden.height);
  const Errors e = compare(gpu, golden);
  for (int c = 0; c < 3; ++c) {
    INFO("channel " << "RGB"[c] << ": max abs error " << e.abs[c] << ", max relative error " << e.rel[c]);
    CHECK(e.abs[c] <= kMaxAbsError);
    CHECK(e.rel[c] <= kMaxRelError);
  }
}

RgbPlane random_plane(std::mt19937& rng, int w, int h, float lo, float hi) {
  std::uniform_real_distribution<float> value(lo, hi);
  RgbPlane p(w, h);
  for (glm::vec3& v : p.data) v = glm::vec3(value(rng), value(rng), value(rng));
  return p;
}

// The device for these tests, with the validation layer; null (after a WARN saying why) when there is none.
std::unique_ptr<VulkanContext> validated_context() {
  std::string reason;
  if (!VulkanContext::available(&reason)) {
    WARN("SKIPPED: no Vulkan device: " << reason);
    return nullptr;
  }
  return std::make_unique<VulkanContext>(VulkanOptions{.validation = true});
}

void check_no_validation_messages(const VulkanContext& context) {
  const ValidationLog& log = context.validation_log();
  for (const std::string& message : log.messages) UNSCOPED_INFO(message);
  CHECK(log.warnings == 0);
  CHECK(log.errors == 0);
}

}  // namespace

TEST_CASE("available() gives a reason exactly when there is no Vulkan device") {
  std::string reason;
  const bool available = VulkanContext::available(&reason);
  CHECK(available == reason.empty());
}

TEST_CASE("the port matches remodulate on random planes of an odd size, black albedo included") {
  const auto context = validated_context();
  if (!context) return;
  INFO("device: " << context->device_name());
  std::mt19937 rng(11);
  const int w = 37, h = 23;  // neither a multiple of the 8x8 workgroup: the last tiles overhang
  const RgbPlane direct = random_plane(rng, w, h, 0.0f, 50.0f), indirect = random_plane(rng, w, h, 0.0f, 50.0f);
  const RgbPlane emission = random_plane(rng, w, h, 0.0f, 5.0f);
  RgbPlane albedo = random_plane(rng, w, h, 0.0f, 1.0f);
  for (size_t i = 0; i < albedo.data.size(); i += 5) albedo.data[i][i % 3] = 0.0f;  // black channels: floor 0.001
  for (size_t i = 0; i < albedo.data.size(); i += 7) albedo.data[i] = glm::vec3(0.0f);
  for (size_t i = 0; i < albedo.data.size(); i += 11) albedo.data[i] = glm::vec3(0.0005f);  // below the floor

  const RgbPlane golden = remodulate(direct, indirect, albedo, emission);
  remodulate_vulkan(*context, direct, indirect, albedo, emission);  // warm-up: lavapipe compiles on first use
  double ms = 0.0;
  const RgbPlane gpu = remodulate_vulkan(*context, direct, indirect, albedo, emission, &ms);
  check_within_bound(gpu, golden);
  INFO("dispatch " << ms << " ms on " << context->device_name());
  CHECK(ms > 0.0);
  check_no_validation_messages(*context);
}

TEST_CASE("the port matches remodulate on a rendered cornell frame") {
  const auto context = validated_context();
  if (!context) return;
  const Frame frame = render_frame(load_scene("cornell"), 0, 64, 36, {});
  const RgbPlane direct = rgb_plane(frame, "direct"), indirect = rgb_plane(frame, "indirect");
  const RgbPlane albedo = rgb_plane(frame, "albedo"), emission = rgb_plane(frame, "emission");
  const RgbPlane golden = remodulate(direct, indirect, albedo, emission);
  double ms = 0.0;
  const RgbPlane gpu = remodulate_vulkan(*context, direct, indirect, albedo, emission, &ms);
  check_within_bound(gpu, golden);
  CHECK(ms > 0.0);
  check_no_validation_messages(*context);
}

TEST_CASE("the port rejects planes of different sizes") {
  const auto context = validated_context();
  if (!context) return;
  const RgbPlane a(4, 4), b(4, 5);
  CHECK_THROWS_AS(remodulate_vulkan(*context, a, a, b, a), Error);
}
