// Tests of motion/glossy.cpp: the glossy reflection motion vector [TRMV21 Eq. 5] against the exact geometry of a
// planar mirror, the lobe's footprint at normal incidence in closed form, the sampling's statistics, the
// validity rules, the static limit, and a frame of the glossy scene.
#include "motion/glossy.h"

#include "core/parallel.h"
#include "scene_fixtures.h"
#include "scenes/gltf_loader.h"
#include "scenes/scene.h"
#include "trace/render_frame.h"

#include <catch2/catch.hpp>

#include <glm/gtc/matrix_transform.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numbers>
#include <vector>

using namespace rtdr;
using namespace rtdr::test;

namespace {

constexpr int kWidth = 160, kHeight = 90;

// The fixture camera: 2 m above the floor y = 0, pitched 0.9 rad (52 degrees) down, looking towards -Z.
const glm::vec3 kEye(0.0f, 2.0f, 0.0f);
const glm::quat kPitchDown = glm::angleAxis(-0.9f, glm::vec3(1.0f, 0.0f, 0.0f));

View view_from(glm::vec3 eye = kEye, glm::quat rotation = kPitchDown, glm::vec2 jitter = glm::vec2(0.0f)) {
  const Scene scene = camera_scene(eye, rotation);
  return make_view(scene, scene.pose(0.0), kWidth, kHeight, jitter);
}

// The floor y = 0 in front of the fixture camera, and a point 0.4 m above it whose mirror image (0.3, -0.4, -2)
// the camera sees near the image centre, at incidence cos i = 0.76, d = |v - s^C| = 0.52 m. Instance 0 is the
// floor, 1 the reflected object.
GlossyRay ray_over_floor(float roughness = 0.0f, uint32_t seed = 7) {
  GlossyRay r;
  r.reflector = {0.2f, 0.0f, -1.5f};
  r.reflector_normal = {0.0f, 1.0f, 0.0f};
  r.hit = {0.3f, 0.4f, -2.0f};
  r.roughness = roughness;
  r.seed = seed;
  r.reflector_instance = 0, r.hit_instance = 1;
  return r;
}

std::vector<InstanceMotion> identities(int n) { return std::vector<InstanceMotion>(size_t(n)); }

glm::dvec3 mirror_y(glm::dvec3 p, double plane_y) { return {p.x, 2.0 * plane_y - p.y, p.z}; }

// How far the ray from `view`'s eye through `screen`, reflected in the plane through `point` with normal `n`,
// passes from `target` (metres), in double: the planar mirror's exact geometry, independent of motion/glossy.cpp.
double reflected_ray_miss(const View& view, glm::dvec2 screen, glm::dvec3 point, glm::dvec3 n, glm::dvec3 target) {
  glm::dvec3 origin, dir;
  pixel_ray(view, screen, origin, dir);
  n = glm::normalize(n);
  const double t = glm::dot(point - origin, n) / glm::dot(dir, n);  // where the eye's ray meets the mirror
  const glm::dvec3 p = origin + t * dir;
  const glm::dvec3 reflected = glm::normalize(dir - 2.0 * glm::dot(dir, n) * n);
  const glm::dvec3 to_target = target - p;
  if (glm::dot(to_target, reflected) <= 0.0) return 1e30;  // the target is not ahead of the reflected ray
  return glm::length(glm::cross(to_target, reflected));
}
double reflected_ray_miss(const View& view, glm::dvec2 screen, double plane_y, glm::dvec3 target) {
  return reflected_ray_miss(view, screen, {0.0, plane_y, 0.0}, {0.0, 1.0, 0.0}, target);
}

double sqrt_trace(const glm::mat2& m) { return std::sqrt(double(m[0][0] + m[1][1])); }

struct ThreadCountGuard {  // restores the default thread count when a test ends, even when it fails
  ~ThreadCountGuard() { set_thread_count(0); }
};

}  // namespace

