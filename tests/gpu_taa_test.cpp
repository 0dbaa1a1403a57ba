// Tests of gpu/taa_gpu.cpp: the Vulkan port (filters/taa/taa.comp) against the golden taa_pass()
// (filters/taa/taa.cpp) on random planes and rendered frames, with the validation layer on. Skipped, with a
// message, where no Vulkan device exists.
//
// Bound: per channel, max |gpu - golden| <= 2e-6 for display colours in [0, 1]; the relative error is measured
// and reported but not bounded (an output near 0 is a difference of values near 1). Derivation: both sides do the
// same fp32 operations in the same order and the shader marks them `precise` (no fma contraction), so the
// history position, the on-screen test, the bilinear taps and weights, the box and the blend round alike. The
// only allowed differences are the divisions, which Vulkan lets be off by 2.5 ulp (Vulkan spec, "Precision and
// Operation of SPIR-V Instructions") where C++ rounds correctly: the mean sum / 9 (YCoCg components in
// [-0.5, 1], so 2.5 ulp <= 2.5 * 2^-24 ~ 1.5e-7 absolute) and the clip t = (face - mean) / d in [0, 1] (the
// clipped point mean + t (h - mean) moves by 2.5 ulp(t) * |h - mean| <= 1.5e-7 * 1.5, plus the mean's error).
// A YCoCg component is thus off by at most ~4e-7 before the blend; (Y + Co) - Cg sums three such errors and
// adds one rounding of a value <= 2: 3 * 4e-7 + 1.2e-7 ~ 1.3e-6 < 2e-6.
// Not covered by that sum: where the box is flat (face F within the padding e of the mean, taa_shared.h), the
// mean's error dm moves t = (F - m) / d by up to t (1 - t) dm / (F - m) <= dm / (4 e) = 256 dm, i.e. up to 3.5e-5.
// Measured on these inputs: 0 on lavapipe (its divisions round correctly), and within 2e-6 on an NVIDIA H100.
// A device whose division errors land on such a steep clip would need 4e-5 here; the whole pipeline's display
// bound (tests/gpu_svgf_test.cpp, 1e-3) carries that worst case.
#include "gpu/taa_gpu.h"

#include "core/error.h"
#include "filters/svgf/modulate.h"
#include "filters/svgf/tonemap.h"
#include "filters/taa/taa.h"
#include "motion/backproject.h"
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

constexpr double kMaxAbsError = 2e-6;

// Motion of every kind: sub-pixel and a few pixels (on screen), far off screen, and behind the camera.
Vec2Plane random_motion(std::mt19937& rng, int w, int h) {
  std::uniform_real_distribution<float> near(-3.0f, 3.0f), far(-60.0f, 60.0f);
  Vec2Plane motion(w, h);
  for (size_t i = 0; i < motion.data.size(); ++i) {
    if (i % 9 == 4) motion.data[i] = glm::vec2(far(rng), far(rng));
    else if (i % 13 == 6) motion.data[i] = glm::vec2(kMotionBehindCamera);
    else if (i % 17 == 8) motion.data[i] = glm::vec2(0.0f);
    else motion.data[i] = glm::vec2(near(rng), near(rng));
  }
  return motion;
}

RgbPlane display_colour(const Frame& frame) {
  return tonemap(remodulate(rgb_plane(frame, "direct"), rgb_plane(frame, "indirect"), rgb_plane(frame, "albedo"),
                            rgb_plane(frame, "emission")),
                 TonemapParams{});
}

}  // namespace

