// Tests of gpu/motion_glossy_gpu.cpp: the Vulkan port (motion/glossy.comp) against the golden glossy_motion()
// (motion/glossy.cpp) on rendered frames (the glossy scene's metallic floor under the orbiting camera; cornell, where
// nothing moves) and on the same frames with every roughness and seed redrawn, with the validation layer on.
// Skipped, with a message, where no Vulkan device exists.
//
// What is exact. Both sides do the same fp32 operations in the same order: the shader marks every result `precise`
// (no fma contraction, no reordering) and writes glm's dot, normalize (v * (1 / sqrt(v . v))), cross and matrix
// products out in glm's order; the C++ is built without fma. The Gaussian draw's two uniform numbers are integer
// hashing (core/sampler.glsl), bit for bit. Pixels without a secondary hit are exact (0, valid 0). What differs:
// the square roots (Vulkan: from inversesqrt, under 4.5 ulp; C++: 0.5) and divisions (2.5 ulp; 0.5), and the
// device's asin, atan (4096 ulp), tan (sin / cos), log (3 ulp, or 2^-21 absolute in [0.5, 2]), sin and cos (2^-11
// absolute in [-pi, pi]; the shader moves Box-Muller's angle there, exactly, with a float 2 pi 1.75e-7 above 2 pi);
// glibc's are within 1 ulp. e = 2^-23; an ulp of a float a is at most e |a|.
//
// Decisions. A decision made from device results may flip only where its terms sit within their error of the
// threshold. The test recomputes each decision's terms in double (terms(), below) and counts and skips the pixels
// where one is within that margin: the eye's or h's height over the plane (either frame) within 1e-4 of |eye - s|
// or |h - s| (their device error is under 20 e of that); |n . (v - eye)| within 1e-4 |v - eye| of the parallel
// threshold; a depth (x_i, mu, the footprint's four ends) within 1e-4 relative of znear; |t1| within 64 e of the
// normal-incidence threshold; and the horizon test sigma_theta < asin(cos i) within
// 4097 e (sigma_theta + pi/2) + min(Delta c / sqrt(1 - (c + Delta c)^2), (pi / sqrt 2) sqrt(Delta c)) rad, with
// Delta c = 40 e c + e, the cosine's device error (asin is Hoelder at 1). Every other pixel's valid flag is exact.
//
// Values, first order, per axis, with W the image's size along it (bound(), below). A world point p known to dp
// projects within S(p, dp) = (W / 2) ((|M_xy| dp + |ndc| |M_w| dp) / w + 3 e |ndc|) + 2 e |s| + e W / 2 (the clip
// rows' norms, the division's 3 ulp, the two roundings after it). A virtual image v is known to
// dv = 40 e |h_height| + 6 e |h - s| + e |v| (normalize's 9 e scales both heights; v = h - 2 h_height n). So
//   mu     B_mu = S(v_i, dv_i) + S(v_{i-1}, dv_{i-1}) + e |mu|
//   a_k    B_a = (S(s^C + r t_k, D) + S(s^C - r t_k, D)) / 2 + e |a_k|, D = |Delta s^C| + r (Delta r / r + 20 e):
//          Delta r / r sums d's relative error (t's division and heights), tan's (Delta tan = (2^-11 (1 + tan) +
//          Delta sigma sec^2) / (cos - 2^-11) + 3 e tan, Delta sigma = 4097 e sigma), and along the plane of
//          incidence cos i's
//   m^R    B_m = B_mu + sum_k (B_a |n_k| + |a_k| Delta n_k) + 3 e (|mu| + sum_k |a_k n_k|), Delta n_k =
//          Delta rho + rho (2^-11 + e + 1.75e-7), Delta rho = min(Delta q / (2 rho), sqrt(Delta q)) + 5 e rho,
//          q = rho^2 = -2 log(1 - u): Delta q = 2^-20 + 2 e q for u <= 1/2, else 8 e q
//   b_k    the current footprint's columns: B_a with the current mirror image and View (the same steps);
//          its flag (has_footprint) is exact away from the same margins
// each times 2 for the second-order terms and the roundings of the same operations on inputs that already differ,
// which the list does not itemise. The bound is loose where Vulkan is: sin and cos to 2^-11 absolute make tan of a
// narrow lobe (sigma_theta = 2.9 mrad at roughness 0) uncertain by a sixth. A simulated device with every one of
// those functions as far off as Vulkan allows, either way, checks the derivation (no Vulkan needed): on the glossy
// frames here its worst is 0.48 of the bound, with no flag differing away from the margins.
// On a CPU device (lavapipe) the square roots and divisions round correctly, so mu is bit-identical and only the
// transcendental functions differ. Measured worst on lavapipe (llvmpipe, LLVM 15), over every frame and build here:
// mu 0; the flags exact (7 pixels of the redrawn frames within a margin, skipped); on the glossy floor a1/a2
// 5.9e-4 px (2.6e-4 of |a_k|) and m^R 1.0e-3 px; with roughnesses redrawn in [0, 1] a1/a2 0.29 px (1.4e-3 of |a_k|,
// footprints of hundreds of pixels where the lobe nears the plane's horizon: Mesa's atan, amplified by tan near
// pi/2) and m^R 0.43 px; at most 0.4 % of the bound.
#include "gpu/motion_glossy_gpu.h"

