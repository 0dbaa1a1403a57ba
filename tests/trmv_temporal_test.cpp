// Tests of TRMV's temporal blend [TRMV21 Eq. 2] and history clamp [TRMV21 Sec. 5] (filters/trmv/temporal.cpp):
// exact blends by hand, exact fetches along integer motions, bilinear taps dropped and renormalised, each vector's
// history test, no history wherever the vector is invalid, and the clamp's bounds by hand, its window on the pixel's
// surface.
#include "filters/trmv/temporal.h"

#include "core/error.h"

#include "trmv_fixtures.h"

#include <catch2/catch.hpp>

#include <cmath>

using namespace rtdr;

namespace {

// A flat wall of mesh 0, 5 m away, facing the camera, standing still.
SurfacePlanes flat(int w, int h) {
  return {FloatPlane(w, h, 5.0f), Vec2Plane(w, h, glm::vec2(0.0f)), RgbPlane(w, h, glm::vec3(0.0f, 0.0f, 1.0f)),
          UIntPlane(w, h, 0u), Vec2Plane(w, h, glm::vec2(0.0f))};
}
// Zero motion, every vector valid, a covered previous frame.
TrmvMotion still(int w, int h) { return {Vec2Plane(w, h, glm::vec2(0.0f)), UIntPlane(w, h, 1u), {}, {}, {}}; }
TrmvHistory history(const RgbPlane& c) { return {c, flat(c.width, c.height)}; }
const SvgfParams kSvgf;

TrmvParams no_clamp() {
  TrmvParams p;
  p.clamp_gamma = 0.0f;
  return p;
}

}  // namespace

TEST_CASE("Eq. 2: zero motion, valid history, no clamp: cbar = alpha c + (1 - alpha) h exactly") {
  const int w = 9, h = 7;
  const RgbPlane c = noise_rgb(w, h, 1), hist = noise_rgb(w, h, 2);
  const SurfacePlanes mesh = flat(w, h);
  FloatPlane alpha(w, h);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) alpha.at(x, y) = 0.1f + 0.05f * float((x + y) % 4);  // alpha^V varies per pixel
  const TrmvTemporalOutput out = trmv_temporal_pass(c, mesh, still(w, h), history(hist), alpha, no_clamp(), kSvgf);
  for (size_t i = 0; i < c.data.size(); ++i) {
    const float a = alpha.data[i];
    CHECK(out.color.data[i] == a * c.data[i] + (1.0f - a) * hist.data[i]);
    CHECK(out.fetched.data[i] == hist.data[i]);
    CHECK(out.clamped.data[i] == hist.data[i]);
    CHECK(out.alpha.data[i] == a);
  }
  // An empty alpha plane is the constant alpha of the table (0.1, [TRMV21 Sec. 5]).
  const TrmvTemporalOutput constant = trmv_temporal_pass(c, mesh, still(w, h), history(hist), FloatPlane(), no_clamp(), kSvgf);
  for (size_t i = 0; i < c.data.size(); ++i)
    CHECK(constant.color.data[i] == 0.1f * c.data[i] + (1.0f - 0.1f) * hist.data[i]);
}

TEST_CASE("Eq. 2: a history shifted by a known integer motion is fetched exactly") {
  const int w = 10, h = 8;
  const glm::ivec2 m(3, -2);  // the content at x was at x + m in the previous frame
  const RgbPlane c = noise_rgb(w, h, 3), hist = noise_rgb(w, h, 4);
  const TrmvMotion motion{Vec2Plane(w, h, glm::vec2(m)), UIntPlane(w, h, 1u), {}, {}, {}};
  const TrmvTemporalOutput out = trmv_temporal_pass(c, flat(w, h), motion, history(hist), FloatPlane(), no_clamp(), kSvgf);
  int fetched = 0;
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      INFO("pixel " << x << ", " << y);
      if (inside(hist, x + m.x, y + m.y)) {
        CHECK(out.fetched.at(x, y) == hist.at(x + m.x, y + m.y));
        CHECK(out.alpha.at(x, y) == 0.1f);
        ++fetched;
      } else {  // x_{i-1} off the previous image: no history, cbar = c~
        CHECK(out.alpha.at(x, y) == 1.0f);
        CHECK(out.color.at(x, y) == c.at(x, y));
      }
    }
  CHECK(fetched == (w - 3) * (h - 2));
}