TEST_CASE("mirror limit: the previous eye's ray through x_i + mu, reflected in the previous floor, hits h's previous position") {
  const View view = view_from();
  const View prev_view = view_from({0.3f, 2.2f, 0.5f}, glm::angleAxis(0.05f, glm::vec3(0.0f, 1.0f, 0.0f)) * kPitchDown);
  std::vector<InstanceMotion> to_previous = identities(2);
  const glm::vec3 d(0.3f, 0.2f, -0.1f);  // the object moved by d: T^{-1} h = h - d
  to_previous[1] = instance_motion(glm::translate(glm::mat4(1.0f), -d));
  const glm::vec3 e(0.1f, -0.05f, 0.2f);  // the floor moved by -e: it was at y = -0.05
  to_previous[0] = instance_motion(glm::translate(glm::mat4(1.0f), e));
  const GlossyRay r = ray_over_floor(0.0f);
  const GlossyMotion m = glossy_motion_pixel(r, to_previous, view, prev_view);
  REQUIRE(m.valid);
  // x_i = P_i(v_i), v_i the mirror image of h in y = 0 (motion/glossy.h), so x^R_{i-1}'s centre is x_i + mu.
  const glm::dvec3 x_i = pinhole_project(view, mirror_y(glm::dvec3(r.hit), 0.0));
  const glm::dvec2 x_prev = glm::dvec2(x_i) + glm::dvec2(m.mu);
  const double miss = reflected_ray_miss(prev_view, x_prev, double(e.y), glm::dvec3(r.hit - d));
  const double sigma_px = sqrt_trace(m.Sigma);
  std::printf("mirror limit: mu (%.4f, %.4f) px, reflected ray misses h_{i-1} by %.3g m, sqrt(trace Sigma) at "
              "roughness 0 %.4f px, |m^R - mu| %.4f px\n", m.mu.x, m.mu.y, miss, sigma_px,
              double(glm::length(m.motion - m.mu)));
  CHECK(miss < 1e-3);
  CHECK(glm::length(m.mu) > 5.0f);  // the reflection moved by many pixels
  // The true mirror is h's previous image: the current one lands elsewhere (the test distinguishes them).
  CHECK(reflected_ray_miss(prev_view, glm::dvec2(x_i), double(e.y), glm::dvec3(r.hit - d)) > 0.05);
  // At roughness 0 the lobe is GGX's narrowest (alpha = kMinGgxAlpha), not a delta: the sample stays within a
  // few of its standard deviations of mu, and here those are a small fraction of a pixel.
  CHECK(sigma_px < 0.1);
  CHECK(glm::length(m.motion - m.mu) <= 5.0 * sigma_px);

  // The mirror tilted since the previous frame (turned 0.1 rad about the X axis through (0, 0, -2)): the previous
  // plane is T^{-1} of the current one, its normal carried by normal_to_previous.
  const glm::mat4 tilt = glm::translate(glm::mat4(1.0f), glm::vec3(0.0f, 0.0f, -2.0f)) *
                         glm::rotate(glm::mat4(1.0f), 0.1f, glm::vec3(1.0f, 0.0f, 0.0f)) *
                         glm::translate(glm::mat4(1.0f), glm::vec3(0.0f, 0.0f, 2.0f));
  to_previous[0] = instance_motion(tilt);
  const GlossyMotion tilted = glossy_motion_pixel(r, to_previous, view, prev_view);
  REQUIRE(tilted.valid);
  const glm::dvec3 prev_point(tilt * glm::vec4(r.reflector, 1.0f));
  const glm::dvec3 prev_normal = glm::dvec3(tilt * glm::vec4(r.reflector_normal, 0.0f));  // a rotation: as a vector
  const double tilted_miss = reflected_ray_miss(prev_view, glm::dvec2(x_i) + glm::dvec2(tilted.mu), prev_point,
                                                prev_normal, glm::dvec3(r.hit - d));
  std::printf("tilted mirror: mu (%.4f, %.4f) px, reflected ray misses h_{i-1} by %.3g m\n", tilted.mu.x, tilted.mu.y,
              tilted_miss);
  CHECK(tilted_miss < 1e-3);
  CHECK(glm::length(tilted.mu - m.mu) > 1.0f);  // the tilt moved the reflection (by 2.8 px)
}

