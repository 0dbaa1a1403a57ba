// Tests of TRMV's non-planar receiver falloff [TRMV21 Eq. 4] (filters/trmv/falloff.cpp): the hand-computed values
// of alpha^V, theta on a planar receiver and on a fold, on a moving receiver carried back to frame i-1, and
// alpha^V = alpha wherever Eq. 4 has no evidence.
#include "filters/trmv/falloff.h"

#include "core/error.h"

#include <catch2/catch.hpp>

#include <glm/gtc/constants.hpp>

#include <cmath>

using namespace rtdr;

namespace {

constexpr float kHalfPi = glm::half_pi<float>();

// A receiver: the plane z = 0 seen from above, one unit of world space per 10 pixels, normal +z.
TrmvReceiver planar_receiver(int w, int h) {
  TrmvReceiver r{RgbPlane(w, h), RgbPlane(w, h, glm::vec3(0.0f, 0.0f, 1.0f)), UIntPlane(w, h, 0u),
                 Vec2Plane(w, h, glm::vec2(0.0f))};
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) r.position.at(x, y) = glm::vec3(0.1f * (float(x) + 0.5f), 0.1f * (float(y) + 0.5f), 0.0f);
  return r;
}

// A tilted plane through (1, 2, 3) with normal n = (1, 2, 3) / |(1, 2, 3)|, spanned by two unit tangents.
TrmvReceiver tilted_receiver(int w, int h) {
  const glm::vec3 n = glm::normalize(glm::vec3(1.0f, 2.0f, 3.0f));
  const glm::vec3 t = glm::normalize(glm::cross(n, glm::vec3(0.0f, 0.0f, 1.0f)));
  const glm::vec3 b = glm::cross(n, t);
  TrmvReceiver r{RgbPlane(w, h), RgbPlane(w, h, n), UIntPlane(w, h, 0u), Vec2Plane(w, h, glm::vec2(0.0f))};
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) r.position.at(x, y) = glm::vec3(1.0f, 2.0f, 3.0f) + 0.1f * float(x) * t + 0.07f * float(y) * b;
  return r;
}

}  // namespace

TEST_CASE("Eq. 4 by hand: theta - pi/2 = 0.1, 0.2, 0.05 rad give alpha^V = 0.45412, 0.87820, 0.20575 (alpha 0.1)") {
  // G(0.1; 0, 0.1) = e^{-1/2} = 0.60653: alpha^V = 1 - 0.60653 x 0.9 = 0.45412; G(0.2) = e^{-2}; G(0.05) = e^{-1/8}.
  CHECK(trmv_falloff_gaussian(0.1f, 0.1f) == Approx(0.60653066).epsilon(1e-6));
  CHECK(trmv_falloff_gaussian(0.0f, 0.1f) == 1.0f);  // peak 1, not normalised
  CHECK(trmv_falloff_alpha(kHalfPi + 0.1f, 0.1f, 0.1f) == Approx(0.45412).margin(1e-5));
  CHECK(trmv_falloff_alpha(kHalfPi + 0.2f, 0.1f, 0.1f) == Approx(0.87820).margin(1e-5));
  CHECK(trmv_falloff_alpha(kHalfPi + 0.05f, 0.1f, 0.1f) == Approx(0.20575).margin(1e-5));
  // Symmetric about pi/2: tilted towards or away from the normal alike.
  CHECK(trmv_falloff_alpha(kHalfPi - 0.1f, 0.1f, 0.1f) == Approx(0.45412).margin(1e-5));
  CHECK(trmv_falloff_alpha(kHalfPi, 0.1f, 0.1f) == Approx(0.1f).margin(1e-7));
  CHECK(trmv_falloff_alpha(0.0f, 0.1f, 0.1f) == Approx(1.0f).margin(1e-6));  // along the normal: no history
}

