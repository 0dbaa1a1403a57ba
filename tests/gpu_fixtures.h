// Shared pieces of the port validation tests (tests/gpu_<stem>_test.cpp, ctest -L vulkan): the device with the
// Khronos validation layer (or a skip where there is none), the zero-message check, random planes, and the
// per-channel comparison of a port's RGB output against its golden pass.
#pragma once

#include "eval/frame_diff.h"
#include "filters/image.h"
#include "filters/surface_planes.h"
#include "gpu/svgf_planes.h"
#include "gpu/vulkan_context.h"
#include "raster/view.h"
#include "test_skip.h"

#include <catch2/catch.hpp>

#include <glm/glm.hpp>

#include <algorithm>
#include <cmath>
#include <limits>
#include <memory>
#include <random>
#include <string>

namespace rtdr::gpu_test {

// The simulated devices of the motion ports' tests (a device as far from C++ as Vulkan lets it be, no Vulkan
// needed): results moved a few ulps off the correctly rounded ones, either way, as a seeded device chooses.
class UlpSkew {
 protected:
  explicit UlpSkew(unsigned seed) : rng_(seed) {}
  // x moved by up to `most` ulps, either way, as the device chooses.
  float skew(float x, int most) {
    const int ulps = std::uniform_int_distribution<int>(-most, most)(rng_);
    for (int k = 0; k < std::abs(ulps); ++k) x = std::nextafter(x, ulps > 0 ? HUGE_VALF : -HUGE_VALF);
    return x;
  }
  // View::project with its division 2 ulps off either way (Vulkan allows 2.5).
  glm::vec3 project(const View& v, const glm::vec3& world) {
    const glm::vec4 clip = v.world_to_clip * glm::vec4(world, 1.0f);
    const glm::vec2 ndc(skew(clip.x / clip.w, 2), skew(clip.y / clip.w, 2));
    return {(ndc.x * 0.5f + 0.5f) * float(v.width), (0.5f - ndc.y * 0.5f) * float(v.height), clip.w};
  }
  std::mt19937 rng_;
};

// The device for these tests, with the validation layer. Where there is none, the calling test case is skipped
// (tests/test_skip.h): ctest reports it as skipped, not passed. Every test calling it runs four times (GENERATE):
// with the ports built for texel-buffer inputs and for storage-buffer inputs (core/shader_shared.h), each with
// fp32 and with fp16 illumination records (filters/svgf/planes_shared.h), so all four builds of every shader are
// validated on whatever device there is.
inline std::unique_ptr<VulkanContext> validated_context() {
  const ShaderInputs inputs = GENERATE(ShaderInputs::Texel, ShaderInputs::Storage);
  const IlluminationRecords records = GENERATE(IlluminationRecords::Fp32, IlluminationRecords::Fp16);
  test::skip_without_vulkan();
  UNSCOPED_INFO("shader inputs: " << shader_inputs_name(inputs) << " buffers, "
                                  << illumination_records_name(records) << " illumination records");
  return std::make_unique<VulkanContext>(
      VulkanOptions{.validation = true, .inputs = inputs, .illumination = records});
}

inline bool half_records(const VulkanContext& context) {
  return context.illumination_records() == IlluminationRecords::Fp16;
}

// What a port reads of an illumination plane: with fp16 records, each colour value and each variance as the record
// holds it (half_record_value, half_record_variance: gpu/svgf_planes.h); with fp32 records the plane itself. The
// golden pass run on these reads what the port reads, so the two differ only by what the port computes and stores.
inline RgbPlane stored_colour(const VulkanContext& context, RgbPlane plane) {
  if (half_records(context))
    for (glm::vec3& v : plane.data)
      v = glm::vec3(half_record_value(v.r), half_record_value(v.g), half_record_value(v.b));
  return plane;
}
inline FloatPlane stored_variance(const VulkanContext& context, FloatPlane plane) {
  if (half_records(context))
    for (float& v : plane.data) v = half_record_variance(v);
  return plane;
}

// The largest relative error of storing an illumination colour value, and a variance, in the context's records:
// 0 with fp32 records. With fp16 records a colour value becomes one of the two halves nearest it, as the device
// chooses (core/shader_shared.h): under 2^-10 relative (11 significant bits), or 2^-24 absolute below 2^-14, which
// the tests' relative floors (1e-3 and above) turn into less than 2^-10 too. That holds on a device that keeps
// subnormal halves, which Vulkan does not require (gpu_svgf_planes_test checks the device at hand). A variance is
// the square of its standard deviation so stored, which the device's sqrt (a few fp32 ulp: under 2^-21) computed
// first: (1 + 2^-10 + 2^-21)^2 - 1, about 2^-9.
inline double colour_storage_error(const VulkanContext& context) {
  return half_records(context) ? std::ldexp(1.0, -10) : 0.0;
}
inline double variance_storage_error(const VulkanContext& context) {
  const double sigma = half_records(context) ? std::ldexp(1.0, -10) + std::ldexp(1.0, -21) : 0.0;
  return (1.0 + sigma) * (1.0 + sigma) - 1.0;
}
// The same for a variance v as an absolute error, the subnormal standard deviations included: a standard deviation
// s below 2^-14 is stored within 2^-24, which moves s^2 by at most 2^-24 (2 s + 2^-24). 0 with fp32 records.
inline double variance_storage_bound(const VulkanContext& context, double v) {
  if (!half_records(context)) return 0.0;
  const double step = std::ldexp(1.0, -24);
  return variance_storage_error(context) * v + step * (2.0 * std::sqrt(v) + step);
}

// Any validation-layer warning or error fails the test: a port that misuses the Vulkan API must not pass because
// one driver forgives it.
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

// A random G-buffer for the bilateral filters' tests (TRMV's spatial filter and clean-up): depth in [2, 3] rising
// along x with a step of 0.5 (past a third of the width, or past half the height); gradients that sometimes match
// it; unit normals spread around +z (a few facing away); a few meshes and about 1 pixel in 8 without a surface.
inline SurfacePlanes random_bilateral_surface(std::mt19937& rng, int w, int h, bool step_along_x) {
  std::uniform_real_distribution<float> u(0.0f, 1.0f);
  SurfacePlanes s = blank_surface(w, h);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      const bool past_step = step_along_x ? x > w / 3 : y > h / 2;
      s.depth.at(x, y) = 2.0f + 0.02f * float(x) + 0.05f * u(rng) + (past_step ? 0.5f : 0.0f);
      s.depth_grad.at(x, y) = u(rng) < 0.5f ? glm::vec2(0.02f, 0.0f) : glm::vec2(0.1f * u(rng) - 0.05f, 0.01f * u(rng));
      const float spread = u(rng) < 0.05f ? 3.0f : 0.3f;
      s.normal.at(x, y) = glm::normalize(glm::vec3(spread * (u(rng) - 0.5f), spread * (u(rng) - 0.5f), 1.0f));
      s.mesh.at(x, y) = u(rng) < 0.125f ? kInvalidId : uint32_t(3.0f * u(rng));
      if (s.mesh.at(x, y) == kInvalidId) s.depth.at(x, y) = 0.0f;
    }
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
      const double diff = abs_difference(gpu.data[i][c], golden.data[i][c]);  // NaN: infinite
      e.abs[c] = std::max(e.abs[c], diff);
      if (golden.data[i][c] != 0.0f) e.rel[c] = std::max(e.rel[c], diff / std::abs(double(golden.data[i][c])));
    }
  return e;
}

