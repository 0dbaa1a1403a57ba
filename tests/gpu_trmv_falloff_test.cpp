// Tests of gpu/trmv_falloff_gpu.cpp: the Vulkan port (filters/trmv/falloff.comp) against the golden
// trmv_falloff_pass() (filters/trmv/falloff.cpp) on random planes and on a rendered frame pair of the shadow-fold
// scene, with the validation layer on. Skipped, with a message, where no Vulkan device exists.
//
// Bound: a pixel without Eq. 4 evidence (no surface, an invalid vector, x^V_{i-1} off the previous image or without
// a surface there, first frame) is exact on both outputs (theta = pi/2, alpha^V = alpha: the same decisions, made
// from the same fp32 operations). Elsewhere, with e = 2^-23 (an ulp of a float x is at most e |x|):
//   theta    B_t = (pi / sqrt 2) sqrt(15 e) + 1.01 (sqrt(e) + 5 e) + 4096 e pi + e pi      (~4.9e-3 rad)
//   alpha^V  B_a = e^{-1/2} / sigma (B_t + e pi / 2) + 9 e                                  (~3.0e-2 at sigma 0.1)
// Derivation. Both sides do the same fp32 operations in the same order: the shader marks every result `precise`
// (no fma contraction, no reordering) and writes glm's dot and length out ((x + y) + z, then sqrt), and the C++ is
// built without fma (no -march, no -ffp-contract). So x^V_{i-1}, the range test, floor, the id tests, d = s^V - s_i
// and both dot products are bit-identical; only the square roots, the division, acos and exp may differ.
//   cos theta = dot(n, d) / (|n| |d|): Vulkan's sqrt inherits 1 / inversesqrt (under 4.5 ulp), C++'s rounds
//   correctly (0.5): each length within 5 e relative; the product rounds once on each side (e), the division has
//   2.5 ulp on the device and 0.5 in C++ (3 e): 14 e relative, under 15 e absolute with the second-order terms and
//   |cos| <= 1 (the clamp is 1-Lipschitz).
//   acos is Hoelder: |acos a - acos b| <= acos(1 - |a - b|) <= (pi / sqrt 2) sqrt |a - b|, the first term. The
//   device's acos inherits atan2(sqrt(1 - x x), x): 1 - x x rounds to within e, sqrt of it moves by at most sqrt(e)
//   plus its own 5 e, which moves atan2 by at most that over the radius ~1 (1.01 for slack): the second term;
//   atan2 itself has 4096 ulp of theta <= pi: the third. glibc's acosf is within 1 ulp: the fourth.
//   x = theta - pi/2 rounds once on each side: Delta x <= B_t + e pi / 2. G(x) = exp(-x^2 / (2 sigma^2)) is
//   Lipschitz with constant max |G'| = e^{-1/2} / sigma (at |x| = sigma). The argument a = -x^2 / (2 sigma^2)
//   rounds to within 4 e a on the device (a product, 2 sigma sigma, 2.5 ulp of division), which moves G by at most
//   4 e a G <= 4 e / e_Euler < 1.5 e; the device's exp has (3 + 2 |a|) ulp, (3 + 2 a) e G <= 3 e; C++'s expf is
//   within 1 ulp and its rounding of a within 1.5 e a (< 0.6 e in G): 6.5 e in all, 7 e with slack. alpha^V =
//   1 - G (1 - alpha): 1 - alpha is the same on both sides; the product and the difference round once each on
//   each side (values <= 1): 2 e, so |Delta alpha^V| <= (1 - alpha) Delta G + 2 e <= the bound.
//   The static-shadow test |d| < 1e-6 (1 + |s_i|) compares two square roots: it may flip on a device only where
//   |d| is within 10 e of the threshold, relative; such pixels (none in these inputs; counted) are not compared.
// On a CPU device (lavapipe) the square roots and the division round correctly, so cos theta is bit-identical and
// only acos and exp (Mesa's polynomials, not libm's) differ. Measured worst on lavapipe (llvmpipe, LLVM 15), over
// every input and build here: theta 1.6e-4 rad (Mesa's acos), alpha^V 3.9e-4 (sigma 0.1); the pixels without
// evidence exact.
#include "gpu/trmv_falloff_gpu.h"

#include "core/error.h"
#include "filters/image.h"
#include "filters/trmv/falloff.h"
#include "filters/trmv/falloff_shared.h"
#include "filters/trmv/footprint.h"
#include "filters/trmv/trmv.h"
#include "scenes/gltf_loader.h"
#include "trace/render_frame.h"