TEST_CASE("Eq. 4: a planar receiver gives theta = pi/2 and alpha^V = alpha") {
  const int w = 16, h = 12;
  for (const TrmvReceiver& r : {planar_receiver(w, h), tilted_receiver(w, h)}) {
    // The shadow moved by (3.5, -2) pixels; the previous frame sees the same plane.
    const TrmvMotion shadow{Vec2Plane(w, h, glm::vec2(3.5f, -2.0f)), UIntPlane(w, h, 1u), {}, {}, {}};
    const TrmvPreviousPositions prev{r.position, r.normal, r.mesh};
    const TrmvFalloffOutput out = trmv_falloff_pass(r, shadow, prev, TrmvParams{});
    for (int y = 0; y < h; ++y)
      for (int x = 0; x < w; ++x) {
        INFO("pixel " << x << ", " << y);
        CHECK(out.theta.at(x, y) == Approx(kHalfPi).margin(1e-4));
        CHECK(out.alpha_v.at(x, y) == Approx(0.1f).margin(1e-6));
      }
    // Where x^V_{i-1} lands inside the previous image, theta comes from Eq. 4's direction, not from the default.
    const glm::vec3 d = prev.position.at(5 + 4, 6 - 2) - r.position.at(5, 6);
    CHECK(glm::length(d) > 0.1f);
    CHECK(trmv_falloff_theta(r.position.at(5, 6), r.normal.at(5, 6), prev.position.at(9, 4)) ==
          Approx(kHalfPi).margin(1e-4));
  }
}

TEST_CASE("Eq. 4: on a fold tilted by 0.1 rad, theta = pi/2 - 0.1 and alpha^V = 0.45412") {
  // The receiver lies on z = 0 with normal +z; the previous frame's pixel under x^V_{i-1} shows a face that
  // rises at 0.1 rad: s^V_{i-1} - s_i = (cos 0.1, 0, sin 0.1), so cos theta = sin 0.1.
  const glm::vec3 s_i(0.0f), n(0.0f, 0.0f, 1.0f);
  const glm::vec3 s_v = s_i + 0.3f * glm::vec3(std::cos(0.1f), 0.0f, std::sin(0.1f));
  CHECK(trmv_falloff_theta(s_i, n, s_v) == Approx(kHalfPi - 0.1f).margin(1e-5));
  // The same through the pass: pixel (1, 0) with a shadow vector of (2, 0) lands on pixel (3, 0) of the previous
  // frame, which holds s_v.
  TrmvReceiver r{RgbPlane(5, 1, s_i), RgbPlane(5, 1, n), UIntPlane(5, 1, 0u), Vec2Plane(5, 1, glm::vec2(0.0f))};
  TrmvPreviousPositions prev{RgbPlane(5, 1, s_i), RgbPlane(5, 1, n), UIntPlane(5, 1, 0u)};
  prev.position.at(3, 0) = s_v;
  const TrmvMotion shadow{Vec2Plane(5, 1, glm::vec2(2.0f, 0.0f)), UIntPlane(5, 1, 1u), {}, {}, {}};
  const TrmvFalloffPixel p = trmv_falloff_pixel(r, shadow, prev, TrmvParams{}, 1, 0);
  CHECK(p.theta == Approx(kHalfPi - 0.1f).margin(1e-5));
  CHECK(p.alpha_v == Approx(0.45412).margin(1e-5));
  // Pixel 0 lands on pixel 2, where s^V_{i-1} = s_i: a static shadow, theta := pi/2.
  const TrmvFalloffPixel still = trmv_falloff_pixel(r, shadow, prev, TrmvParams{}, 0, 0);
  CHECK(still.theta == kHalfPi);
  CHECK(still.alpha_v == Approx(0.1f).margin(1e-7));
}