TEST_CASE("Sigma shrinks with the lobe to GGX's narrowest at roughness 0, in proportion to tan(sigma_theta)") {
  const View view = view_from();
  const std::vector<InstanceMotion> still = identities(2);
  const auto size_over_tan = [&](float roughness) {  // sqrt(trace Sigma) / tan(sigma_theta): the geometry alone
    const GlossyMotion m = glossy_motion_pixel(ray_over_floor(roughness), still, view, view);
    REQUIRE(m.valid);
    return sqrt_trace(m.Sigma) / std::tan(double(glossy_lobe_angle(ggx_alpha(roughness))));
  };
  const double s0 = sqrt_trace(glossy_motion_pixel(ray_over_floor(0.0f), still, view, view).Sigma);
  const double s_tiny = sqrt_trace(glossy_motion_pixel(ray_over_floor(1e-3f), still, view, view).Sigma);
  const double s_rough = sqrt_trace(glossy_motion_pixel(ray_over_floor(0.4f), still, view, view).Sigma);
  std::printf("sqrt(trace Sigma): roughness 0 %.5f px, 1e-3 %.5f px, 0.4 %.3f px; per tan(sigma_theta): %.3f, "
              "%.3f (roughness 0, 0.05)\n", s0, s_tiny, s_rough, size_over_tan(0.0f), size_over_tan(0.05f));
  CHECK(s_tiny == s0);              // both at alpha = kMinGgxAlpha: roughness^2 = 1e-6 is below it
  CHECK(s0 < 0.01 * s_rough);       // alpha 1e-3 against 0.16: tan(sigma_theta) 2.9e-3 against 0.50
  CHECK(s0 > 0.0);
  // Sigma's size is the footprint's, d tan(sigma_theta), projected: linear in tan(sigma_theta) for small lobes.
  CHECK(std::abs(size_over_tan(0.0f) / size_over_tan(0.05f) - 1.0) < 1e-3);
}

TEST_CASE("normal incidence: the footprint is a circle of radius d tan(sigma_theta), f d tan(sigma_theta) / D pixels") {
  // A camera 3 m above the mirror y = 0, looking straight down; h 1 m above the mirror under the camera. Then
  // s^C is below the eye, d = |v - s^C| = 1, D = 3 the depth of s^C, and a circle of radius rho around s^C,
  // parallel to the image plane, projects to a circle of f rho / D pixels, f = H / (2 tan(yfov / 2)).
  const glm::quat straight_down = glm::angleAxis(-0.5f * std::numbers::pi_v<float>, glm::vec3(1, 0, 0));
  const View view = view_from({0.0f, 3.0f, 0.0f}, straight_down);
  GlossyRay r;
  r.reflector = {0.4f, 0.0f, -0.3f};
  r.reflector_normal = {0.0f, 1.0f, 0.0f};
  r.hit = {0.0f, 1.0f, 0.0f};
  r.roughness = 0.3f;
  r.reflector_instance = 0, r.hit_instance = 1;
  const GlossyMotion m = glossy_motion_pixel(r, identities(2), view, view);
  REQUIRE(m.valid);
  const double f = 0.5 * kHeight / double(view.tan_half_fov_y);
  const double expected = f * 1.0 * std::tan(double(glossy_lobe_angle(ggx_alpha(r.roughness)))) / 3.0;
  const double a1 = glm::length(m.axes[0]), a2 = glm::length(m.axes[1]);
  std::printf("normal incidence: |a1| %.5f px, |a2| %.5f px, closed form %.5f px, a1.a2 %.2g\n", a1, a2, expected,
              double(glm::dot(m.axes[0], m.axes[1])));
  CHECK(std::abs(a1 - expected) < 1e-4 * expected);
  CHECK(std::abs(a2 - expected) < 1e-4 * expected);
  CHECK(std::abs(glm::dot(m.axes[0], m.axes[1])) < 1e-4 * expected * expected);
  CHECK(glm::length(m.mu) < 1e-4f);  // static: the virtual image stays put
}