// Max |a - b| over every pixel and channel (a NaN on either side: infinite).
inline double max_difference(const RgbPlane& a, const RgbPlane& b) {
  const RgbErrors e = compare_rgb(a, b);
  return std::max({e.abs.r, e.abs.g, e.abs.b});
}

// Max |a - b| over every value (a NaN on either side: infinite).
inline double max_difference(const FloatPlane& a, const FloatPlane& b) {
  double m = 0.0;
  for (size_t i = 0; i < b.data.size(); ++i) m = std::max(m, abs_difference(a.data[i], b.data[i]));
  return m;
}

// The largest channel value of a plane: C in the bounds below.
inline double max_value(const RgbPlane& p) {
  double m = 0.0;
  for (const glm::vec3& v : p.data) m = std::max({m, double(v.r), double(v.g), double(v.b)});
  return m;
}

// The bound on TRMV's separable joint bilateral (two 1-D passes of radius r) for inputs of largest value C
// (`cmax`), derived in tests/gpu_trmv_spatial_test.cpp: each tap weight may differ by D = ln 2 sigma_n 2^-21 +
// `weight_ulps` e (the device's pow and exp, and the divisions), e = 2^-23.
inline double bilateral_bound(int radius, double sigma_n, double cmax, double weight_ulps) {
  const double e = std::ldexp(1.0, -23);
  const double d = std::log(2.0) * sigma_n * std::ldexp(1.0, -21) + weight_ulps * e;
  const int n = 2 * radius + 1;
  return 2.0 * (2.0 * radius * d + (4.0 * n + 4.0) * e) * cmax;
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
