// Tests of the gradient image on the stratum grid [ASVGF18 Sec. 3.4, Eq. 3, Eq. 13]: delta and Delta of a stratum's
// gradient sample, the stratum's mean luminance and variance, the representative pixel of a full and of a partial
// stratum, and the refusal of two samples in one stratum. Every expected value is computed by hand.
#include "filters/asvgf/gradient_image.h"

#include "core/error.h"

#include <catch2/catch.hpp>

using namespace rtdr;

namespace {

// A 5 x 4 frame (strata of 3: 2 x 2 strata, the right column and bottom row partial) whose every pixel sees a
// surface, with grey colour l(x, y) = x + 10 y (a grey colour's luminance is its value) and no gradient sample.
struct Input {
  RgbPlane noisy{5, 4};
  UIntPlane source{5, 4, kInvalidId};
  FloatPlane prev{5, 4};
  SurfacePlanes surface;
  Input() {
    surface.depth = FloatPlane(5, 4, 2.0f);
    surface.depth_grad = Vec2Plane(5, 4);
    surface.normal = RgbPlane(5, 4, glm::vec3(0.0f, 1.0f, 0.0f));
    surface.mesh = UIntPlane(5, 4, 7u);
    for (int y = 0; y < 4; ++y)
      for (int x = 0; x < 5; ++x) {
        noisy.at(x, y) = glm::vec3(float(x + 10 * y));
        surface.depth.at(x, y) = 1.0f + float(x + 10 * y);  // so that the representative's depth names it
      }
  }
};

}  // namespace

TEST_CASE("gradient image: delta and Delta of the sample, mean and variance of the stratum, its centre's geometry") {
  Input in;
  // A gradient sample at (2, 1) in stratum (0, 0): now l = 12, before 20 [ASVGF18 Eq. 3, 13].
  in.source.at(2, 1) = 3u;
  in.prev.at(2, 1) = 20.0f;
  const GradientImage g = gradient_image(in.noisy, in.source, in.prev, in.surface, 3);
  REQUIRE(g.values.delta.width == 2);
  REQUIRE(g.values.delta.height == 2);
  CHECK(g.values.delta.at(0, 0) == -8.0f);  // 12 - 20
  CHECK(g.values.norm.at(0, 0) == 20.0f);   // max(12, 20)
  CHECK(g.values.delta.at(1, 0) == 0.0f);   // no sample: 0, 0
  CHECK(g.values.norm.at(1, 0) == 0.0f);
  // Stratum (0, 0): l = x + 10 y over x, y in 0..2: mean 1 + 10 = 11; variance 2/3 (x) + 200/3 (10 y) = 202/3.
  CHECK(g.values.luminance.at(0, 0) == Approx(11.0f));
  CHECK(g.values.variance.at(0, 0) == Approx(202.0f / 3.0f).epsilon(1e-5));
  // Its representative is the centre (1, 1): depth 1 + 11.
  CHECK(g.surface.depth.at(0, 0) == 12.0f);
  CHECK(g.surface.mesh.at(0, 0) == 7u);
  // Partial stratum (1, 1): pixels x in 3..4, y = 3: l = 33, 34; mean 33.5, variance 0.25. Its centre (4, 4) is
  // clipped to (4, 3): depth 1 + 34.
  CHECK(g.values.luminance.at(1, 1) == Approx(33.5f));
  CHECK(g.values.variance.at(1, 1) == Approx(0.25f).epsilon(1e-4));
  CHECK(g.surface.depth.at(1, 1) == 35.0f);
  // Replicated to pixels, stratum (x / 3, y / 3).
  const FloatPlane delta = replicate_strata(g.values.delta, 3, 5, 4);
  CHECK(delta.at(2, 2) == -8.0f);
  CHECK(delta.at(3, 2) == 0.0f);
}

TEST_CASE("gradient image: a stratum whose centre sees nothing takes its first covered pixel, or none") {
  Input in;
  in.surface.mesh.at(1, 1) = kInvalidId;  // stratum (0, 0)'s centre
  in.surface.mesh.at(0, 0) = kInvalidId;
  for (int y = 0; y < 3; ++y)  // stratum (1, 0): no surface at all
    for (int x = 3; x < 5; ++x) in.surface.mesh.at(x, y) = kInvalidId;
  const GradientImage g = gradient_image(in.noisy, in.source, in.prev, in.surface, 3);
  CHECK(g.surface.depth.at(0, 0) == 2.0f);  // (1, 0), the first covered pixel in raster order
  // The mean skips the two pixels without a surface: (sum 0..22 over the stratum - l(0,0) - l(1,1)) / 7.
  CHECK(g.values.luminance.at(0, 0) == Approx((99.0f - 0.0f - 11.0f) / 7.0f));
  CHECK(g.surface.mesh.at(1, 0) == kInvalidId);
  CHECK(g.values.luminance.at(1, 0) == 0.0f);
}