#include "gpu_fixtures.h"

#include <catch2/catch.hpp>

#include <glm/gtc/constants.hpp>

#include <algorithm>
#include <cmath>
#include <random>
#include <string>

using namespace rtdr;
using namespace rtdr::gpu_test;

namespace {

const double kE = std::ldexp(1.0, -23);

// The banner's bounds.
double theta_bound() {
  const double pi = glm::pi<double>();
  return pi / std::sqrt(2.0) * std::sqrt(15.0 * kE) + 1.01 * (std::sqrt(kE) + 5.0 * kE) + 4096.0 * kE * pi + kE * pi;
}
double alpha_bound(double sigma) {
  return std::exp(-0.5) / sigma * (theta_bound() + kE * glm::half_pi<double>()) + 9.0 * kE;
}

// How the golden pass treated pixel (x, y), from its probe.
enum class Kind { NoEvidence, Static, Angle, NearThreshold };

Kind classify(const TrmvReceiver& r, const TrmvMotion& m, const TrmvPreviousPositions& prev, const TrmvParams& p,
              int x, int y) {
  Probe probe;
  trmv_falloff_pixel(r, m, prev, p, x, y, &probe);
  bool has_theta = false;
  glm::dvec3 s_i(0.0), s_v(0.0);
  for (const Probe::Term& t : probe.terms()) {
    if (t.name == "theta") has_theta = true;
    if (t.name == "s_i") s_i = glm::dvec3(t.value[0], t.value[1], t.value[2]);
    if (t.name == "s^V_{i-1}") s_v = glm::dvec3(t.value[0], t.value[1], t.value[2]);
  }
  if (!has_theta) return Kind::NoEvidence;
  const double len = glm::length(s_v - s_i);
  const double threshold = double(kTrmvFalloffSamePointRelative) * (1.0 + glm::length(s_i));
  if (std::abs(len - threshold) <= 10.0 * kE * threshold) return Kind::NearThreshold;
  return len < threshold ? Kind::Static : Kind::Angle;
}

struct Counts {
  int no_evidence = 0, stat = 0, angle = 0, near_threshold = 0;
};

// Port and golden pass on the same inputs: exact without evidence, within the banner's bounds elsewhere.
Counts check_port(VulkanContext& context, const TrmvReceiver& r, const TrmvMotion& m,
                  const TrmvPreviousPositions& prev, const TrmvParams& p, double* ms = nullptr) {
  const TrmvFalloffOutput golden = trmv_falloff_pass(r, m, prev, p);
  const TrmvFalloffOutput gpu = trmv_falloff_vulkan(context, r, m, prev, p, ms);
  REQUIRE(gpu.theta.width == golden.theta.width);
  REQUIRE(gpu.theta.height == golden.theta.height);
  Counts c;
  size_t exact_mismatches = 0;
  double theta = 0.0, alpha = 0.0;
  for (int y = 0; y < golden.theta.height; ++y)
    for (int x = 0; x < golden.theta.width; ++x) {
      const float gt = gpu.theta.at(x, y), ct = golden.theta.at(x, y);
      const float ga = gpu.alpha_v.at(x, y), ca = golden.alpha_v.at(x, y);
      switch (classify(r, m, prev, p, x, y)) {
        case Kind::NearThreshold: ++c.near_threshold; continue;
        case Kind::NoEvidence: ++c.no_evidence; exact_mismatches += gt != ct || ga != ca; continue;
        case Kind::Static: ++c.stat; break;
        case Kind::Angle: ++c.angle; break;
      }
      // A NaN on either side counts as an infinite difference.
      const auto diff = [](float a, float b) {
        return std::isnan(a) || std::isnan(b) ? HUGE_VAL : std::abs(double(a) - double(b));
      };
      theta = std::max(theta, diff(gt, ct));
      alpha = std::max(alpha, diff(ga, ca));
    }
  WARN("measured max |gpu - golden| on " << context.device_name() << ": theta " << theta << " rad (bound "
                                         << theta_bound() << "), alpha^V " << alpha << " (bound "
                                         << alpha_bound(p.falloff_sigma) << "); " << c.no_evidence
                                         << " pixels without evidence (" << exact_mismatches << " not exact), "
                                         << c.stat << " static, " << c.angle << " with an angle, "
                                         << c.near_threshold << " at the static threshold (not compared)");
  CHECK(exact_mismatches == 0);
  CHECK(theta <= theta_bound());
  CHECK(alpha <= alpha_bound(p.falloff_sigma));
  return c;
}

UIntPlane random_mesh(std::mt19937& rng, int w, int h, float uncovered) {
  std::uniform_real_distribution<float> u(0.0f, 1.0f);
  UIntPlane mesh(w, h);
  for (uint32_t& v : mesh.data) v = u(rng) < uncovered ? kInvalidId : uint32_t(u(rng) < 0.5f);
  return mesh;
}

// A receiver on the plane y = 0 (normal +y, some pixels' normals tilted and not unit), its previous positions the
// same points moved by the motion, some lifted off the plane (a fold: theta away from pi/2), some the same point
// (a static shadow: theta = pi/2).
struct RandomInputs {
  TrmvReceiver receiver;
  TrmvMotion motion;
  TrmvPreviousPositions prev;
};

RandomInputs random_inputs(std::mt19937& rng, int w, int h) {
  std::uniform_real_distribution<float> u(0.0f, 1.0f);
  // The receivers stand still (surface motion 0): with falloff_carry, s_i and n(s_i) are the previous frame's at
  // the same pixel where it shows the same mesh.
  RandomInputs in{{RgbPlane(w, h), RgbPlane(w, h), random_mesh(rng, w, h, 0.1f), Vec2Plane(w, h)},
                  {Vec2Plane(w, h), UIntPlane(w, h), {}, {}, {}},
                  {RgbPlane(w, h), RgbPlane(w, h), random_mesh(rng, w, h, 0.1f)}};
  // Pixel (x, y) sees the floor point (x / 8 - 2, 0, y / 8 - 1); the previous frame saw the same points.
  const auto floor_point = [](float px, float py) { return glm::vec3(px / 8.0f - 2.0f, 0.0f, py / 8.0f - 1.0f); };
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      in.receiver.position.at(x, y) = floor_point(float(x) + 0.5f, float(y) + 0.5f);
      glm::vec3 n(0.0f, 1.0f, 0.0f);
      if (u(rng) < 0.2f) n = glm::vec3(0.3f * u(rng) - 0.15f, 0.5f + u(rng), 0.3f * u(rng) - 0.15f);  // not unit
      in.receiver.normal.at(x, y) = n;
      in.prev.normal.at(x, y) = n;
      in.prev.position.at(x, y) = floor_point(float(x) + 0.5f, float(y) + 0.5f);
    }
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      glm::vec2 v = 6.0f * glm::vec2(u(rng), u(rng)) - 3.0f;  // fractional, within +-3 pixels
      const float r = u(rng);
      if (r < 0.05f) v += glm::vec2(float(w) + 2.0f * u(rng), 0.0f) * (x < w / 2 ? -1.0f : 1.0f);  // off the image
      else if (r < 0.08f) v = glm::vec2(1e6f, -1e6f);       // far off any screen (kMotionBehindCamera)
      else if (r < 0.10f) v = glm::vec2(std::nanf(""), 0.0f);  // NaN: off the image too
      else if (r < 0.25f) v = glm::vec2(0.0f);               // a static shadow: s^V_{i-1} = s_i
      in.motion.motion.at(x, y) = v;
      in.motion.valid.at(x, y) = u(rng) < 0.9f ? 1u : 0u;
    }
  // A fold: a third of the previous points lifted off the plane by up to 0.3 (theta up to ~70 degrees off pi/2),
  // some of them by under 0.01 (theta within ~sigma of pi/2, where G is steepest).
  for (glm::vec3& p : in.prev.position.data) {
    const float r = u(rng);
    if (r < 0.15f) p.y = 0.3f * (2.0f * u(rng) - 1.0f);
    else if (r < 0.33f) p.y = 0.01f * (2.0f * u(rng) - 1.0f);
  }
  return in;
}