TEST_CASE("Eq. 2: a half-pixel motion fetches the mean of two pixels, a tap without a surface is dropped") {
  const int w = 6, h = 3;
  RgbPlane hist(w, h, glm::vec3(0.0f));
  hist.at(2, 1) = glm::vec3(1.0f, 2.0f, 4.0f);
  hist.at(3, 1) = glm::vec3(3.0f, 0.0f, 8.0f);
  TrmvHistory prev = history(hist);
  const TrmvMotion motion{Vec2Plane(w, h, glm::vec2(0.5f, 0.0f)), UIntPlane(), {}, {}, {}};  // empty: all valid
  const SurfacePlanes cur = flat(w, h);
  glm::vec3 fetched;
  // x_{i-1} = (2.5, 1.5) + (0.5, 0) = (3, 1.5): halfway between the centres of pixels 2 and 3.
  REQUIRE(trmv_fetch_history(prev, glm::vec2(3.0f, 1.5f), cur, 2, 1, kTrmvTestNone, kSvgf, fetched));
  CHECK(fetched == glm::vec3(2.0f, 1.0f, 6.0f));
  // Pixel 3 sees no surface in the previous frame: its tap is dropped, pixel 2's weight renormalised to 1.
  prev.surface.mesh.at(3, 1) = kInvalidId;
  REQUIRE(trmv_fetch_history(prev, glm::vec2(3.0f, 1.5f), cur, 2, 1, kTrmvTestNone, kSvgf, fetched));
  CHECK(fetched == glm::vec3(1.0f, 2.0f, 4.0f));
  const TrmvTemporalOutput out =
      trmv_temporal_pass(RgbPlane(w, h, glm::vec3(0.0f)), cur, motion, prev, FloatPlane(), no_clamp(), kSvgf);
  CHECK(out.fetched.at(2, 1) == glm::vec3(1.0f, 2.0f, 4.0f));
  // Every tap without a surface: no history at all.
  prev.surface.mesh = UIntPlane(w, h, kInvalidId);
  CHECK_FALSE(trmv_fetch_history(prev, glm::vec2(3.0f, 1.5f), cur, 2, 1, kTrmvTestNone, kSvgf, fetched));
  // Far off the image (the back-projection's behind-the-camera sentinel is 1e6 pixels): no history.
  CHECK_FALSE(trmv_fetch_history(history(hist), glm::vec2(1.0e6f, 1.0e6f), cur, 2, 1, kTrmvTestNone, kSvgf, fetched));
}

TEST_CASE("Eq. 2: an invalid vector, the first frame or no surface give cbar = c~ with alpha = 1") {
  const int w = 5, h = 4;
  const RgbPlane c = noise_rgb(w, h, 5), hist = noise_rgb(w, h, 6);
  SurfacePlanes mesh = flat(w, h);
  mesh.mesh.at(0, 0) = kInvalidId;
  TrmvMotion motion = still(w, h);
  motion.valid.at(2, 1) = 0;
  const TrmvTemporalOutput out = trmv_temporal_pass(c, mesh, motion, history(hist), FloatPlane(), TrmvParams{}, kSvgf);
  for (glm::ivec2 p : {glm::ivec2(2, 1), glm::ivec2(0, 0)}) {
    CHECK(out.color.at(p.x, p.y) == c.at(p.x, p.y));
    CHECK(out.alpha.at(p.x, p.y) == 1.0f);
    CHECK(out.fetched.at(p.x, p.y) == glm::vec3(0.0f));  // w_C = 0 in Eq. 8
    CHECK(out.clamped.at(p.x, p.y) == glm::vec3(0.0f));
  }
  CHECK(out.alpha.at(3, 2) == 0.1f);
  const TrmvTemporalOutput first =
      trmv_temporal_pass(c, mesh, motion, TrmvHistory{}, FloatPlane(), TrmvParams{}, kSvgf);
  for (size_t i = 0; i < c.data.size(); ++i) CHECK(first.color.data[i] == c.data[i]);
  CHECK_THROWS_AS(trmv_temporal_pass(c, flat(w, h + 1), motion, history(hist), FloatPlane(), TrmvParams{}, kSvgf),
                  Error);
}