TEST_CASE("gradient image: two samples in one stratum, or planes of another size, are refused") {
  Input in;
  in.source.at(0, 0) = 1u;
  in.source.at(2, 2) = 2u;
  CHECK_THROWS_WITH(gradient_image(in.noisy, in.source, in.prev, in.surface, 3),
                    Catch::Contains("holds two gradient samples"));
  Input other;
  other.prev = FloatPlane(4, 4);
  CHECK_THROWS_AS(gradient_image(other.noisy, other.source, other.prev, other.surface, 3), Error);
  CHECK_THROWS_AS(gradient_image(other.noisy, other.source, Input().prev, other.surface, 0), Error);
}

TEST_CASE("gradient image variants: abs(delta), or the sample's ratio beside a sample-present weight, and the probe names them") {
  Input in;
  // The sample of the test above: now l = 12, before 20: delta = -8, Delta = 20, ratio 8/20 = 0.4.
  in.source.at(2, 1) = 3u;
  in.prev.at(2, 1) = 20.0f;
  const auto stratum = [&](const GradientForm& form, Probe* probe = nullptr) {
    return gradient_stratum(in.noisy, in.source, in.prev, in.surface, 3, 0, 0, form, probe);
  };
  const GradientStratum paper = stratum({});
  CHECK(paper.delta == -8.0f);
  CHECK(paper.norm == 20.0f);
  const GradientStratum absolute = stratum({.absolute = true});
  CHECK(absolute.delta == 8.0f);  // opposite changes can no longer cancel
  CHECK(absolute.norm == 20.0f);
  // Normalised before the reconstruction: r = min(1, k (8/20)^p), and the sample-present weight 1 as Delta.
  CHECK(stratum({.before = true}).delta == Approx(0.4f).epsilon(1e-6));
  CHECK(stratum({.before = true}).norm == 1.0f);
  CHECK(stratum({.before = true, .exponent = 2}).delta == Approx(0.16f).epsilon(1e-6));            // Q2RTX
  CHECK(stratum({.before = true, .scale = 0.1f}).delta == Approx(0.04f).epsilon(1e-6));            // RTGL1
  CHECK(stratum({.before = true, .absolute = true}).delta == Approx(0.4f).epsilon(1e-6));          // r is unsigned
  CHECK(gradient_sample_values(3.0f, 0.0f, {.before = true, .scale = 0.5f}).x == 0.5f);           // k r
  CHECK(gradient_sample_values(9.0f, 0.0f, {.before = true}).x == 1.0f);                          // min(1, .)
  CHECK(gradient_sample_values(0.0f, 0.0f, {.before = true}) == glm::vec2(0.0f, 1.0f));  // black both: r 0, present
  // Mean and variance do not depend on the form.
  CHECK(stratum({.before = true}).luminance == paper.luminance);
  CHECK(stratum({.before = true}).variance == paper.variance);
  // Strata without a sample hold (0, 0) in every form: they stay in the sums, so the density cancels.
  const GradientImage g = gradient_image(in.noisy, in.source, in.prev, in.surface, 3, {.before = true});
  CHECK(g.values.delta.at(1, 0) == 0.0f);
  CHECK(g.values.norm.at(1, 0) == 0.0f);
  CHECK(g.values.delta.at(0, 0) == Approx(0.4f).epsilon(1e-6));
  // The probe records both luminances, the raw delta and Delta, and what the form made of them.
  Probe probe;
  stratum({.before = true, .exponent = 2}, &probe);
  CHECK(probe.find("f_i - f_{i-1}").value.front() == -8.0f);
  CHECK(probe.find("max(f_i, f_{i-1})").value.front() == 20.0f);
  CHECK(probe.find("r (the sample's ratio)").value.front() == Approx(0.16f).epsilon(1e-6));
  CHECK(probe.find("sample-present weight").value.front() == 1.0f);
  Probe signed_probe;
  stratum({}, &signed_probe);
  CHECK(signed_probe.find("delta").value.front() == -8.0f);
  CHECK(signed_probe.find("Delta").value.front() == 20.0f);
}
