// Tests of gpu/svgf_planes.cpp: the fp16 illumination records (filters/svgf/planes_shared.h) - the rounding and
// saturation of half_record_value, the standard deviation behind half_record_variance, and what packing into and
// unpacking from records of either format gives back, that the device keeps the subnormal halves they may hold -
// and the choice of records by $RTDR_VK_ILLUMINATION.
// The tests that need a device skip, with a message, where no Vulkan device exists.
#include "gpu/svgf_planes.h"

#include "core/error.h"
#include "core/shader_shared.h"
#include "gpu/atrous_gpu.h"

#include "gpu_fixtures.h"

#include <catch2/catch.hpp>

#include <bit>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <limits>
#include <string>

using namespace rtdr;
using namespace rtdr::gpu_test;

namespace {

// Sets an environment variable for one scope, then restores what was there.
class ScopedEnv {
 public:
  ScopedEnv(const char* name, const char* value) : name_(name) {
    if (const char* old = std::getenv(name)) old_ = old, had_ = true;
    setenv(name, value, 1);
  }
  ~ScopedEnv() {
    if (had_) setenv(name_, old_.c_str(), 1);
    else unsetenv(name_);
  }

 private:
  const char* name_;
  std::string old_;
  bool had_ = false;
};

}  // namespace

TEST_CASE("half_record_value rounds to the nearest half, ties to even, and saturates at 65504") {
  // Halves hold 11 significant bits: between 1 and 2 they are 2^-10 apart.
  const float ulp = std::ldexp(1.0f, -10);
  CHECK(half_record_value(1.0f) == 1.0f);
  CHECK(half_record_value(1.0f + ulp) == 1.0f + ulp);
  CHECK(half_record_value(1.0f + 0.25f * ulp) == 1.0f);           // nearer 1
  CHECK(half_record_value(1.0f + 0.75f * ulp) == 1.0f + ulp);     // nearer 1 + ulp
  CHECK(half_record_value(1.0f + 0.5f * ulp) == 1.0f);            // a tie: to the even significand
  CHECK(half_record_value(1.0f + 1.5f * ulp) == 1.0f + 2 * ulp);  // a tie: to the even significand
  CHECK(half_record_value(0.0f) == 0.0f);
  CHECK(half_record_value(std::ldexp(1.0f, -24)) == std::ldexp(1.0f, -24));  // the smallest subnormal
  CHECK(half_record_value(std::ldexp(1.0f, -26)) == 0.0f);                   // below half of it
  CHECK(half_record_value(65504.0f) == 65504.0f);
  CHECK(half_record_value(65520.0f) == kHalfMax);  // would round to infinity
  CHECK(half_record_value(1e30f) == kHalfMax);
  CHECK(half_record_value(-1e30f) == -kHalfMax);
  CHECK(half_record_value(std::numeric_limits<float>::infinity()) == kHalfMax);
  // Within 2^-11 relative everywhere in the normal range.
  for (float v = 7e-5f; v < 6e4f; v *= 1.37f) CHECK(std::abs(half_record_value(v) - v) <= std::ldexp(v, -11));
}

TEST_CASE("half_record_variance is the square of the stored standard deviation") {
  CHECK(half_record_variance(0.0f) == 0.0f);
  CHECK(half_record_variance(4.0f) == 4.0f);  // sigma = 2 is a half
  const float sigma = half_record_value(std::sqrt(2.0f));
  CHECK(half_record_variance(2.0f) == sigma * sigma);
  // Far beyond 65504 (a firefly's variance) while its standard deviation is not; a tiny variance keeps its
  // relative precision where a half variance would be a subnormal of a few bits or 0.
  CHECK(half_record_variance(1e9f) == Approx(1e9f).epsilon(2e-3));
  CHECK(half_record_variance(1e-8f) == Approx(1e-8f).epsilon(2e-3));
  CHECK(half_record_value(1e-8f) == 0.0f);
}