#include "core/error.h"
#include "motion/glossy.h"
#include "motion/glossy_shared.h"
#include "scenes/gltf_loader.h"
#include "core/geometry.h"
#include "scenes/scene.h"
#include "trace/render_frame.h"
#include "core/sampler.h"

#include "gpu_fixtures.h"

#include <catch2/catch.hpp>

#include <glm/gtc/constants.hpp>

#include <algorithm>
#include <cmath>
#include <random>
#include <string>
#include <vector>

using namespace rtdr;
using namespace rtdr::gpu_test;

namespace {

const double kE = std::ldexp(1.0, -23);
const double kSinCos = std::ldexp(1.0, -11);  // Vulkan's absolute error of sin and cos in [-pi, pi]
const double kMargin = 1e-4;                  // the relative margins of the banner's decisions

// S(p, dp) of the banner, per axis: how far the device's projection of p, known to dp, may be from the C++'s.
glm::dvec2 screen_bound(const View& view, const glm::dvec3& p, double dp) {
  const glm::dmat4 m(view.world_to_clip);
  const glm::dvec4 clip = m * glm::dvec4(p, 1.0);
  const auto row_norm = [&](int r) { return glm::length(glm::dvec3(m[0][r], m[1][r], m[2][r])); };
  const glm::dvec2 ndc = glm::dvec2(clip) / clip.w;
  const glm::dvec2 size(view.width, view.height);
  const glm::dvec2 screen((ndc.x * 0.5 + 0.5) * size.x, (0.5 - ndc.y * 0.5) * size.y);
  glm::dvec2 b;
  for (int a = 0; a < 2; ++a)
    b[a] = size[a] / 2.0 * ((row_norm(a) * dp + std::abs(ndc[a]) * row_norm(3) * dp) / std::abs(clip.w) +
                            3.0 * kE * std::abs(ndc[a])) +
           2.0 * kE * std::abs(screen[a]) + kE * size[a] / 2.0;
  return b;
}

double depth_of(const View& view, const glm::dvec3& p) {
  return (glm::dmat4(view.world_to_clip) * glm::dvec4(p, 1.0)).w;
}

// The golden pass's terms at one frame, in double, from the same float inputs.
struct MirrorTerms {
  bool ok = false;    // eye and h strictly on one side, not parallel
  bool near = false;  // a decision within its margin (banner)
  double eye_height = 0, h_height = 0, len = 0, t = 0, cos_i = 0, d = 0, dv = 0, dt_rel = 0, dcos_rel = 0;
  glm::dvec3 n{0.0}, v{0.0}, line{0.0}, sc{0.0}, incidence{0.0};
};

MirrorTerms mirror_terms(glm::dvec3 eye, glm::dvec3 h, glm::dvec3 s, glm::dvec3 n) {
  MirrorTerms m;
  m.n = glm::normalize(n);
  m.eye_height = glm::dot(m.n, eye - s), m.h_height = glm::dot(m.n, h - s);
  m.near = std::abs(m.eye_height) <= kMargin * glm::length(eye - s) ||
           std::abs(m.h_height) <= kMargin * glm::length(h - s);
  if (!(m.eye_height * m.h_height > 0.0)) return m;
  if (m.eye_height < 0.0) m.n = -m.n, m.eye_height = -m.eye_height, m.h_height = -m.h_height;
  m.v = h - 2.0 * m.h_height * m.n;
  m.line = m.v - eye;
  m.len = glm::length(m.line);
  const double n_dot_line = glm::dot(m.n, m.line);
  m.near = m.near || std::abs(std::abs(n_dot_line) - double(kGlossyParallelCosine) * m.len) <= kMargin * m.len;
  if (std::abs(n_dot_line) <= double(kGlossyParallelCosine) * m.len) return m;
  m.ok = true;
  m.t = m.eye_height / (m.eye_height + m.h_height);
  m.sc = eye + m.t * m.line;
  m.incidence = m.line / m.len;
  m.cos_i = -n_dot_line / m.len;
  m.d = (1.0 - m.t) * m.len;
  // The device's errors (banner): the heights' (normalize's 9 e and the dot's roundings), v's, t's and cos i's.
  const double d_eye = 9.0 * kE * m.eye_height + 3.0 * kE * glm::length(eye - s);
  const double d_h = 9.0 * kE * m.h_height + 3.0 * kE * glm::length(h - s);
  m.dv = 40.0 * kE * m.h_height + 6.0 * kE * glm::length(h - s) + kE * glm::length(m.v);
  m.dt_rel = 3.0 * kE + d_eye / m.eye_height + (d_eye + d_h) / (m.eye_height + m.h_height);
  m.dcos_rel = (9.0 * kE * std::abs(n_dot_line) + m.dv + 3.0 * kE * m.len) / std::abs(n_dot_line) + 8.0 * kE;
  return m;
}

bool near_znear(double depth, float znear) {
  return std::abs(depth - double(znear)) <= kMargin * std::max(std::abs(depth), double(znear));
}

// Per pixel: whether a decision is within its margin, and the banner's bounds on mu, a1, a2 and m^R (per axis), and
// on b1, b2, the current footprint's columns.
struct PixelBound {
  bool near = false;
  glm::dvec2 mu{0.0}, a1{0.0}, a2{0.0}, motion{0.0}, b1{0.0}, b2{0.0};
};

// The golden transform_point (float), widened.
glm::dvec3 transform_point(const glm::mat4& m, const glm::vec3& p) {
  return glm::dvec3(glm::vec3(m * glm::vec4(p, 1.0f)));
}

// The footprint of a mirror image seen by `view` (the golden footprint_axes): false when it has none; `near` set
// where one of its decisions lies within its margin; da the banner's B_a per column (before the doubling).
bool footprint_bound(const MirrorTerms& m, double sigma, const View& view, const glm::mat2& golden_axes, bool& near,
                     glm::dvec2 (&da)[2]) {
  // The horizon test and the normal-incidence test.
  const double c = std::clamp(m.cos_i, 0.0, 1.0), dc = 40.0 * kE * c + kE;
  const double one_minus = 1.0 - std::min(c + dc, 1.0) * std::min(c + dc, 1.0);
  const double dasin = std::min(one_minus > 0.0 ? dc / std::sqrt(one_minus) : HUGE_VAL,
                                glm::pi<double>() / std::sqrt(2.0) * std::sqrt(dc));
  near = near || std::abs(sigma - std::asin(c)) <= 4097.0 * kE * (sigma + glm::half_pi<double>()) + dasin;
  if (!(sigma < std::asin(c))) return false;
  glm::dvec3 t1 = m.incidence - glm::dot(m.n, m.incidence) * m.n;
  near = near || std::abs(glm::length(t1) - double(kGlossyNormalIncidence)) <= 64.0 * kE;
  if (glm::length(t1) < double(kGlossyNormalIncidence)) {
    glm::vec3 t, unused;
    orthonormal_basis(glm::vec3(m.n), t, unused);
    t1 = glm::dvec3(t);
  }
  t1 = glm::normalize(t1);
  const glm::dvec3 t2 = glm::cross(m.n, t1);
  // r and its relative error (banner).
  const double tan_sigma = std::tan(sigma), sec2 = 1.0 + tan_sigma * tan_sigma;
  const double dtan = (kSinCos * (1.0 + tan_sigma) + 4097.0 * kE * sigma * sec2) / (std::cos(sigma) - kSinCos) +
                      3.0 * kE * tan_sigma;
  const double dd_rel = 5.0 * kE + m.dt_rel * m.t / (1.0 - m.t) + kE;
  const double r_across = m.d * tan_sigma, r_along = r_across / m.cos_i;
  const double dr_across = dd_rel + dtan / tan_sigma + 2.0 * kE, dr_along = dr_across + m.dcos_rel + 3.0 * kE;
  const double dsc = m.dt_rel * m.t * m.len + m.t * m.dv + 2.0 * kE * glm::length(m.sc);
  const glm::dvec3 semi[2] = {r_along * t1, r_across * t2};
  const double dsemi[2] = {r_along * (dr_along + 20.0 * kE), r_across * (dr_across + 20.0 * kE)};
  bool behind = false;
  for (int k = 0; k < 2; ++k) {
    const double z_plus = depth_of(view, m.sc + semi[k]), z_minus = depth_of(view, m.sc - semi[k]);
    near = near || near_znear(z_plus, view.znear) || near_znear(z_minus, view.znear);
    behind = behind || z_plus < double(view.znear) || z_minus < double(view.znear);
    da[k] = 0.5 * (screen_bound(view, m.sc + semi[k], dsc + dsemi[k]) +
                   screen_bound(view, m.sc - semi[k], dsc + dsemi[k])) +
            kE * glm::abs(glm::dvec2(golden_axes[k]));
  }
  return !behind;
}

PixelBound bound(const GlossyRay& r, const std::vector<InstanceMotion>& to_previous, const View& view,
                 const View& prev_view, const GlossyMotion& golden) {
  PixelBound b;
  if (r.reflector_instance == kInvalidId || r.hit_instance == kInvalidId) return b;
  const MirrorTerms now = mirror_terms(view.eye, r.hit, r.reflector, r.reflector_normal);
  b.near = now.near || (now.ok && near_znear(depth_of(view, now.v), view.znear));
  const double sigma = 2.0 * std::atan(double(kGgxLobeTanPerAlpha) * double(ggx_alpha(r.roughness)));
  // The current footprint (the glossy filter's kernel), where the current mirror image is in front of the camera.
  if (now.ok && depth_of(view, now.v) >= double(view.znear)) {
    glm::dvec2 db[2];
    if (footprint_bound(now, sigma, view, golden.footprint_axes, b.near, db)) b.b1 = 2.0 * db[0], b.b2 = 2.0 * db[1];
  }
  // The previous frame's inputs: the same float operations on both sides (exact), then double.
  const InstanceMotion& T = to_previous[r.reflector_instance];
  const glm::dvec3 h_prev = transform_point(to_previous[r.hit_instance].to_previous, r.hit);
  const glm::dvec3 s_prev = transform_point(T.to_previous, r.reflector);
  const glm::dvec3 n_prev = glm::dvec3(T.normal_to_previous * r.reflector_normal);
  const MirrorTerms before = mirror_terms(prev_view.eye, h_prev, s_prev, n_prev);
  b.near = b.near || before.near || (before.ok && near_znear(depth_of(prev_view, before.v), prev_view.znear));
  if (!now.ok || !before.ok) return b;
  glm::dvec2 da[2];
  if (!footprint_bound(before, sigma, prev_view, golden.axes, b.near, da)) return b;
  // The Gaussian pair: rho = |n|, Box-Muller's radius (banner).
  const glm::dvec2 n12(glossy_normal_pair(r.seed));
  const double rho = glm::length(n12), q = rho * rho;
  const double u = 1.0 - std::exp(-q / 2.0);
  const double dq = u <= 0.5 ? std::ldexp(1.0, -20) + 2.0 * kE * q : 8.0 * kE * q;
  const double drho = std::min(rho > 0.0 ? dq / (2.0 * rho) : HUGE_VAL, std::sqrt(dq)) + 5.0 * kE * rho;
  const double dn = drho + rho * (kSinCos + kE + 1.75e-7);

  const glm::dvec2 mu_abs = glm::abs(glm::dvec2(golden.mu));
  b.mu = 2.0 * (screen_bound(view, now.v, now.dv) + screen_bound(prev_view, before.v, before.dv) + kE * mu_abs);
  b.a1 = 2.0 * da[0], b.a2 = 2.0 * da[1];
  glm::dvec2 sum_an(0.0);
  for (int k = 0; k < 2; ++k) sum_an += glm::abs(glm::dvec2(golden.axes[k])) * std::abs(n12[k]);
  b.motion = b.mu + 2.0 * (da[0] * std::abs(n12.x) + da[1] * std::abs(n12.y) +
                           (glm::abs(glm::dvec2(golden.axes[0])) + glm::abs(glm::dvec2(golden.axes[1]))) * dn +
                           3.0 * kE * (mu_abs + sum_an));
  return b;
}

struct Counts {
  int invalid = 0, valid = 0, near = 0, footprints = 0;
};

double worst_over(glm::vec2 gpu, glm::vec2 golden, glm::dvec2 limit, double& worst, double& ratio) {
  double over = 0.0;
  for (int a = 0; a < 2; ++a) {
    const double diff = abs_difference(gpu[a], golden[a]);  // NaN: infinite
    worst = std::max(worst, diff);
    ratio = std::max(ratio, limit[a] > 0.0 ? diff / limit[a] : (diff > 0.0 ? HUGE_VAL : 0.0));
    over += diff > limit[a];
  }
  return over;
}

// Port and golden pass on the same frame: the flags exact away from the margins, invalid pixels exact, the values
// within the banner's bounds.
Counts check_port(VulkanContext& context, const FrameGeometry& g, const Frame& frame, double* ms = nullptr) {
  const std::vector<GlossyMotion> golden = glossy_motion(g, frame);
  const std::vector<GlossyMotion> gpu = glossy_motion_vulkan(context, g, frame, ms);
  REQUIRE(gpu.size() == golden.size());
  const GlossyRayLayers rays(frame);
  const std::vector<InstanceMotion> to_previous = instance_to_previous(g.pose, g.prev_pose);
  Counts c;
  size_t flag_mismatches = 0, invalid_mismatches = 0, over = 0;
  double worst_mu = 0, worst_a = 0, worst_a_rel = 0, worst_m = 0, worst_b = 0, ratio = 0;
  for (size_t i = 0; i < golden.size(); ++i) {
    const PixelBound b = bound(rays.at(i), to_previous, g.view, g.prev_view, golden[i]);
    if (b.near) {
      ++c.near;
      continue;
    }
    if (gpu[i].valid != golden[i].valid || gpu[i].has_footprint != golden[i].has_footprint) {
      ++flag_mismatches;
      continue;
    }
    if (golden[i].has_footprint) {  // the current footprint, b1 and b2
      ++c.footprints;
      over += worst_over(gpu[i].footprint_axes[0], golden[i].footprint_axes[0], b.b1, worst_b, ratio);
      over += worst_over(gpu[i].footprint_axes[1], golden[i].footprint_axes[1], b.b2, worst_b, ratio);
    }
    if (!golden[i].valid) {
      ++c.invalid;
      invalid_mismatches += gpu[i].motion != glm::vec2(0.0f);
      continue;
    }
    ++c.valid;
    over += worst_over(gpu[i].mu, golden[i].mu, b.mu, worst_mu, ratio);
    over += worst_over(gpu[i].axes[0], golden[i].axes[0], b.a1, worst_a, ratio);
    over += worst_over(gpu[i].axes[1], golden[i].axes[1], b.a2, worst_a, ratio);
    for (int k = 0; k < 2; ++k)
      worst_a_rel = std::max(worst_a_rel, glm::length(glm::dvec2(gpu[i].axes[k] - golden[i].axes[k])) /
                                              glm::length(glm::dvec2(golden[i].axes[k])));
    over += worst_over(gpu[i].motion, golden[i].motion, b.motion, worst_m, ratio);
  }
  WARN("measured max |gpu - golden| on " << context.device_name() << ": mu " << worst_mu << " px, a1/a2 "
                                         << worst_a << " px (" << worst_a_rel << " of |a_k|), b1/b2 " << worst_b
                                         << " px over " << c.footprints << " current footprints, m^R " << worst_m
                                         << " px (at most " << ratio << " of the bound) over " << c.valid
                                         << " valid pixels; " << c.invalid << " invalid (" << invalid_mismatches
                                         << " not (0, 0)); " << c.near << " near a threshold (not compared); "
                                         << flag_mismatches << " flags differ");
  CHECK(flag_mismatches == 0);
  CHECK(invalid_mismatches == 0);
  CHECK(over == 0);
  return c;
}

// The same frame with every pixel's roughness redrawn in [0, 1] and its seed replaced: other lobes (up to past the
// plane's horizon) and other draws.
Frame redrawn(Frame frame, uint32_t seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> u(0.0f, 1.0f);
  for (float& r : frame.float_channel("material.roughness").data) r = u(rng);
  for (uint32_t& s : frame.uint_channel("rng.seed").data) s = uint32_t(rng());
  return frame;
}

// A device as far from C++ as Vulkan lets it be, simulated: glossy_motion_pixel's operations in the golden order, each
// division 2 ulps and each square root 4 ulps off the correctly rounded result, asin and atan 4096 ulps, log 3 ulps
// (2^-21 absolute in [0.5, 2]), sin and cos 2^-11 absolute (tan their quotient), either way, as the device chooses.
class SkewedDevice {
 public:
  explicit SkewedDevice(unsigned seed) : rng_(seed) {}