TEST_CASE("Sec. 5 clamp: a history within mu +- 3 sigma passes unchanged, one outside lands on the bound") {
  // c~ over the 3x3 window: four pixels 0.5, four 1.5, the centre 1. mu = 9 / 9 = 1, E[c^2] = 11 / 9,
  // sigma = sqrt(2 / 9) = 0.471405: mu +- 3 sigma = [-0.414214, 2.414214], mu +- sigma = [0.528595, 1.471405].
  RgbPlane c(3, 3, glm::vec3(0.0f));
  for (int i = 0; i < 9; ++i) c.data[size_t(i)] = glm::vec3(i == 4 ? 1.0f : (i % 2 ? 0.5f : 1.5f));
  const SurfacePlanes mesh = flat(3, 3);
  const glm::vec3 h(2.0f, 3.0f, -1.0f);  // inside, above, below
  const glm::vec3 clamped = trmv_clamp_history(h, c, mesh, 3.0f, 1, true, kSvgf, 1, 1);
  CHECK(clamped.x == 2.0f);
  CHECK(clamped.y == Approx(2.414214).epsilon(1e-6));
  CHECK(clamped.z == Approx(-0.414214).epsilon(1e-5));
  // Salvi's mu +- sigma [TRMV21 Sec. 4.3], the "Trad. (Clamp)" baseline.
  const glm::vec3 salvi = trmv_clamp_history(glm::vec3(1.2f, 3.0f, -1.0f), c, mesh, 1.0f, 1, true, kSvgf, 1, 1);
  CHECK(salvi.x == 1.2f);
  CHECK(salvi.y == Approx(1.471405).epsilon(1e-6));
  CHECK(salvi.z == Approx(0.528595).epsilon(1e-6));
  // gamma = 0: no clamp at all.
  CHECK(trmv_clamp_history(h, c, mesh, 0.0f, 1, true, kSvgf, 1, 1) == h);
  // Through the pass, zero motion: cbar = alpha c~ + (1 - alpha) cbar*, and both histories are kept.
  const TrmvTemporalOutput out =
      trmv_temporal_pass(c, mesh, still(3, 3), history(RgbPlane(3, 3, h)), FloatPlane(), TrmvParams{}, kSvgf);
  CHECK(out.fetched.at(1, 1) == h);
  CHECK(out.clamped.at(1, 1) == clamped);
  CHECK(out.color.at(1, 1) == 0.1f * c.at(1, 1) + (1.0f - 0.1f) * clamped);
  // The window skips pixels without a surface: with only the centre left, sigma = 0 and the history is c~.
  SurfacePlanes alone = flat(3, 3);
  alone.mesh = UIntPlane(3, 3, kInvalidId);
  alone.mesh.at(1, 1) = 0u;
  CHECK(trmv_clamp_history(h, c, alone, 3.0f, 1, true, kSvgf, 1, 1) == glm::vec3(1.0f));
}

TEST_CASE("the clamp's window keeps to the pixel's surface: another mesh beside it does not widen mu +- 3 sigma") {
  // The centre's surface (mesh 0) holds c~ = 1 at all nine pixels but the right column, which is another mesh
  // (a slat in front of the floor) with c~ = 0. On the pixel's surface alone sigma = 0: the history lands on 1.
  // Mixing surfaces (history_test = 0, as before): mu = 6/9, sigma = sqrt(6/9 - 36/81) = 0.471405, and the history
  // 0.2 lies inside mu - 3 sigma = -0.747547: it passes unclamped.
  RgbPlane c(3, 3, glm::vec3(1.0f));
  SurfacePlanes s = flat(3, 3);
  for (int y = 0; y < 3; ++y) c.at(2, y) = glm::vec3(0.0f), s.mesh.at(2, y) = 7u;
  const glm::vec3 h(0.2f);
  CHECK(trmv_clamp_history(h, c, s, 3.0f, 1, true, kSvgf, 1, 1) == glm::vec3(1.0f));
  CHECK(trmv_clamp_history(h, c, s, 3.0f, 1, false, kSvgf, 1, 1) == h);
  // The same mesh at another depth (a fold more than 10 % away) or facing elsewhere is another surface too.
  s.mesh = UIntPlane(3, 3, 0u);
  for (int y = 0; y < 3; ++y) s.depth.at(2, y) = 6.0f;
  CHECK(trmv_clamp_history(h, c, s, 3.0f, 1, true, kSvgf, 1, 1) == glm::vec3(1.0f));
}