TEST_CASE("illumination records hold what half_record_value and half_record_variance say, or the values, both "
          "streams side by side") {
  const auto context = validated_context();
  RgbPlane colour(3, 2);
  FloatPlane variance(3, 2);
  const float values[6] = {0.0f, 1.0f / 3.0f, 2.5f, 1e5f, 7e-6f, 1234.567f};
  for (int i = 0; i < 6; ++i) {
    colour.data[i] = glm::vec3(values[i], values[(i + 1) % 6], values[(i + 2) % 6]);
    variance.data[i] = values[(i + 3) % 6];
  }
  // The indirect stream: other values, so that a record read from the wrong stream shows.
  RgbPlane colour_indirect(3, 2);
  FloatPlane variance_indirect(3, 2);
  for (int i = 0; i < 6; ++i) {
    colour_indirect.data[i] = 2.0f * colour.data[5 - i] + 1.0f;
    variance_indirect.data[i] = variance.data[5 - i] + 0.5f;
  }
  colour_indirect.data[1].r = 3.0f;  // 0x4200 as a half, for the layout check below
  const bool half = half_records(*context);
  const auto buffer = illumination_buffer(*context, 3, 2);
  CHECK(buffer->format() == (half ? TexelFormat::RGBA16F : TexelFormat::RGBA32F));
  CHECK(buffer->floats() == (half ? 24u : 48u));  // two records of 8 or 16 bytes a pixel
  pack_illumination(kDirectStream, colour, &variance, *buffer);
  pack_illumination(kIndirectStream, colour_indirect, &variance_indirect, *buffer);
  CHECK(unpack_illumination(*buffer, 3, 2, kDirectStream).data == stored_colour(*context, colour).data);
  CHECK(unpack_variance(*buffer, 3, 2, kDirectStream).data == stored_variance(*context, variance).data);
  CHECK(unpack_illumination(*buffer, 3, 2, kIndirectStream).data == stored_colour(*context, colour_indirect).data);
  CHECK(unpack_variance(*buffer, 3, 2, kIndirectStream).data == stored_variance(*context, variance_indirect).data);
  // The layout the shaders read (planes_shared.h): pixel i's direct record, then its indirect one. Pixel 1's
  // indirect red is the first value of its second record: float 4 of the pixel's 8 (32 bytes), or the low half of
  // 32-bit word 2 of its 4 (16 bytes).
  const float* pixel1 = buffer->data() + (half ? 4 : 8);
  if (half) CHECK((std::bit_cast<uint32_t>(pixel1[2]) & 0xFFFFu) == 0x4200u);
  else CHECK(pixel1[4] == 3.0f);
  CHECK_THROWS_WITH(pack_illumination(2, colour, nullptr, *buffer), Catch::Contains("stream must be"));
  CHECK_THROWS_WITH(unpack_variance(*buffer, 3, 2, -1), Catch::Contains("stream must be"));
  if (half) CHECK_THROWS_WITH(pack_rgb(colour, *buffer), Catch::Contains("halves"));
}

TEST_CASE("an empty plane packs into and unpacks from the one texel plane_buffer gives it, a larger one throws") {
  const auto context = validated_context();
  for (const TexelFormat format : {TexelFormat::RGBA32F, TexelFormat::RGBA16F, TexelFormat::RG32F}) {
    const auto buffer = plane_buffer(*context, 0, 0, format);
    CHECK(buffer->floats() == texel_floats(format));
  }
  const auto rgba = plane_buffer(*context, 0, 0, TexelFormat::RGBA32F);
  const auto illumination = illumination_buffer(*context, 0, 0);
  const auto rg = plane_buffer(*context, 0, 0, TexelFormat::RG32F);
  const auto ids = plane_buffer(*context, 0, 0, TexelFormat::R32UI);
  CHECK_NOTHROW(pack_rgb(RgbPlane(0, 0), *rgba));
  CHECK_NOTHROW(pack_illumination(kDirectStream, RgbPlane(0, 0), nullptr, *illumination));
  CHECK_NOTHROW(pack_vec2(Vec2Plane(0, 0), *rg));
  CHECK_NOTHROW(pack_ids(UIntPlane(0, 0), *ids));
  CHECK(unpack_illumination(*illumination, 0, 0, kIndirectStream).data.empty());
  CHECK(unpack_variance(*illumination, 0, 0, kIndirectStream).data.empty());
  // One texel is no room for two.
  CHECK_THROWS_WITH(pack_rgb(RgbPlane(2, 1), *rgba), Catch::Contains("cannot hold 2 records"));
  CHECK_THROWS_WITH(unpack_rgb(*rgba, 2, 1), Catch::Contains("cannot hold 2 records"));
  CHECK_THROWS_WITH(unpack_illumination(*illumination, 1, 1, kDirectStream), Catch::Contains("cannot hold 2 records"));
}

