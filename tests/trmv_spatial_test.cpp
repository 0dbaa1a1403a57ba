// Tests of TRMV's separable joint-bilateral spatial filter (filters/trmv/spatial.cpp) [TRMV21 Sec. 5]: the
// weights normalise (a constant stays constant), a spike spreads as the separable Gaussian G(dx) G(dy) / S^2 on a
// flat surface, normals and missing surfaces stop it, std 0 is the identity.
#include "filters/trmv/spatial.h"

#include "core/error.h"

#include "svgf_fixtures.h"

#include "trmv_fixtures.h"

#include <catch2/catch.hpp>

#include <cmath>

using namespace rtdr;

namespace {

// A plane tilted in x: depth grows by `slope` per pixel, and depth.dX says so; w_z = exp(-1 / sigma_z) per tap.
SurfacePlanes tilted_surface(int w, int h, float slope) {
  SurfacePlanes s = flat_surface(w, h);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      s.depth.at(x, y) = 2.0f + slope * float(x);
      s.depth_grad.at(x, y) = glm::vec2(slope, 0.0f);
    }
  return s;
}

}  // namespace

TEST_CASE("spatial filter: a constant image stays constant, flat or tilted, RGB or scalar (the weights normalise)") {
  const SvgfParams edges;  // 31x31, std 5
  for (const SurfacePlanes& s : {flat_surface(40, 33), tilted_surface(40, 33, 0.05f)}) {
    const RgbPlane rgb = trmv_spatial_pass(RgbPlane(40, 33, glm::vec3(0.25f, 0.5f, 2.0f)), s, 15, 5.0f, edges);
    const FloatPlane v = trmv_spatial_pass(FloatPlane(40, 33, 0.75f), s, 15, 5.0f, edges);
    for (size_t i = 0; i < rgb.data.size(); ++i) {
      CHECK(rgb.data[i].x == Approx(0.25f).epsilon(1e-6));
      CHECK(rgb.data[i].y == Approx(0.5f).epsilon(1e-6));
      CHECK(rgb.data[i].z == Approx(2.0f).epsilon(1e-6));
      CHECK(v.data[i] == Approx(0.75f).epsilon(1e-6));
    }
  }
}

TEST_CASE("spatial filter: on a flat surface a spike spreads as G(dx) G(dy) / S^2, by hand") {
  // radius 1, std 1: G(0) = 1, G(1) = e^{-1/2} = 0.60653, S = 1 + 2 G(1) = 2.21306 (w_z = w_n = 1 on the flat
  // surface). Centre 1 / S^2 = 0.204180, edge neighbours G(1) / S^2 = 0.123841, corners G(1)^2 / S^2 = 0.0751136.
  FloatPlane spike(7, 7, 0.0f);
  spike.at(3, 3) = 1.0f;
  const FloatPlane out = trmv_spatial_pass(spike, flat_surface(7, 7), 1, 1.0f, SvgfParams{});
  CHECK(out.at(3, 3) == Approx(0.204180).epsilon(1e-5));
  CHECK(out.at(4, 3) == Approx(0.123841).epsilon(1e-5));
  CHECK(out.at(3, 2) == Approx(0.123841).epsilon(1e-5));
  CHECK(out.at(2, 4) == Approx(0.0751136).epsilon(1e-5));
  CHECK(out.at(5, 3) == 0.0f);  // outside the 3x3 footprint
  CHECK(out.at(1, 1) == 0.0f);
  CHECK(trmv_spatial_weight(1.0f, 1.0f) == Approx(0.60653066).epsilon(1e-6));
  CHECK(trmv_spatial_weight(0.0f, 5.0f) == 1.0f);  // peak 1
  // The same std per pixel and axis (the penumbra filter's form) is the same filter; std 0 across keeps each row's
  // own value, so the spike spreads only down its column: 1/S at the centre, G(1)/S above and below.
  const FloatPlane ones(7, 7, 1.0f), zeros(7, 7, 0.0f);
  const FloatPlane same = trmv_spatial_pass(spike, flat_surface(7, 7), 1, ones, ones, SvgfParams{});
  for (size_t i = 0; i < out.data.size(); ++i) CHECK(same.data[i] == out.data[i]);
  const FloatPlane column = trmv_spatial_pass(spike, flat_surface(7, 7), 1, zeros, ones, SvgfParams{});
  CHECK(column.at(3, 3) == Approx(1.0 / 2.21306).epsilon(1e-5));
  CHECK(column.at(3, 2) == Approx(0.60653 / 2.21306).epsilon(1e-5));
  CHECK(column.at(4, 3) == 0.0f);
}

TEST_CASE("spatial filter: two faces at right angles do not mix (w_n = 0), and surfaceless taps are skipped") {
  SurfacePlanes s = flat_surface(20, 6);
  FloatPlane v(20, 6, 0.0f);
  for (int y = 0; y < 6; ++y)
    for (int x = 10; x < 20; ++x) {
      s.normal.at(x, y) = glm::vec3(1.0f, 0.0f, 0.0f);  // the right half faces +x: n . n' = 0 across the edge
      v.at(x, y) = 1.0f;
    }
  // A pixel without a surface holding a large value: no tap may read it, and it passes through itself.
  s.mesh.at(4, 3) = kInvalidId;
  v.at(4, 3) = 100.0f;
  const FloatPlane out = trmv_spatial_pass(v, s, 15, 5.0f, SvgfParams{});
  for (int y = 0; y < 6; ++y)
    for (int x = 0; x < 20; ++x) {
      INFO("pixel " << x << ", " << y);
      if (x == 4 && y == 3) CHECK(out.at(x, y) == 100.0f);
      else if (x < 10) CHECK(out.at(x, y) == 0.0f);
      else CHECK(out.at(x, y) == Approx(1.0f).epsilon(1e-6));
    }
}

TEST_CASE("spatial filter: std 0 and radius 0 are the identity exactly, and sizes are checked") {
  const RgbPlane c = noise_rgb(12, 9, 3);
  const SurfacePlanes s = tilted_surface(12, 9, 0.1f);
  const RgbPlane a = trmv_spatial_pass(c, s, 15, 0.0f, SvgfParams{});
  const RgbPlane b = trmv_spatial_pass(c, s, 0, 5.0f, SvgfParams{});
  for (size_t i = 0; i < c.data.size(); ++i) {
    CHECK(a.data[i] == c.data[i]);
    CHECK(b.data[i] == c.data[i]);
  }
  CHECK_THROWS_AS(trmv_spatial_pass(c, flat_surface(11, 9), 15, 5.0f, SvgfParams{}), Error);
}