TrmvParams params_with(float alpha, float sigma) {
  TrmvParams p;
  p.alpha = alpha;
  p.falloff_sigma = sigma;
  return p;
}

}  // namespace

TEST_CASE("the TRMV falloff port matches trmv_falloff_pass on random planes of an odd size") {
  const auto context = validated_context();
  std::mt19937 rng(4);
  const int w = 41, h = 29;
  const RandomInputs in = random_inputs(rng, w, h);
  for (const float sigma : {0.1f, 0.5f, 0.01f}) {
    INFO("sigma " << sigma);
    const TrmvParams params = params_with(0.1f, sigma);
    trmv_falloff_vulkan(*context, in.receiver, in.motion, in.prev, params);  // warm-up: lavapipe compiles
    double ms = 0.0;
    const Counts c = check_port(*context, in.receiver, in.motion, in.prev, params, &ms);
    WARN("trmv_falloff dispatch " << ms << " ms (" << w << "x" << h << ") on " << context->device_name());
    CHECK(ms > 0.0);
    // Every path of trmv_falloff_pixel is taken somewhere.
    CHECK(c.no_evidence > 0);
    CHECK(c.stat > 0);
    CHECK(c.angle > 0);
    CHECK(c.near_threshold == 0);
    // Every vector valid (the validity plane empty), another alpha.
    check_port(*context, in.receiver, {in.motion.motion, {}, {}, {}, {}}, in.prev, params_with(0.3f, sigma));
  }
  const TrmvParams params = params_with(0.1f, 0.1f);
  // First frame (empty previous positions): no evidence anywhere.
  const Counts first = check_port(*context, in.receiver, in.motion, TrmvPreviousPositions{}, params);
  CHECK(first.no_evidence == w * h);
  // Previous positions of another size (vectors land off a smaller image), and a fully uncovered previous frame.
  std::mt19937 rng2(9);
  const RandomInputs other = random_inputs(rng2, 37, 23);
  check_port(*context, in.receiver, in.motion, other.prev, params);
  TrmvPreviousPositions uncovered = in.prev;
  std::fill(uncovered.mesh.data.begin(), uncovered.mesh.data.end(), kInvalidId);
  CHECK(check_port(*context, in.receiver, in.motion, uncovered, params).no_evidence == w * h);
  check_no_validation_messages(*context);
}

