// Tests of gpu/motion_shadow_gpu.cpp: the Vulkan port of the shadow motion vector [TRMV21 Eq. 3]
// (motion/shadow.comp) against the golden shadow_motion() (motion/shadow.cpp), on rendered frames of the
// fence (a moving blocker) and falling-light (a moving light) scenes and on random inputs, with the validation layer
// on. Skipped, with a message, where no Vulkan device exists.
//
// Bound, shadow motion. Both sides do the same fp32 operations in the same order: the shader marks every result
// `precise` (no fma contraction, no reordering) and writes glm's dot, mat3 * vec3 and mat4 * vec4 out in glm's order,
// and the C++ is built without fma (no -march, no -ffp-contract). Vulkan rounds +, - and * correctly, so T^{-1} l_i,
// T^{-1} b_i, T^{-1} s_i, T^{-1} n, b - l, n.(b - l) and n.(s - l) are bit-identical; only the square root (the
// parallel test), the division t = n.(s - l) / n.(b - l) and the two divisions of each projection (clip.xy / clip.w)
// may differ. With e = 2^-23 (an ulp of a float x is at most e |x|; rounding to nearest moves x by at most e |x| / 2
// on each side, e |x| between two sides whose inputs differ), per pixel:
//   decisions  the id tests are exact. The parallel test |n.(b - l)| <= 1e-6 |b - l| compares a bit-identical dot
//              product with a length whose sqrt is within 4.5 ulp on the device (1 / inversesqrt) and 0.5 in C++,
//              and whose product rounds on each side: it can flip only within 8 e of the threshold, relative. t > 1:
//              the device's division is within 2.5 ulp, C++'s 0.5, so t differs by at most 3 e |t|: it can flip only
//              where |t - 1| <= 4 e |t|. depth >= znear: the depth clip.w differs by at most Delta c_w (below): it
//              can flip only within 2 Delta c_w of znear. Such pixels are counted and not compared (none here);
//              every other pixel has the golden validity, exactly.
//   s^         Delta t = 3 e |t|; s^ = l + t (b - l), lb = b - l, per component:
//              Delta s^_c = Delta t |lb_c| + e |t lb_c| + e |s^_c| (the product and the sum round on each side), for
//              s^_i and for s^_{i-1} alike.
//   project    clip_k = (M_k0 x + M_k1 y) + (M_k2 z + M_k3):
//              Delta c_k = sum_j |M_kj| Delta s_j + 3 e (sum_j |M_kj s_j| + |M_k3|) (three roundings deep on each
//              side). ndc = c / c_w: Delta ndc = Delta c / |c_w| + |c| Delta c_w / c_w^2 + 3 e |ndc| (2.5 + 0.5 ulp
//              of the divisions). Screen x = (ndc 0.5 + 0.5) W: Delta x = W (Delta ndc / 2 + e (|ndc| / 2 + 1 / 2))
//              + e |x|; y likewise with H.
//   m^V        = x_{i-1} - x_i: Delta m = Delta x_{i-1} + Delta x_i + e |m|, times 1.001 for the second-order terms.
// At most 2.5e-4 px on the rendered frames here, 0.19 px on the random rays (a line nearly parallel to its plane:
// t and its error large). A simulated device whose divisions are 2 ulp and square roots 4 ulp off, either way,
// stays within 0.44 of it (the first test case). Divisions outside [2^-126, 2^126] have no stated precision in
// Vulkan; no input here comes near.
// On a CPU device (lavapipe) the square root and the divisions round correctly, so the port is bit-exact there.
// Measured worst on lavapipe (llvmpipe, LLVM 15), over every input and all four builds here: 0 (bit-exact); no pixel
// near a threshold. The splat of these vectors is the filter's (filters/trmv/splat.h), tested with its port in
// tests/gpu_trmv_splat_test.cpp.
#include "gpu/motion_shadow_gpu.h"

#include "core/error.h"
#include "motion/shadow.h"
#include "raster/gbuffer_frame.h"
#include "scene_fixtures.h"
#include "scenes/gltf_loader.h"
#include "trace/render_frame.h"

