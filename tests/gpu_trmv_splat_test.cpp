// Tests of gpu/trmv_splat_gpu.cpp: the Vulkan port of TRMV's splat of shadow motion vectors [TRMV21 Sec. 4.1]
// (filters/trmv/splat.comp) against the golden trmv_splat_pass() (filters/trmv/splat.cpp), on random planes of an
// odd size at several window sides, with and without a carried property, and on a rendered fence frame, with the
// validation layer on. Skipped, with a message, where no Vulkan device exists.
//
// Bound. The same sums in the same order (the window row by row, left to right, `precise` in the shader, no fma in
// the C++), and the same same-surface test (the instance, and glm's dot product of the normals against
// kTrmvSplatNormalCosine, correctly rounded on both sides): `landed` is exact, and so is a pixel where nothing
// landed (the surface motion, or (0, 0), and a carried 0). The means sum / count are the device's division: within
// 3 e |mean| per component, e = 2^-23 (2.5 ulp allowed to Vulkan, 0.5 to C++). On a CPU device (lavapipe) the
// divisions round correctly, and the test asks for bit-identical outputs there. Measured on lavapipe: 0.
#include "gpu/trmv_splat_gpu.h"

#include "core/error.h"
#include "filters/surface_planes.h"
#include "filters/trmv/footprint.h"
#include "filters/trmv/trmv.h"
#include "scenes/gltf_loader.h"
#include "trace/render_frame.h"

#include "gpu_fixtures.h"

#include <catch2/catch.hpp>

#include <cmath>
#include <random>

using namespace rtdr;
using namespace rtdr::gpu_test;

namespace {

const double kE = std::ldexp(1.0, -23);

// A NaN on either side counts as an infinite difference.
double diff(float a, float b) { return std::isnan(a) || std::isnan(b) ? HUGE_VAL : std::abs(double(a) - double(b)); }

// Port and golden pass on the same planes: `landed` and the pixels where nothing landed exactly, the means within
// the banner's bound (exactly on a CPU device). Returns how many pixels a vector landed on.
size_t check_port(VulkanContext& context, const TrmvSplatPlanes& in, int size, double* ms = nullptr) {
  const TrmvSplatOutput golden = trmv_splat_pass(in, size);
  const TrmvSplatOutput gpu = trmv_splat_vulkan(context, in, size, ms);
  REQUIRE(gpu.motion.data.size() == golden.motion.data.size());
  const double relative = context.cpu_device() ? 0.0 : 3.01 * kE;  // 3 e, and the e^2 terms
  size_t exact_mismatches = 0, over_bound = 0, landed = 0;
  double worst = 0.0;
  for (size_t i = 0; i < golden.motion.data.size(); ++i) {
    exact_mismatches += gpu.landed.data[i] != golden.landed.data[i];
    if (golden.landed.data[i] == 0) {
      exact_mismatches += gpu.motion.data[i] != golden.motion.data[i] || gpu.carried.data[i] != golden.carried.data[i];
      continue;
    }
    ++landed;
    const float got[3] = {gpu.motion.data[i].x, gpu.motion.data[i].y, gpu.carried.data[i]};
    const float want[3] = {golden.motion.data[i].x, golden.motion.data[i].y, golden.carried.data[i]};
    for (int a = 0; a < 3; ++a) {
      const double d = diff(got[a], want[a]);
      over_bound += !(d <= relative * std::abs(double(want[a])));
      worst = std::max(worst, d);
    }
  }
  WARN("splat " << size << "x" << size << ": measured max |gpu - golden| on " << context.device_name() << ": "
                << worst << " over " << landed << " pixels where vectors landed");
  CHECK(exact_mismatches == 0);
  CHECK(over_bound == 0);
  return landed;
}

// Random planes: a third of the vectors valid, three instances and some pixels without a surface, normals that
// mostly agree and sometimes turn past the splat's cosine, and a carried property.
TrmvSplatPlanes random_planes(std::mt19937& rng, int w, int h) {
  std::uniform_real_distribution<float> u(0.0f, 1.0f);
  TrmvSplatPlanes in{Vec2Plane(w, h), UIntPlane(w, h), Vec2Plane(w, h),
                     UIntPlane(w, h), RgbPlane(w, h),  FloatPlane(w, h)};
  for (size_t i = 0; i < in.shadow.data.size(); ++i) {
    in.shadow.data[i] = 10.0f * glm::vec2(u(rng), u(rng)) - 5.0f;
    in.valid.data[i] = u(rng) < 0.35f ? 1u : 0u;
    in.surface_motion.data[i] = 4.0f * glm::vec2(u(rng), u(rng)) - 2.0f;
    in.instance.data[i] = u(rng) < 0.1f ? kInvalidId : uint32_t(3.0f * u(rng));
    const float tilt = u(rng) < 0.2f ? 1.5f : 0.2f;
    in.normal.data[i] = glm::normalize(glm::vec3(tilt * (u(rng) - 0.5f), 1.0f, tilt * (u(rng) - 0.5f)));
    in.carried.data[i] = 0.3f * u(rng);
  }
  return in;
}

}  // namespace

TEST_CASE("the TRMV splat port matches trmv_splat_pass on random planes, every window side") {
  const auto context = validated_context();
  std::mt19937 rng(11);
  TrmvSplatPlanes in = random_planes(rng, 41, 29);  // a multiple of neither workgroup shape
  for (const int size : {1, 3, 9, 31, 61}) {
    INFO("window " << size);
    double ms = 0.0;
    CHECK(check_port(*context, in, size, &ms) > 0);
    CHECK(ms > 0.0);
  }
  in.carried = FloatPlane();  // no carried property: the port carries 0
  check_port(*context, in, 9);
  check_no_validation_messages(*context);
}

TEST_CASE("the TRMV splat port matches trmv_splat_pass on a rendered fence frame") {
  const auto context = validated_context();
  const int w = 64, h = 36;
  const Frame frame = render_frame(load_scene("fence"), 10, w, h, {});
  const TrmvSplatPlanes in = trmv_splat_planes(frame, SurfacePlanes::from_frame(frame), FloatPlane());
  const int size = trmv_windows(TrmvParams{}, h).splat_size;
  double ms = 0.0;
  const size_t landed = check_port(*context, in, size, &ms);
  WARN("trmv_splat dispatch " << ms << " ms (" << w << "x" << h << ", window " << size << ") on "
                              << context->device_name() << "; vectors landed on " << landed << " pixels");
  CHECK(landed > 50);  // the fence's moving shadow
  check_no_validation_messages(*context);
}

TEST_CASE("the TRMV splat port rejects what trmv_splat_pass rejects") {
  const auto context = validated_context();
  std::mt19937 rng(3);
  const TrmvSplatPlanes in = random_planes(rng, 12, 10);
  CHECK_THROWS_AS(trmv_splat_vulkan(*context, in, 4), Error);  // an even side
  CHECK_THROWS_AS(trmv_splat_vulkan(*context, in, 0), Error);
  TrmvSplatPlanes short_normal = in;
  short_normal.normal = RgbPlane(12, 9);
  CHECK_THROWS_AS(trmv_splat_vulkan(*context, short_normal, 3), Error);
  TrmvSplatPlanes short_carried = in;
  short_carried.carried = FloatPlane(11, 10);
  CHECK_THROWS_AS(trmv_splat_vulkan(*context, short_carried, 3), Error);
}