TEST_CASE("the TRMV falloff port matches trmv_falloff_pass on a rendered frame pair of the shadow-fold scene") {
  const auto context = validated_context();
  const Scene scene = load_scene("shadow-fold");
  const int w = 64, h = 36;
  const Frame previous = render_frame(scene, 19, w, h, {}), current = render_frame(scene, 20, w, h, {});
  // The inputs as filters/trmv/trmv.cpp's prepare_visibility builds them.
  const SurfacePlanes surface = SurfacePlanes::from_frame(current);
  const TrmvSplatOutput splat =
      trmv_splat_pass(trmv_splat_planes(current, surface, FloatPlane()), trmv_windows(TrmvParams{}, h).splat_size);
  const TrmvMotion shadow{splat.motion, splat.landed, {}, {}, {}};
  const TrmvReceiver receiver{xyz_plane(current, "position"), xyz_plane(current, "geonormal"),
                              current.uint_channel("id.mesh"), surface.motion};
  const TrmvPreviousPositions prev{xyz_plane(previous, "position"), xyz_plane(previous, "geonormal"),
                                   previous.uint_channel("id.mesh")};
  const TrmvParams params;  // alpha 0.1, sigma 0.1
  double ms = 0.0;
  const Counts c = check_port(*context, receiver, shadow, prev, params, &ms);
  WARN("trmv_falloff dispatch " << ms << " ms (" << w << "x" << h << ") on " << context->device_name());
  CHECK(ms > 0.0);
  CHECK(c.angle > 0);
  CHECK(c.near_threshold == 0);
  check_no_validation_messages(*context);
}

TEST_CASE("the TRMV falloff port rejects planes of different sizes") {
  const auto context = validated_context();
  const TrmvReceiver receiver{RgbPlane(12, 12), RgbPlane(12, 12), UIntPlane(12, 12), Vec2Plane(12, 12)};
  const TrmvReceiver short_normal{RgbPlane(12, 12), RgbPlane(12, 11), UIntPlane(12, 12), Vec2Plane(12, 12)};
  CHECK_THROWS_AS(trmv_falloff_vulkan(*context, short_normal, {Vec2Plane(12, 12), {}, {}, {}, {}}, {}, TrmvParams{}),
                  Error);
  CHECK_THROWS_AS(trmv_falloff_vulkan(*context, receiver, {Vec2Plane(12, 12), UIntPlane(11, 12), {}, {}, {}}, {},
                                      TrmvParams{}),
                  Error);
  CHECK_THROWS_AS(trmv_falloff_vulkan(*context, receiver, {Vec2Plane(12, 12), {}, {}, {}, {}},
                                      {RgbPlane(12, 12), RgbPlane(12, 12), UIntPlane(11, 12)}, TrmvParams{}),
                  Error);
}