#include "gpu_fixtures.h"

#include <catch2/catch.hpp>

#include <glm/gtc/matrix_transform.hpp>

#include <algorithm>
#include <cmath>
#include <random>
#include <string>
#include <vector>

using namespace rtdr;
using namespace rtdr::gpu_test;

namespace {

const double kE = std::ldexp(1.0, -23);

// The golden pass's decision at a pixel; each kind of invalid pixel apart, so that a test can see every path taken.
enum class Decision { NotInShadow, Parallel, NotBeyond, BehindCamera, Valid, NearThreshold };

// intersect_shadow_line as the golden pass computes it (the same float operations), with the bound on each
// component of the device's s^ (the banner's Delta s^), or NearThreshold where a decision is within rounding.
Decision intersect_with_bound(const glm::vec3& l, const glm::vec3& b, const glm::vec3& s, const glm::vec3& n,
                              glm::vec3& point, glm::dvec3& bound) {
  const glm::vec3 lb = b - l;
  const float n_dot_lb = glm::dot(n, lb);
  const double threshold = double(kShadowParallelCosine) * double(glm::length(lb));
  if (std::abs(std::abs(double(n_dot_lb)) - threshold) <= 8.0 * kE * threshold) return Decision::NearThreshold;
  if (std::abs(n_dot_lb) <= kShadowParallelCosine * glm::length(lb)) return Decision::Parallel;
  const float numerator = glm::dot(n, s - l);
  const double q = double(numerator) / double(n_dot_lb);
  if (std::abs(q - 1.0) <= 4.0 * kE * std::abs(q)) return Decision::NearThreshold;
  const float t = numerator / n_dot_lb;
  if (!(t > 1.0f)) return Decision::NotBeyond;
  point = l + t * lb;
  const double dt = 3.0 * kE * std::abs(q);
  for (int c = 0; c < 3; ++c)
    bound[c] =
        dt * std::abs(double(lb[c])) + kE * std::abs(double(t) * double(lb[c])) + kE * std::abs(double(point[c]));
  return Decision::Valid;
}

// View::project of a point known within `ds` per component: (x, y, depth) and the banner's bound on each.
struct Projection {
  glm::dvec3 x, bound;
};

Projection project_with_bound(const View& v, const glm::vec3& s, const glm::dvec3& ds) {
  const glm::dmat4 m(v.world_to_clip);
  const glm::dvec3 p(s);
  glm::dvec4 c(0.0), dc(0.0);
  for (int k = 0; k < 4; ++k) {
    double magnitude = std::abs(m[3][k]);
    c[k] = m[3][k];
    for (int j = 0; j < 3; ++j) {
      c[k] += m[j][k] * p[j];
      dc[k] += std::abs(m[j][k]) * ds[j];
      magnitude += std::abs(m[j][k] * p[j]);
    }
    dc[k] += 3.0 * kE * magnitude;
  }
  Projection out;
  const double size[2] = {double(v.width), double(v.height)};
  for (int a = 0; a < 2; ++a) {
    const double ndc = c[a] / c.w;
    const double d_ndc = dc[a] / std::abs(c.w) + std::abs(c[a]) * dc.w / (c.w * c.w) + 3.0 * kE * std::abs(ndc);
    out.x[a] = (a == 0 ? ndc * 0.5 + 0.5 : 0.5 - ndc * 0.5) * size[a];
    out.bound[a] = size[a] * (0.5 * d_ndc + kE * (0.5 * std::abs(ndc) + 0.5)) + kE * std::abs(out.x[a]);
  }
  out.x.z = c.w, out.bound.z = dc.w;
  return out;
}

// What the golden pass decides at a pixel, and the bound on |gpu - golden| of each component of m^V.
struct Expected {
  Decision decision = Decision::NotInShadow;
  double bound = 0.0;
};

Expected expected_at(const ShadowRay& r, const std::vector<InstanceMotion>& to_previous, const View& view,
                     const View& prev_view) {
  Expected out;
  if (r.receiver_instance == kInvalidId || r.blocker_instance == kInvalidId || r.light_instance == kInvalidId)
    return out;
  glm::vec3 s_hat, s_hat_prev;
  glm::dvec3 ds(0.0), ds_prev(0.0);
  out.decision = intersect_with_bound(r.light, r.blocker, r.receiver, r.receiver_normal, s_hat, ds);
  if (out.decision != Decision::Valid) return out;
  const InstanceMotion& T = to_previous[r.receiver_instance];
  const glm::vec3 l_prev = glm::vec3(to_previous[r.light_instance].to_previous * glm::vec4(r.light, 1.0f));
  const glm::vec3 b_prev = glm::vec3(to_previous[r.blocker_instance].to_previous * glm::vec4(r.blocker, 1.0f));
  const glm::vec3 s_prev = glm::vec3(T.to_previous * glm::vec4(r.receiver, 1.0f));
  const glm::vec3 n_prev = T.normal_to_previous * r.receiver_normal;
  out.decision = intersect_with_bound(l_prev, b_prev, s_prev, n_prev, s_hat_prev, ds_prev);
  if (out.decision != Decision::Valid) return out;
  const Projection x_prev = project_with_bound(prev_view, s_hat_prev, ds_prev);
  if (std::abs(x_prev.x.z - double(prev_view.znear)) <= 2.0 * x_prev.bound.z) {
    out.decision = Decision::NearThreshold;
    return out;
  }
  if (x_prev.x.z < double(prev_view.znear)) {
    out.decision = Decision::BehindCamera;
    return out;
  }
  const Projection x_cur = project_with_bound(view, s_hat, ds);
  for (int a = 0; a < 2; ++a)
    out.bound =
        std::max(out.bound, 1.001 * (x_prev.bound[a] + x_cur.bound[a] + kE * std::abs(x_prev.x[a] - x_cur.x[a])));
  return out;
}

struct Counts {
  int invalid = 0, valid = 0, near_threshold = 0;
  int not_in_shadow = 0, parallel = 0, not_beyond = 0, behind_camera = 0;  // the invalid ones, by reason
};

// A NaN on either side counts as an infinite difference.
double diff(float a, float b) { return std::isnan(a) || std::isnan(b) ? HUGE_VAL : std::abs(double(a) - double(b)); }

// The shadow port and the golden pass on one frame: the golden validity exactly (away from the thresholds), m^V
// within the banner's per-pixel bound. Returns the golden vectors.
std::vector<ShadowMotion> check_shadow_port(VulkanContext& context, const FrameGeometry& g, const Frame& frame,
                                            Counts& c, double* ms = nullptr) {
  const std::vector<ShadowMotion> golden = shadow_motion(g, frame);
  const std::vector<ShadowMotion> gpu = shadow_motion_vulkan(context, g, frame, ms);
  REQUIRE(gpu.size() == golden.size());
  const ShadowRayLayers rays(frame);
  const std::vector<InstanceMotion> to_previous = instance_to_previous(g.pose, g.prev_pose);
  size_t validity_mismatches = 0, mirror_mismatches = 0, over_bound = 0;
  double worst = 0.0, worst_ratio = 0.0, largest_bound = 0.0;  // worst_ratio: the largest difference / bound
  for (size_t i = 0; i < golden.size(); ++i) {
    const Expected e = expected_at(rays.at(i), to_previous, g.view, g.prev_view);
    if (e.decision == Decision::NearThreshold) {
      ++c.near_threshold;
      continue;
    }
    mirror_mismatches += golden[i].valid != (e.decision == Decision::Valid);  // the test's mirror is the golden pass
    validity_mismatches += gpu[i].valid != golden[i].valid;
    if (!golden[i].valid) {
      ++c.invalid;
      c.not_in_shadow += e.decision == Decision::NotInShadow, c.parallel += e.decision == Decision::Parallel;
      c.not_beyond += e.decision == Decision::NotBeyond, c.behind_camera += e.decision == Decision::BehindCamera;
      validity_mismatches += gpu[i].motion != glm::vec2(0.0f);  // (0, 0) exactly
      continue;
    }
    ++c.valid;
    const double d = std::max(diff(gpu[i].motion.x, golden[i].motion.x), diff(gpu[i].motion.y, golden[i].motion.y));
    over_bound += !(d <= e.bound);
    worst = std::max(worst, d);
    if (d > 0.0) worst_ratio = std::max(worst_ratio, d / e.bound);
    largest_bound = std::max(largest_bound, e.bound);
  }
  WARN("shadow motion: measured max |gpu - golden| on "
       << context.device_name() << ": " << worst << " px, at most " << worst_ratio
       << " of its pixel's bound (largest bound " << largest_bound << " px); " << c.valid << " valid, " << c.invalid
       << " invalid (" << c.not_in_shadow << " not in shadow, " << c.parallel << " parallel, " << c.not_beyond
       << " not beyond the blocker, " << c.behind_camera << " behind the camera), " << c.near_threshold
       << " near a threshold (not compared)");
  CHECK(mirror_mismatches == 0);
  CHECK(validity_mismatches == 0);
  CHECK(over_bound == 0);
  return golden;
}

// Frame `index` of a shipped scene with its geometry, at 1 spp, as `rtdr render` makes it.
struct RenderedFrame {
  FrameGeometry geometry;
  Frame frame;
};

RenderedFrame render(const std::string& name, int index, int w, int h) {
  const Scene scene = load_scene(name);
  return {rasterize_frame(scene, index, w, h), render_frame(scene, index, w, h, RenderSettings{})};
}

// A random rigid-ish motion (rotation, scale, translation) for the random inputs' instances.
glm::mat4 random_transform(std::mt19937& rng, float spread) {
  std::uniform_real_distribution<float> u(-1.0f, 1.0f);
  glm::mat4 m = glm::translate(glm::mat4(1.0f), spread * glm::vec3(u(rng), u(rng), u(rng)));
  m = glm::rotate(m, 0.3f * spread * u(rng),
                  glm::normalize(glm::vec3(u(rng), u(rng), u(rng)) + glm::vec3(0.0f, 2.0f, 0.0f)));
  return glm::scale(m, glm::vec3(1.0f + 0.1f * spread * u(rng)));
}

// Random shadow rays in front of a camera at the origin looking down -Z: a light above, a receiver below on a plane
// with a tilted normal (not unit), the blocker between them on the line, or beyond the receiver (t < 1); some lines
// parallel to the plane, some rays unblocked, some pixels without a surface; four instances with random motions, the
// last one moved towards and behind the previous camera.
RenderedFrame random_inputs(std::mt19937& rng, int w, int h) {
  std::uniform_real_distribution<float> u(0.0f, 1.0f);
  RenderedFrame r;
  FrameGeometry& g = r.geometry;
  g.vis.width = w, g.vis.height = h;
  for (int k = 0; k < 4; ++k) {
    g.pose.instance_to_world.push_back(random_transform(rng, 1.0f));
    g.prev_pose.instance_to_world.push_back(random_transform(rng, 1.0f));
  }
  g.prev_pose.instance_to_world[3] = glm::translate(g.pose.instance_to_world[3], glm::vec3(0.0f, 0.0f, 6.0f));
  g.view = make_view(test::camera_scene(), test::camera_scene().pose(0.0), w, h, {0.25f, -0.125f});
  g.prev_view = make_view(test::camera_scene(glm::vec3(0.1f, 0.05f, 0.2f)),
                          test::camera_scene(glm::vec3(0.1f, 0.05f, 0.2f)).pose(0.0), w, h, {-0.375f, 0.5f});
  const size_t n = size_t(w) * size_t(h);
  std::vector<glm::vec3> light(n), blocker(n), position(n), normal(n);
  UIntPlane light_id(w, h), blocker_id(w, h), receiver_id(w, h);
  for (size_t i = 0; i < n; ++i) {
    const glm::vec3 l(2.0f * u(rng) - 1.0f, 3.0f + 2.0f * u(rng), -5.0f - 2.0f * u(rng));
    const glm::vec3 s(6.0f * u(rng) - 3.0f, -1.5f - 0.5f * u(rng), -4.0f - 4.0f * u(rng));
    const float r1 = u(rng);
    const float along = r1 < 0.1f ? 1.0f + 0.5f * u(rng) : 0.3f + 0.4f * u(rng);  // beyond s: t < 1
    const glm::vec3 b = l + along * (s - l);
    glm::vec3 nrm(0.4f * u(rng) - 0.2f, 0.5f + u(rng), 0.4f * u(rng) - 0.2f);
    if (u(rng) < 0.03f) nrm = glm::cross(b - l, glm::vec3(u(rng), 0.0f, 1.0f));  // the line parallel to the plane
    light[i] = l, blocker[i] = b, position[i] = s, normal[i] = nrm;
    light_id.data[i] = uint32_t(4.0f * u(rng)) % 4u;
    blocker_id.data[i] = u(rng) < 0.1f ? kInvalidId : uint32_t(4.0f * u(rng)) % 4u;
    receiver_id.data[i] = u(rng) < 0.03f ? kInvalidId : uint32_t(4.0f * u(rng)) % 4u;
    if (u(rng) < 0.02f) light_id.data[i] = kInvalidId;
  }
  r.frame = Frame(w, h);
  r.frame.set_vec3("path.light", light);
  r.frame.set_vec3("path.blocker", blocker);
  r.frame.set_vec3("position", position);
  r.frame.set_vec3("geonormal", normal);
  r.frame.add_uint("path.light.instance") = light_id;
  r.frame.add_uint("path.blocker.instance") = blocker_id;
  r.frame.add_uint("id.instance") = receiver_id;
  return r;
}

// A device as far from C++ as Vulkan lets it be, simulated: shadow_motion_pixel's operations in the golden order,
// each division and square root rounded `ulps()` ulps off the correctly rounded result (Vulkan allows 2.5 ulp for a
// division, 4.5 for 1 / inversesqrt; C++'s is the correctly rounded one).
class SkewedDevice : public UlpSkew {
 public:
  explicit SkewedDevice(unsigned seed) : UlpSkew(seed) {}