  GlossyMotion pixel(const GlossyRay& r, const std::vector<InstanceMotion>& to_previous, const View& view,
                     const View& prev_view) {
    GlossyMotion out;
    if (r.reflector_instance == kInvalidId || r.hit_instance == kInvalidId) return out;
    Mirror now, before;
    if (!mirror(view.eye, r.hit, r.reflector, r.reflector_normal, now)) return out;
    const glm::vec3 x_cur = project(view, now.image);
    if (x_cur.z < view.znear) return out;
    const InstanceMotion& T = to_previous[r.reflector_instance];
    const glm::vec3 h_prev = glm::vec3(to_previous[r.hit_instance].to_previous * glm::vec4(r.hit, 1.0f));
    const glm::vec3 s_prev = glm::vec3(T.to_previous * glm::vec4(r.reflector, 1.0f));
    if (!mirror(prev_view.eye, h_prev, s_prev, T.normal_to_previous * r.reflector_normal, before)) return out;
    const glm::vec3 mu = project(prev_view, before.image);
    if (mu.z < prev_view.znear) return out;
    glm::mat2 axes;
    const float sigma_theta = 2.0f * skew(std::atan(kGgxLobeTanPerAlpha * ggx_alpha(r.roughness)), 4096);
    if (!footprint(before, sigma_theta, prev_view, axes)) return out;
    out.mu = glm::vec2(mu) - glm::vec2(x_cur);
    out.axes = axes;
    out.motion = out.mu + axes * normal_pair(r.seed);
    out.valid = true;
    return out;
  }