TEST_CASE("Eq. 4: no evidence (invalid vector, off the image, no previous surface, first frame) gives alpha^V = alpha") {
  const int w = 6, h = 4;
  TrmvReceiver r = planar_receiver(w, h);
  TrmvPreviousPositions prev{r.position, r.normal, r.mesh};
  for (auto& p : prev.position.data) p.z = 1.0f;  // every target is off the plane: alpha^V = 1 where seen
  TrmvMotion shadow{Vec2Plane(w, h, glm::vec2(1.0f, 0.0f)), UIntPlane(w, h, 1u), {}, {}, {}};
  TrmvParams current_planes;  // s_i on z = 0 as it is now (carried back, the plane would have moved to z = 1)
  current_planes.falloff_carry = 0;
  shadow.valid.at(0, 0) = 0;         // invalid vector
  prev.mesh.at(2, 1) = kInvalidId;   // pixel (1, 1) lands where the previous frame saw nothing
  r.mesh.at(3, 3) = kInvalidId;      // no surface now
  const TrmvFalloffOutput out = trmv_falloff_pass(r, shadow, prev, current_planes);
  for (glm::ivec2 q : {glm::ivec2(0, 0), glm::ivec2(1, 1), glm::ivec2(3, 3), glm::ivec2(5, 2)}) {  // (5, 2): off
    INFO("pixel " << q.x << ", " << q.y);
    CHECK(out.alpha_v.at(q.x, q.y) == 0.1f);
    CHECK(out.theta.at(q.x, q.y) == kHalfPi);
  }
  // A pixel with evidence: s^V is 1 above the plane and 0.1 beside s_i, theta = atan(0.1) = 0.0997 rad, far from
  // pi/2: alpha^V is 1 to within 1e-6.
  CHECK(out.alpha_v.at(2, 2) == Approx(1.0f).margin(1e-6));
  const TrmvFalloffOutput first = trmv_falloff_pass(r, shadow, TrmvPreviousPositions{}, TrmvParams{});
  for (float a : first.alpha_v.data) CHECK(a == 0.1f);
  CHECK_THROWS_AS(trmv_falloff_pass(r, TrmvMotion{Vec2Plane(w, h + 1), UIntPlane(), {}, {}, {}}, prev, TrmvParams{}),
                  Error);
}

TEST_CASE("Eq. 4 on a moving receiver: carried back to frame i-1, a plane that turned and moved stays planar") {
  // The receiver is the plane z = 0 now; in frame i-1 it stood turned by 0.2 rad about y and shifted: previous
  // point p' = R p + t. It moved one pixel left since, so its surface motion is (+1, 0). The shadow moved three
  // pixels along it: s^V_{i-1} = the previous position at x + 3, a point of the receiver's previous plane.
  const int w = 12, h = 4;
  TrmvReceiver r = planar_receiver(w, h);
  r.motion = Vec2Plane(w, h, glm::vec2(1.0f, 0.0f));
  const glm::mat3 R = glm::mat3(std::cos(0.2f), 0.0f, -std::sin(0.2f), 0.0f, 1.0f, 0.0f, std::sin(0.2f), 0.0f,
                                std::cos(0.2f));
  const glm::vec3 t(0.3f, -0.1f, 0.5f);
  TrmvPreviousPositions prev{RgbPlane(w, h), RgbPlane(w, h, R * glm::vec3(0.0f, 0.0f, 1.0f)), UIntPlane(w, h, 0u)};
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) prev.position.at(x, y) = R * r.position.at(x, y) + t;
  const TrmvMotion shadow{Vec2Plane(w, h, glm::vec2(3.0f, 0.0f)), UIntPlane(w, h, 1u), {}, {}, {}};
  // Carried back (the default): n(s_i) and s_i are the previous plane's, s^V_{i-1} lies in it, theta = pi/2.
  glm::vec3 s = r.position.at(2, 1), n = r.normal.at(2, 1);
  REQUIRE(trmv_falloff_carry_back(r, prev, 2, 1, s, n));
  CHECK(s == prev.position.at(3, 1));  // x_i + m = (3.5, 1.5): the pixel (3, 1)
  const TrmvFalloffOutput carried = trmv_falloff_pass(r, shadow, prev, TrmvParams{});
  // With the current planes (falloff_carry = 0), as before: z = 0 and +z against a point of the turned plane.
  TrmvParams current_planes;
  current_planes.falloff_carry = 0;
  const TrmvFalloffOutput current = trmv_falloff_pass(r, shadow, prev, current_planes);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x + 3 < w; ++x) {
      INFO("pixel " << x << ", " << y);
      CHECK(carried.theta.at(x, y) == Approx(kHalfPi).margin(1e-4));
      CHECK(carried.alpha_v.at(x, y) == Approx(0.1f).margin(1e-5));
      CHECK(current.alpha_v.at(x, y) > 0.9f);  // the history would be thrown away on a flat, moving receiver
    }
  // The previous frame shows another mesh where the receiver was: not carried, the current planes stand.
  prev.mesh.at(3, 1) = 4u;
  s = r.position.at(2, 1);
  CHECK_FALSE(trmv_falloff_carry_back(r, prev, 2, 1, s, n));
  CHECK(s == r.position.at(2, 1));
}