  ShadowMotion pixel(const ShadowRay& r, const std::vector<InstanceMotion>& to_previous, const View& view,
                     const View& prev_view) {
    ShadowMotion out;
    if (r.receiver_instance == kInvalidId || r.blocker_instance == kInvalidId || r.light_instance == kInvalidId)
      return out;
    glm::vec3 s_hat, s_hat_prev;
    if (!intersect(r.light, r.blocker, r.receiver, r.receiver_normal, s_hat)) return out;
    const InstanceMotion& T = to_previous[r.receiver_instance];
    const glm::vec3 l_prev = glm::vec3(to_previous[r.light_instance].to_previous * glm::vec4(r.light, 1.0f));
    const glm::vec3 b_prev = glm::vec3(to_previous[r.blocker_instance].to_previous * glm::vec4(r.blocker, 1.0f));
    const glm::vec3 s_prev = glm::vec3(T.to_previous * glm::vec4(r.receiver, 1.0f));
    if (!intersect(l_prev, b_prev, s_prev, T.normal_to_previous * r.receiver_normal, s_hat_prev)) return out;
    const glm::vec3 x_prev = project(prev_view, s_hat_prev);
    if (x_prev.z < prev_view.znear) return out;
    out.motion = glm::vec2(x_prev) - glm::vec2(project(view, s_hat));
    out.valid = true;
    return out;
  }