 private:
  struct Mirror {
    glm::vec3 image, specular_point, normal, incidence;
    float cos_incidence, distance;
  };

  // x moved by up to `most` of its ulps, or by up to `absolute`, either way.
  float skew(float x, double most) {
    if (x == 0.0f || !std::isfinite(x)) return x;  // an ulp of 0 is 0 (and nothing is off an infinity)
    const double ulp = std::ldexp(1.0, std::max(std::ilogb(x), -126) - 23);
    return float(double(x) + std::uniform_real_distribution<double>(-most, most)(rng_) * ulp);
  }
  float shift(double x, double absolute) {
    return float(x + std::uniform_real_distribution<double>(-absolute, absolute)(rng_));
  }
  float div(float a, float b) { return skew(a / b, 2); }
  float root(float x) { return skew(std::sqrt(x), 4); }
  float length(const glm::vec3& v) { return root(glm::dot(v, v)); }
  glm::vec3 normalize(const glm::vec3& v) { return v * div(1.0f, root(glm::dot(v, v))); }
  glm::vec3 divide(const glm::vec3& v, float d) { return {div(v.x, d), div(v.y, d), div(v.z, d)}; }
  glm::vec3 project(const View& v, const glm::vec3& world) {
    const glm::vec4 clip = v.world_to_clip * glm::vec4(world, 1.0f);
    const glm::vec2 ndc(div(clip.x, clip.w), div(clip.y, clip.w));
    return {(ndc.x * 0.5f + 0.5f) * float(v.width), (0.5f - ndc.y * 0.5f) * float(v.height), clip.w};
  }

