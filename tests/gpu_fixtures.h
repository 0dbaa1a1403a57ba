// Shared pieces of the port validation tests (tests/gpu_<stem>_test.cpp, ctest -L vulkan): the device with the
// Khronos validation layer (or a skip where there is none), the zero-message check, random planes, and the
// per-channel comparison of a port's RGB output against its golden pass.
#pragma once

#include "filters/image.h"
#include "filters/svgf/svgf_shared.h"
#include "gpu/vulkan_context.h"

#include <catch2/catch.hpp>

#include <glm/glm.hpp>

#include <algorithm>
#include <cmath>
#include <limits>
#include <memory>
#include <random>
#include <string>

namespace rtdr::gpu_test {

// The device for these tests, with the validation layer; null (after a WARN saying why) when there is none:
// the calling test then returns, skipped rather than failed. Every test calling it runs twice (GENERATE): with
// the ports built for texel-buffer inputs and with those built for storage-buffer inputs (core/shader_shared.h),
// so both builds of every shader are validated on whatever device there is.
inline std::unique_ptr<VulkanContext> validated_context() {
  const ShaderInputs inputs = GENERATE(ShaderInputs::Texel, ShaderInputs::Storage);
  std::string reason;
  if (!VulkanContext::available(&reason)) {
    WARN("SKIPPED: no Vulkan device: " << reason);
    return nullptr;
  }
  UNSCOPED_INFO("shader inputs: " << shader_inputs_name(inputs) << " buffers");
  return std::make_unique<VulkanContext>(VulkanOptions{.validation = true, .inputs = inputs});
}

// Any validation-layer warning or error fails the test (issue 6: "any validation message fails the test").
inline void check_no_validation_messages(const VulkanContext& context) {
  const ValidationLog& log = context.validation_log();
  for (const std::string& message : log.messages) UNSCOPED_INFO(message);
  CHECK(log.warnings == 0);
  CHECK(log.errors == 0);
}

// A w x h G-buffer with every plane allocated and zero, for the tests to fill.
inline SurfacePlanes blank_surface(int w, int h) {
  SurfacePlanes s;
  s.depth = FloatPlane(w, h);
  s.depth_grad = Vec2Plane(w, h);
  s.normal = RgbPlane(w, h);
  s.mesh = UIntPlane(w, h);
  s.motion = Vec2Plane(w, h);
  return s;
}

inline RgbPlane random_plane(std::mt19937& rng, int w, int h, float lo, float hi) {
  std::uniform_real_distribution<float> value(lo, hi);
  RgbPlane p(w, h);
  for (glm::vec3& v : p.data) v = glm::vec3(value(rng), value(rng), value(rng));
  return p;
}

// Per channel, the largest absolute and relative (to the golden value) difference; a NaN on either side counts
// as an infinite difference (std::max would drop it).
struct RgbErrors {
  glm::dvec3 abs{0.0}, rel{0.0};
};

inline RgbErrors compare_rgb(const RgbPlane& gpu, const RgbPlane& golden) {
  RgbErrors e;
  for (size_t i = 0; i < golden.data.size(); ++i)
    for (int c = 0; c < 3; ++c) {
      double diff = std::abs(double(gpu.data[i][c]) - double(golden.data[i][c]));
      if (std::isnan(diff)) diff = std::numeric_limits<double>::infinity();
      e.abs[c] = std::max(e.abs[c], diff);
      if (golden.data[i][c] != 0.0f) e.rel[c] = std::max(e.rel[c], diff / std::abs(double(golden.data[i][c])));
    }
  return e;
}

// Checks a port's RGB output against the golden one within the stated per-channel bounds (a relative bound of
// infinity checks the absolute error alone).
inline void check_rgb_within(const RgbPlane& gpu, const RgbPlane& golden, double max_abs,
                             double max_rel = std::numeric_limits<double>::infinity()) {
  REQUIRE(gpu.width == golden.width);
  REQUIRE(gpu.height == golden.height);
  const RgbErrors e = compare_rgb(gpu, golden);
  for (int c = 0; c < 3; ++c) {
    INFO("channel " << "RGB"[c] << ": max abs error " << e.abs[c] << ", max relative error " << e.rel[c]);
    CHECK(e.abs[c] <= max_abs);
    CHECK(e.rel[c] <= max_rel);
  }
}

}  // namespace rtdr::gpu_test