TEST_CASE("the port matches taa_pass on random planes of an odd size, with every kind of motion and jitter") {
  const auto context = validated_context();
  INFO("device: " << context->device_name());
  std::mt19937 rng(23);
  std::uniform_real_distribution<float> unit(0.0f, 1.0f), half(-0.5f, 0.5f);
  const int w = 41, h = 29;  // a multiple of neither workgroup shape (8x8, 32x2): the last tiles overhang
  const RgbPlane current = random_plane(rng, w, h, 0.0f, 1.0f), history = random_plane(rng, w, h, 0.0f, 1.0f);
  const Vec2Plane motion = random_motion(rng, w, h);

  taa_vulkan(*context, current, history, motion, TaaParams{});  // warm-up: lavapipe compiles on first use
  for (int trial = 0; trial < 8; ++trial) {
    const TaaParams params{.alpha = trial == 0 ? TaaParams{}.alpha : unit(rng), .clip_history = trial % 2 == 0 ? 1 : 0};
    const TaaJitter jitter = trial < 2 ? TaaJitter{} : TaaJitter{{half(rng), half(rng)}, {half(rng), half(rng)}};
    INFO("trial " << trial << ": alpha " << params.alpha << ", clip_history " << params.clip_history << ", jitter ("
                  << jitter.current.x << ", " << jitter.current.y << ") previous (" << jitter.previous.x << ", "
                  << jitter.previous.y << ")");
    const RgbPlane golden = taa_pass(current, history, motion, params, jitter);
    double ms = 0.0;
    const RgbPlane gpu = taa_vulkan(*context, current, history, motion, params, jitter, &ms);
    check_rgb_within(gpu, golden, kMaxAbsError);
    INFO("dispatch " << ms << " ms on " << context->device_name());
    CHECK(ms > 0.0);
  }
  check_no_validation_messages(*context);
}

TEST_CASE("without history the port returns the current colour, as taa_pass does") {
  const auto context = validated_context();
  std::mt19937 rng(29);
  const int w = 41, h = 29;
  const RgbPlane current = random_plane(rng, w, h, 0.0f, 1.0f);
  const Vec2Plane motion = random_motion(rng, w, h);
  const TaaJitter jitter{taa_jitter(3), taa_jitter(2)};
  const RgbPlane golden = taa_pass(current, RgbPlane(), motion, TaaParams{}, jitter);
  const RgbPlane gpu = taa_vulkan(*context, current, RgbPlane(), motion, TaaParams{}, jitter);
  check_rgb_within(gpu, golden, kMaxAbsError);
  CHECK(gpu.data == current.data);
  check_no_validation_messages(*context);
}

TEST_CASE("the port matches taa_pass on rendered cornell frames") {
  const auto context = validated_context();
  const Scene scene = load_scene("cornell");
  const Frame previous = render_frame(scene, 0, 64, 36, {});
  const Frame frame = render_frame(scene, 1, 64, 36, {});
  const RgbPlane history = display_colour(previous), current = display_colour(frame);
  const Vec2Plane motion = xy_plane(frame, "motion");
  // render_frame's motion is jitter-free (TaaJitter{}); the Halton pair exercises the jitter terms as well.
  for (const TaaJitter& jitter : {TaaJitter{}, TaaJitter{taa_jitter(1), taa_jitter(0)}}) {
    for (const int clip : {1, 0}) {
      const TaaParams params{.clip_history = clip};
      INFO("clip_history " << clip << ", jitter (" << jitter.current.x << ", " << jitter.current.y << ")");
      const RgbPlane golden = taa_pass(current, history, motion, params, jitter);
      double ms = 0.0;
      const RgbPlane gpu = taa_vulkan(*context, current, history, motion, params, jitter, &ms);
      check_rgb_within(gpu, golden, kMaxAbsError);
      CHECK(ms > 0.0);
    }
  }
  check_no_validation_messages(*context);
}

TEST_CASE("the port rejects what taa_pass rejects") {
  const auto context = validated_context();
  const RgbPlane a(4, 4), b(4, 5);
  const Vec2Plane m(4, 4), m_wrong(5, 4);
  CHECK_THROWS_AS(taa_vulkan(*context, a, a, m_wrong, TaaParams{}), Error);
  CHECK_THROWS_AS(taa_vulkan(*context, a, b, m, TaaParams{}), Error);
  CHECK_THROWS_AS(taa_vulkan(*context, a, a, m, TaaParams{.alpha = 2.0f}), Error);
}