  bool mirror(const glm::vec3& eye, const glm::vec3& h, const glm::vec3& s, glm::vec3 n, Mirror& out) {
    n = normalize(n);
    float eye_height = glm::dot(n, eye - s), h_height = glm::dot(n, h - s);
    if (!(eye_height * h_height > 0.0f)) return false;
    if (eye_height < 0.0f) n = -n, eye_height = -eye_height, h_height = -h_height;
    const glm::vec3 v = h - 2.0f * h_height * n;
    const glm::vec3 eye_to_v = v - eye;
    const float len = length(eye_to_v);
    const float n_dot_line = glm::dot(n, eye_to_v);
    if (std::abs(n_dot_line) <= kGlossyParallelCosine * len) return false;
    const float t = div(eye_height, eye_height + h_height);
    out = {v, eye + t * eye_to_v, n, divide(eye_to_v, len), div(-n_dot_line, len), (1.0f - t) * len};
    return true;
  }

  bool footprint(const Mirror& m, float sigma_theta, const View& view, glm::mat2& axes) {
    const float axis_to_plane = skew(std::asin(std::clamp(m.cos_incidence, 0.0f, 1.0f)), 4096);
    if (!(sigma_theta < axis_to_plane)) return false;
    glm::vec3 t1 = m.incidence - glm::dot(m.normal, m.incidence) * m.normal;
    if (length(t1) < kGlossyNormalIncidence) {
      glm::vec3 unused;
      orthonormal_basis(m.normal, t1, unused);
    }
    t1 = normalize(t1);
    const glm::vec3 t2 = glm::cross(m.normal, t1);
    const float tan_sigma = div(shift(std::sin(sigma_theta), kSinCos), shift(std::cos(sigma_theta), kSinCos));
    const float r_across = m.distance * tan_sigma;
    const float r_along = div(r_across, m.cos_incidence);
    const glm::vec3 semi_axes[2] = {r_along * t1, r_across * t2};
    for (int k = 0; k < 2; ++k) {
      const glm::vec3 plus = project(view, m.specular_point + semi_axes[k]);
      const glm::vec3 minus = project(view, m.specular_point - semi_axes[k]);
      if (plus.z < view.znear || minus.z < view.znear) return false;
      axes[k] = 0.5f * (glm::vec2(plus) - glm::vec2(minus));
    }
    return true;
  }