TEST_CASE("sampling: 10^4 seeds give mean mu and covariance Sigma, and Sigma grows with roughness") {
  const View view = view_from();
  const std::vector<InstanceMotion> still = identities(2);
  const int n = 10000;
  const GlossyMotion ref = glossy_motion_pixel(ray_over_floor(0.2f, 0), still, view, view);
  REQUIRE(ref.valid);
  glm::dvec2 sum(0.0);
  glm::dmat2 sum_outer(0.0);
  for (int k = 0; k < n; ++k) {
    const GlossyMotion m = glossy_motion_pixel(ray_over_floor(0.2f, uint32_t(k)), still, view, view);
    REQUIRE(m.mu == ref.mu);  // the seed moves only the sample
    const glm::dvec2 x = glm::dvec2(m.motion - m.mu);
    sum += x;
    sum_outer += glm::outerProduct(x, x);
  }
  const glm::dvec2 mean = sum / double(n);
  const glm::dmat2 cov = sum_outer / double(n) - glm::outerProduct(mean, mean);
  const glm::dmat2 Sigma(ref.Sigma);
  const double norm =  // Frobenius
      std::sqrt(Sigma[0][0] * Sigma[0][0] + 2.0 * Sigma[1][0] * Sigma[1][0] + Sigma[1][1] * Sigma[1][1]);
  double worst_entry = 0.0;
  for (int c = 0; c < 2; ++c)
    for (int r = 0; r < 2; ++r) worst_entry = std::max(worst_entry, std::abs(cov[c][r] - Sigma[c][r]) / norm);
  std::printf("sampling: Sigma [[%.4f, %.4f], [%.4f, %.4f]] px^2, sample covariance [[%.4f, %.4f], [%.4f, %.4f]], "
              "worst entry %.2f %% of |Sigma|; mean - mu (%.4f, %.4f) px, standard errors (%.4f, %.4f)\n",
              Sigma[0][0], Sigma[1][0], Sigma[0][1], Sigma[1][1], cov[0][0], cov[1][0], cov[0][1], cov[1][1],
              100.0 * worst_entry, mean.x, mean.y, std::sqrt(Sigma[0][0] / n), std::sqrt(Sigma[1][1] / n));
  CHECK(std::abs(mean.x) < 3.0 * std::sqrt(Sigma[0][0] / n));
  CHECK(std::abs(mean.y) < 3.0 * std::sqrt(Sigma[1][1] / n));
  CHECK(worst_entry < 0.05);

  double prev_det = 0.0, prev_trace = 0.0;
  for (float roughness : {0.05f, 0.1f, 0.2f, 0.4f}) {
    const glm::mat2 S = glossy_motion_pixel(ray_over_floor(roughness), still, view, view).Sigma;
    const double det = glm::determinant(glm::dmat2(S)), trace = double(S[0][0] + S[1][1]);
    std::printf("roughness %.2f: det Sigma %.4g px^4, trace Sigma %.4g px^2\n", roughness, det, trace);
    CHECK(det > prev_det);
    CHECK(trace > prev_trace);
    prev_det = det, prev_trace = trace;
  }
}

TEST_CASE("glossy motion is invalid without a secondary hit, with h behind the mirror, or an eye behind it, in either frame") {
  const View view = view_from();
  const std::vector<InstanceMotion> still = identities(2);
  CHECK(glossy_motion_pixel(ray_over_floor(), still, view, view).valid);

  GlossyRay escaped = ray_over_floor();
  escaped.hit_instance = kInvalidId;  // the BSDF ray left the scene
  CHECK_FALSE(glossy_motion_pixel(escaped, still, view, view).valid);

  GlossyRay below = ray_over_floor();
  below.hit = {0.3f, -0.4f, -2.0f};  // h on the far side of the mirror from the eye: no reflection of it
  CHECK_FALSE(glossy_motion_pixel(below, still, view, view).valid);

  // The previous eye under the floor (y = -0.5): it sees the floor's back, and no reflection of h.
  const View under = view_from({0.0f, -0.5f, 0.0f}, glm::quat(1, 0, 0, 0));
  const GlossyMotion m = glossy_motion_pixel(ray_over_floor(), still, view, under);
  CHECK_FALSE(m.valid);
  CHECK(m.motion == glm::vec2(0.0f));
  CHECK_FALSE(glossy_motion_pixel(ray_over_floor(), still, under, view).valid);  // and so in the current frame

  // The previous camera turned around (looking level towards +Z): v is behind it.
  const View turned = view_from(kEye, glm::angleAxis(std::numbers::pi_v<float>, glm::vec3(0, 1, 0)));
  CHECK_FALSE(glossy_motion_pixel(ray_over_floor(), still, view, turned).valid);
}