 private:
  bool intersect(const glm::vec3& l, const glm::vec3& b, const glm::vec3& s, const glm::vec3& n, glm::vec3& point) {
    const glm::vec3 lb = b - l;
    const float n_dot_lb = glm::dot(n, lb);
    if (std::abs(n_dot_lb) <= kShadowParallelCosine * skew(glm::length(lb), 4)) return false;
    const float t = skew(glm::dot(n, s - l) / n_dot_lb, 2);
    if (!(t > 1.0f)) return false;
    point = l + t * lb;
    return true;
  }

};

}  // namespace

TEST_CASE("the shadow motion bound holds for a simulated device whose divisions and square roots are ulps off") {
  // No Vulkan needed: this checks the banner's derivation, where lavapipe (exact) cannot.
  std::mt19937 rng(7);
  const RenderedFrame r = random_inputs(rng, 41, 29);
  const FrameGeometry& g = r.geometry;
  const ShadowRayLayers rays(r.frame);
  const std::vector<InstanceMotion> to_previous = instance_to_previous(g.pose, g.prev_pose);
  const std::vector<ShadowMotion> golden = shadow_motion(g, r.frame);
  double worst_ratio = 0.0;
  size_t compared = 0, differ = 0;
  for (unsigned seed = 0; seed < 8; ++seed) {
    SkewedDevice device(seed);
    for (size_t i = 0; i < golden.size(); ++i) {
      const Expected e = expected_at(rays.at(i), to_previous, g.view, g.prev_view);
      const ShadowMotion m = device.pixel(rays.at(i), to_previous, g.view, g.prev_view);
      if (e.decision == Decision::NearThreshold) continue;
      REQUIRE(m.valid == golden[i].valid);
      if (!m.valid) continue;
      ++compared;
      const double d = std::max(diff(m.motion.x, golden[i].motion.x), diff(m.motion.y, golden[i].motion.y));
      differ += d > 0.0;
      CHECK(d <= e.bound);
      if (d > 0.0) worst_ratio = std::max(worst_ratio, d / e.bound);
    }
  }
  WARN("simulated device: " << differ << " of " << compared << " vectors differ, at most " << worst_ratio
                            << " of their bound");
  CHECK(differ > compared / 2);  // the simulation does move the vectors
}