  // Box-Muller as the shader computes it, its angle moved into [-pi, pi).
  glm::vec2 normal_pair(uint32_t seed) {
    const glm::vec2 u = Sampler(hash_combine(seed, kGlossyStream), 0).next_2d();
    const float x = 1.0f - u.x;
    const float log_x = x >= 0.5f ? shift(std::log(x), std::ldexp(1.0, -21)) : skew(std::log(x), 3);
    const float radius = root(-2.0f * log_x);
    const float phi = 2.0f * kGlossyPi * u.y;
    const float angle = phi < kGlossyPi ? phi : phi - 2.0f * kGlossyPi;
    return {radius * shift(std::cos(angle), kSinCos), radius * shift(std::sin(angle), kSinCos)};
  }

  std::mt19937 rng_;
};

}  // namespace

TEST_CASE("the glossy motion bound holds for a simulated device whose functions are as far off as Vulkan allows") {
  // No Vulkan needed: this checks the banner's derivation, where lavapipe (a few functions off) cannot.
  const Scene scene = load_scene("glossy");
  const int w = 100, h = 57, index = 20;
  const FrameGeometry g = rasterize_frame(scene, index, w, h);
  const Frame frame = render_frame(scene, index, w, h, RenderSettings{});
  const std::vector<InstanceMotion> to_previous = instance_to_previous(g.pose, g.prev_pose);
  double worst_ratio = 0.0;
  size_t compared = 0, differ = 0, near = 0, flags = 0, over = 0;
  for (const Frame& f : {frame, redrawn(frame, 5u)}) {
    const GlossyRayLayers rays(f);
    const std::vector<GlossyMotion> golden = glossy_motion(g, f);
    for (unsigned seed = 0; seed < 4; ++seed) {
      SkewedDevice device(seed);
      for (size_t i = 0; i < golden.size(); ++i) {
        const GlossyRay ray = rays.at(i);
        const PixelBound b = bound(ray, to_previous, g.view, g.prev_view, golden[i]);
        const GlossyMotion m = device.pixel(ray, to_previous, g.view, g.prev_view);
        if (b.near) {
          ++near;
          continue;
        }
        if (m.valid != golden[i].valid) {
          ++flags;
          continue;
        }
        if (!m.valid) continue;
        ++compared;
        double worst = 0.0, ratio = 0.0;
        over += worst_over(m.mu, golden[i].mu, b.mu, worst, ratio);
        over += worst_over(m.axes[0], golden[i].axes[0], b.a1, worst, ratio);
        over += worst_over(m.axes[1], golden[i].axes[1], b.a2, worst, ratio);
        over += worst_over(m.motion, golden[i].motion, b.motion, worst, ratio);
        differ += worst > 0.0;
        worst_ratio = std::max(worst_ratio, ratio);
      }
    }
  }
  WARN("simulated device: " << differ << " of " << compared << " valid pixels differ, at most " << worst_ratio
                            << " of their bound; " << near << " near a threshold (not compared); " << flags
                            << " flags differ");
  CHECK(flags == 0);
  CHECK(over == 0);
  CHECK(differ > compared / 2);  // the simulation does move the vectors
}