TEST_CASE("a lobe that reaches past the plane's horizon has no footprint: valid while sigma_theta < pi/2 - i") {
  const View view = view_from();
  const std::vector<InstanceMotion> still = identities(2);
  // The incidence angle at the specular point, from the mirror geometry: the eye's line to h's virtual image.
  const GlossyRay r = ray_over_floor();
  const glm::vec3 v(r.hit.x, 2.0f * r.reflector.y - r.hit.y, r.hit.z);
  const float cos_i = std::abs(glm::normalize(v - kEye).y);
  const float limit = std::asin(cos_i);  // pi/2 - i
  // The largest alpha with 2 atan(1.458 alpha) < pi/2 - i, and the roughness that gives it (alpha = roughness^2).
  const float roughness_limit = std::sqrt(std::tan(0.5f * limit) / kGgxLobeTanPerAlpha);
  INFO("incidence " << std::acos(cos_i) * 180.0f / std::numbers::pi_v<float> << " degrees, roughness limit "
       << roughness_limit);
  CHECK(glossy_motion_pixel(ray_over_floor(0.98f * roughness_limit), still, view, view).valid);
  CHECK_FALSE(glossy_motion_pixel(ray_over_floor(1.02f * roughness_limit), still, view, view).valid);
  CHECK_FALSE(glossy_motion_pixel(ray_over_floor(1.0f), still, view, view).valid);  // sigma_theta = 111 degrees
}

TEST_CASE("static views with TAA-style jitter: mu equals the jitter difference, the surface motion's, to 1e-3 px") {
  // The projection adds its jitter in screen space (raster/view.h), so for any still point P_{i-1} - P_i is the
  // jitter difference: the surface motion of a still scene. Ours is the virtual image's, so it must be too.
  const glm::vec2 jitter_now(0.25f, -0.375f), jitter_before(-0.125f, 0.3125f);
  const View view = view_from(kEye, kPitchDown, jitter_now);
  const View prev_view = view_from(kEye, kPitchDown, jitter_before);
  double worst = 0.0;
  for (float hx : {-0.5f, 0.0f, 0.5f})
    for (float hy : {0.2f, 0.5f, 1.0f}) {
      GlossyRay r = ray_over_floor();
      r.hit = {hx, hy, -2.0f};
      const GlossyMotion m = glossy_motion_pixel(r, identities(2), view, prev_view);
      REQUIRE(m.valid);
      worst = std::max(worst, double(glm::length(m.mu - (jitter_before - jitter_now))));
    }
  std::printf("jittered still views: worst |mu - jitter difference| %.3g px\n", worst);
  CHECK(worst < 1e-3);
}