TEST_CASE("the device keeps subnormal halves, which the fp16 records' bounds rely on") {
  // Vulkan lets a device flush a subnormal to 0 wherever a shader converts to or from fp16 (core/shader_shared.h).
  // The fp16 ports' bounds assume it does not (gpu_fixtures.h). The a-trous port passes a pixel without a surface
  // through, so its records must come back as they went in: read by RTDR_INPUT_ILLUMINATION, stored by
  // RTDR_OUTPUT_ILLUMINATION.
  const auto context = validated_context();
  const float tiny = std::ldexp(1.0f, -24);  // the smallest subnormal half; 2^-14 is the smallest normal one
  const float values[] = {tiny, 3.0f * tiny, 1023.0f * tiny, std::ldexp(1.0f, -15) + tiny, 0.25f, 0.0f};
  const int w = 6, h = 1;
  RgbPlane colour(w, h);
  FloatPlane variance(w, h);
  SurfacePlanes s = blank_surface(w, h);
  for (int i = 0; i < w; ++i) {
    colour.data[i] = glm::vec3(values[i], values[(i + 1) % w], values[(i + 2) % w]);
    variance.data[i] = values[(i + 3) % w] * values[(i + 3) % w];  // the standard deviation is one of the values
    s.mesh.data[i] = kInvalidId;
  }
  const AtrousOutput gpu = atrous_level_vulkan(*context, colour, variance, s, 0, SvgfParams{});
  INFO("device " << context->device_name() << ": a value that comes back as 0 was flushed; fp16 records need a "
       "device that keeps subnormal halves, elsewhere use RTDR_VK_ILLUMINATION=fp32");
  CHECK(gpu.color.data == stored_colour(*context, colour).data);
  CHECK(gpu.variance.data == stored_variance(*context, variance).data);
  check_no_validation_messages(*context);
}

TEST_CASE("RTDR_VK_ILLUMINATION picks the illumination records, and a bad value is an error") {
  rtdr::test::skip_without_vulkan();
  {
    const ScopedEnv env("RTDR_VK_ILLUMINATION", "fp16");
    CHECK(VulkanContext().illumination_records() == IlluminationRecords::Fp16);
    // An explicit choice wins over the environment.
    CHECK(VulkanContext(VulkanOptions{.illumination = IlluminationRecords::Fp32}).illumination_records() ==
          IlluminationRecords::Fp32);
  }
  {
    const ScopedEnv env("RTDR_VK_ILLUMINATION", "fp32");
    CHECK(VulkanContext().illumination_records() == IlluminationRecords::Fp32);
  }
  {
    const ScopedEnv env("RTDR_VK_ILLUMINATION", "half");
    CHECK_THROWS_WITH(VulkanContext(), Catch::Contains("RTDR_VK_ILLUMINATION must be fp32 or fp16, got \"half\""));
  }
  {
    // Unset: fp32 on a CPU device, fp16 on a GPU.
    const ScopedEnv env("RTDR_VK_ILLUMINATION", "");
    const VulkanContext context;
    CHECK(context.illumination_records() ==
          (context.cpu_device() ? IlluminationRecords::Fp32 : IlluminationRecords::Fp16));
  }
}