TEST_CASE("history tests: SVGF's for the surface vector, the same mesh for the dual and glossy ones, none for the "
          "shadow's") {
  // A 4x1 previous frame, fetched at x_{i-1} = (2, 0.5), halfway between pixels 1 and 2: pixel 1 shows what the
  // current pixel (1, 0) shows; pixel 2 is varied below.
  const int w = 4, h = 1;
  RgbPlane hist(w, h, glm::vec3(0.0f));
  hist.at(1, 0) = glm::vec3(1.0f), hist.at(2, 0) = glm::vec3(3.0f);
  const SurfacePlanes cur = flat(w, h);
  const glm::vec2 at(2.0f, 0.5f);
  const auto fetch = [&](const TrmvHistory& prev, uint32_t test) {
    glm::vec3 out(-1.0f);
    REQUIRE(trmv_fetch_history(prev, at, cur, 1, 0, test, kSvgf, out));
    return out.x;
  };
  TrmvHistory same = history(hist);
  for (uint32_t test : {kTrmvTestNone, kTrmvTestMesh, kTrmvTestSurface}) CHECK(fetch(same, test) == 2.0f);
  // Pixel 2 on another mesh: only the forced reuse keeps it.
  TrmvHistory other_mesh = history(hist);
  other_mesh.surface.mesh.at(2, 0) = 5u;
  CHECK(fetch(other_mesh, kTrmvTestNone) == 2.0f);
  CHECK(fetch(other_mesh, kTrmvTestMesh) == 1.0f);
  CHECK(fetch(other_mesh, kTrmvTestSurface) == 1.0f);
  // The same mesh, 20 % deeper (|5 - 6| > 0.1 x 6): SVGF's test drops it, the mesh test keeps it.
  TrmvHistory deeper = history(hist);
  deeper.surface.depth.at(2, 0) = 6.0f;
  CHECK(fetch(deeper, kTrmvTestMesh) == 2.0f);
  CHECK(fetch(deeper, kTrmvTestSurface) == 1.0f);
  // The same mesh, its normal turned 30 degrees (cos 0.866 < 0.9): SVGF's test drops it too.
  TrmvHistory turned = history(hist);
  turned.surface.normal.at(2, 0) = glm::vec3(0.5f, 0.0f, 0.8660254f);
  CHECK(fetch(turned, kTrmvTestMesh) == 2.0f);
  CHECK(fetch(turned, kTrmvTestSurface) == 1.0f);
  // Through the pass: the per-pixel test plane chooses; a pixel whose every tap fails takes the spatial result alone.
  TrmvMotion m{Vec2Plane(w, h, glm::vec2(1.0f, 0.0f)), UIntPlane(w, h, 1u), UIntPlane(w, h, kTrmvTestSurface), {}, {}};
  TrmvHistory far = history(hist);
  far.surface.depth = FloatPlane(w, h, 9.0f);  // everything 80 % deeper: no consistent tap
  const RgbPlane c(w, h, glm::vec3(0.5f));
  const TrmvTemporalOutput out = trmv_temporal_pass(c, cur, m, far, FloatPlane(), no_clamp(), kSvgf);
  CHECK(out.alpha.at(1, 0) == 1.0f);
  CHECK(out.color.at(1, 0) == glm::vec3(0.5f));
  m.test.at(1, 0) = kTrmvTestMesh;  // the same mesh is enough: the history is used
  CHECK(trmv_temporal_pass(c, cur, m, far, FloatPlane(), no_clamp(), kSvgf).alpha.at(1, 0) == 0.1f);
}