TEST_CASE("cornell, nothing moves: mu equals the motion layer to 1e-3 px, and at roughness 0 the sample stays within the narrowest lobe") {
  // cornell (scenes/README.md): nothing moves, and rtdr renders without jitter, so `motion` is 0 up to rounding,
  // and so is mu (T^{-1} = M(t_{i-1}) M(t_i)^{-1} is the identity up to rounding). cornell's roughness 1 gives no
  // vector at all (the lobe reaches past the plane's horizon), so every pixel is drawn as a mirror, roughness 0.
  // (On the `static` scene the motion layer's own rounding reaches 6e-3 px.)
  const Scene scene = load_scene("cornell");
  const FrameGeometry g = rasterize_frame(scene, 3, 64, 64);
  const Frame frame = render_frame(scene, 3, 64, 64, RenderSettings{});
  const std::vector<glm::vec2> surface = frame.get_vec2("motion");
  const GlossyRayLayers rays(frame);
  const std::vector<InstanceMotion> to_previous = instance_to_previous(g.pose, g.prev_pose);
  const std::vector<GlossyMotion> all = glossy_motion(g, frame);
  int valid = 0;
  double worst_mu = 0.0, worst_sample = 0.0, worst_in_sigmas = 0.0, largest_sigma = 0.0, worst_footprint = 0.0;
  for (size_t i = 0; i < surface.size(); ++i) {
    GlossyRay r = rays.at(i);
    // cornell is rough (roughness 1): its lobes reach past every plane's horizon, so no pixel has a vector.
    CHECK_FALSE(all[i].valid);
    r.roughness = 0.0f;
    const GlossyMotion mirror = glossy_motion_pixel(r, to_previous, g.view, g.prev_view);
    if (!mirror.valid) continue;
    ++valid;
    worst_mu = std::max(worst_mu, double(glm::length(mirror.mu - surface[i])));
    // Nothing moves: the current footprint (the glossy filter's kernel) is Eq. 5's Sigma, up to rounding: T^{-1} is
    // the identity to a few 1e-7 of the positions, which the narrowest lobes' short semi-axes amplify (measured
    // 2.2e-3 of the trace at most).
    REQUIRE(mirror.has_footprint);
    const double scale = std::max(1e-6, double(std::abs(mirror.Sigma[0][0]) + std::abs(mirror.Sigma[1][1])));
    for (int a = 0; a < 2; ++a)
      for (int b = 0; b < 2; ++b)
        worst_footprint = std::max(worst_footprint, std::abs(double(mirror.footprint[a][b] - mirror.Sigma[a][b])) / scale);
    const double sample_error = glm::length(mirror.motion - surface[i]), sigma = sqrt_trace(mirror.Sigma);
    worst_sample = std::max(worst_sample, sample_error);
    worst_in_sigmas = std::max(worst_in_sigmas, (sample_error - 1e-3) / sigma);  // beyond mu's tolerance
    largest_sigma = std::max(largest_sigma, sigma);
  }
  std::printf("cornell 64x64: %d valid pixels, worst |mu - motion| %.3g px; roughness 0: worst |m^R - motion| "
              "%.4f px (%.2f sqrt(trace Sigma)), largest sqrt(trace Sigma) %.4f px; current footprint within %.3g of "
              "Sigma\n",
              valid, worst_mu, worst_sample, worst_in_sigmas, largest_sigma, worst_footprint);
  REQUIRE(valid > 1000);
  CHECK(worst_mu < 1e-3);
  CHECK(worst_footprint < 1e-2);
  CHECK(worst_in_sigmas < 5.0);
}