TEST_CASE("the glossy motion port matches glossy_motion on the glossy scene's floor under the orbiting camera") {
  const auto context = validated_context();
  const Scene scene = load_scene("glossy");
  const int w = 100, h = 57, index = 20;  // the last tiles overhang on either workgroup shape (32 x 2, 8 x 8)
  const FrameGeometry g = rasterize_frame(scene, index, w, h);
  const Frame frame = render_frame(scene, index, w, h, RenderSettings{});
  glossy_motion_vulkan(*context, g, frame);  // warm-up: lavapipe compiles
  double ms = 0.0;
  const Counts c = check_port(*context, g, frame, &ms);
  WARN("motion_glossy dispatch " << ms << " ms (" << w << "x" << h << ") on " << context->device_name());
  CHECK(ms > 0.0);
  CHECK(c.valid > 100);  // the floor's reflections (tests/motion_glossy_test.cpp)
  CHECK(c.footprints >= c.valid / 2);  // the current footprint where the previous one is, but for the frame's edges
  CHECK(c.invalid > 0);
  // Other lobes, from GGX's narrowest to past the plane's horizon, and other draws.
  CHECK(check_port(*context, g, redrawn(frame, 5u)).valid > 100);
  check_no_validation_messages(*context);
}

TEST_CASE("the glossy motion port matches glossy_motion on cornell, where nothing moves") {
  const auto context = validated_context();
  const Scene scene = load_scene("cornell");
  const FrameGeometry g = rasterize_frame(scene, 3, 64, 64);
  const Frame frame = render_frame(scene, 3, 64, 64, RenderSettings{});
  // Cornell's own materials are rough: their lobes reach past the plane's horizon, and no pixel has a vector. With
  // roughnesses drawn in [0, 1], the smoother ones do, on the walls, the floor and the boxes.
  check_port(*context, g, frame);
  CHECK(check_port(*context, g, redrawn(frame, 11u)).valid > 100);
  check_no_validation_messages(*context);
}

TEST_CASE("the glossy motion port refuses a frame without the path layers, or of another size") {
  const auto context = validated_context();
  const Scene scene = load_scene("cornell");
  const FrameGeometry g = rasterize_frame(scene, 3, 32, 32);
  CHECK_THROWS_AS(glossy_motion_vulkan(*context, g, Frame(32, 32)), Error);
  const Frame frame = render_frame(scene, 3, 16, 16, RenderSettings{});
  CHECK_THROWS_WITH(glossy_motion_vulkan(*context, g, frame), "glossy_motion: a 16x16 frame for a 32x32 geometry");
}