TEST_CASE("the shadow motion port matches shadow_motion on rendered frames") {
  const auto context = validated_context();
  const int w = 64, h = 36;
  int valid = 0;
  for (const auto& [name, index] : {std::pair<std::string, int>{"fence", 10}, {"falling-light", 10}}) {
    INFO(name << " frame " << index);
    const RenderedFrame r = render(name, index, w, h);
    shadow_motion_vulkan(*context, r.geometry, r.frame);  // warm-up: lavapipe compiles
    double shadow_ms = 0.0;
    Counts c;
    check_shadow_port(*context, r.geometry, r.frame, c, &shadow_ms);
    CHECK(c.near_threshold == 0);
    valid += c.valid;
    WARN("motion_shadow dispatch " << shadow_ms << " ms (" << w << "x" << h << ") on " << context->device_name());
    CHECK(shadow_ms > 0.0);
  }
  CHECK(valid > 50);  // moving shadows on both
  check_no_validation_messages(*context);
}

TEST_CASE("the shadow motion port matches shadow_motion on random rays of an odd size") {
  const auto context = validated_context();
  std::mt19937 rng(7);
  const RenderedFrame r = random_inputs(rng, 41, 29);
  Counts c;
  check_shadow_port(*context, r.geometry, r.frame, c);
  CHECK(c.near_threshold == 0);
  CHECK(c.valid > 200);
  CHECK(c.invalid > 200);
  // Every path of shadow_motion_pixel is taken somewhere.
  CHECK(c.not_in_shadow > 0);
  CHECK(c.parallel > 0);
  CHECK(c.not_beyond > 0);
  CHECK(c.behind_camera > 0);
  // No instances at all: every id is beyond the (empty) list: the port reads no instance, every pixel invalid.
  // (The golden pass's precondition is an id below the count; it is not run.)
  FrameGeometry none = r.geometry;
  none.pose.instance_to_world.clear(), none.prev_pose.instance_to_world.clear();
  for (const ShadowMotion& m : shadow_motion_vulkan(*context, none, r.frame)) CHECK_FALSE(m.valid);
  check_no_validation_messages(*context);
}

TEST_CASE("the shadow motion port rejects what the golden pass rejects") {
  const auto context = validated_context();
  std::mt19937 rng(3);
  RenderedFrame r = random_inputs(rng, 12, 10);
  FrameGeometry other = r.geometry;
  other.vis.width = 11;
  CHECK_THROWS_AS(shadow_motion_vulkan(*context, other, r.frame), Error);
  Frame missing(12, 10);
  CHECK_THROWS_AS(shadow_motion_vulkan(*context, r.geometry, missing), Error);
}