TEST_CASE("glossy scene: the floor's reflections have vectors, the same for 1 and 2 threads, spread as Sigma says") {
  ThreadCountGuard guard;
  const Scene scene = load_scene("glossy");
  const int w = 96, h = 54, index = 20;  // the camera orbits at 3.8 m/s (scenes/README.md)
  const FrameGeometry g = rasterize_frame(scene, index, w, h);
  Frame frame = render_frame(scene, index, w, h, RenderSettings{});
  set_thread_count(1);
  const std::vector<GlossyMotion> one = glossy_motion(g, frame);
  set_thread_count(2);
  const std::vector<GlossyMotion> two = glossy_motion(g, frame);
  write_glossy_motion_layers(g, frame);
  const std::vector<glm::vec2> written = frame.get_vec2("motion.glossy");
  const UIntPlane& written_valid = frame.uint_channel("motion.glossy.valid");
  const std::vector<glm::vec2> written_mean = frame.get_vec2("motion.glossy_mean");
  const UIntPlane& written_has_footprint = frame.uint_channel("glossy.footprint.valid");
  const FloatPlane& footprint_xx = frame.float_channel("glossy.footprint.XX");
  const FloatPlane& footprint_xy = frame.float_channel("glossy.footprint.XY");
  const FloatPlane& footprint_yy = frame.float_channel("glossy.footprint.YY");

  const std::vector<glm::vec2> surface = frame.get_vec2("motion");
  const std::vector<glm::vec3> hit = frame.get_vec3("path.secondary");
  const FloatPlane& metallic = frame.float_channel("material.metallic");
  const UIntPlane& hit_id = frame.uint_channel("path.secondary.instance");
  int floor = 0, floor_invalid = 0, identical = 0;
  double sum_to_surface = 0.0, sum_mu_to_surface = 0.0, sum_spread = 0.0, sum_spread_in_sigmas = 0.0;
  double sum_sigma = 0.0, worst_miss = 0.0;
  for (size_t i = 0; i < one.size(); ++i) {
    identical += one[i].valid == two[i].valid && one[i].motion == two[i].motion && one[i].Sigma == two[i].Sigma;
    CHECK(written_valid.data[i] == (one[i].valid ? 1u : 0u));
    CHECK(written[i] == one[i].motion);
    CHECK(written_mean[i] == (one[i].valid ? one[i].mu : glm::vec2(0.0f)));
    CHECK(written_has_footprint.data[i] == (one[i].has_footprint ? 1u : 0u));
    CHECK(footprint_xx.data[i] == one[i].footprint[0][0]);
    CHECK(footprint_xy.data[i] == one[i].footprint[1][0]);
    CHECK(footprint_yy.data[i] == one[i].footprint[1][1]);
    if (metallic.data[i] != 1.0f) continue;  // the floor: metallic 1, roughness 0.15
    if (!one[i].valid) {
      floor_invalid += hit_id.data[i] != kInvalidId;  // a reflection, but no vector (motion/glossy.h says when)
      continue;
    }
    const GlossyMotion& m = one[i];
    ++floor;
    const double sigma = sqrt_trace(m.Sigma), spread = glm::length(m.motion - m.mu);
    sum_to_surface += glm::length(m.motion - surface[i]);
    sum_mu_to_surface += glm::length(m.mu - surface[i]);
    sum_spread += spread, sum_sigma += sigma, sum_spread_in_sigmas += spread / sigma;
    // The scene stands still and the floor is y = 0: the previous eye's ray through x_i + mu, reflected in the
    // floor, must hit h (Eq. 5's mirror part, on real data). x_i = P_i(v_i).
    const glm::dvec3 x_i = pinhole_project(g.view, mirror_y(glm::dvec3(hit[i]), 0.0));
    worst_miss = std::max(worst_miss, reflected_ray_miss(g.prev_view, glm::dvec2(x_i) + glm::dvec2(m.mu), 0.0,
                                                         glm::dvec3(hit[i])));
  }
  const double mean_spread_in_sigmas = sum_spread_in_sigmas / std::max(floor, 1);
  std::printf("glossy %dx%d frame %d: %d valid floor pixels, %d with a secondary hit but invalid; "
              "mean |m^R - motion| %.3f px (|mu - motion| %.3f px); mean |m^R - mu| %.3f px, "
              "mean sqrt(trace Sigma) %.3f px, mean |m^R - mu| / sqrt(trace Sigma) %.3f; mirror part misses h by "
              "at most %.3g m; %d of %zu pixels identical for 1 and 2 threads\n",
              w, h, index, floor, floor_invalid, sum_to_surface / std::max(floor, 1),
              sum_mu_to_surface / std::max(floor, 1), sum_spread / std::max(floor, 1),
              sum_sigma / std::max(floor, 1), mean_spread_in_sigmas, worst_miss, identical, one.size());
  CHECK(identical == int(one.size()));
  REQUIRE(floor > 500);
  CHECK(worst_miss < 1e-3);
  CHECK(sum_spread <= 3.0 * sum_sigma);
  // For x = a1 n1 + a2 n2, E|x| / sqrt(trace Sigma) lies between sqrt(2 / pi) = 0.798 (one axis) and
  // sqrt(pi) / 2 = 0.886 (a circle); the mean over the floor's pixels must land near that band.
  CHECK(mean_spread_in_sigmas > 0.75);
  CHECK(mean_spread_in_sigmas < 0.93);
  CHECK(sum_to_surface / floor > 0.1);  // the reflection does not move with the floor under an orbiting camera
}
