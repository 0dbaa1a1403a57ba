// Tests of gpu/trmv_spatial_gpu.cpp's trmv_spatial_vulkan: the Vulkan port (filters/trmv/spatial.comp, dispatched
// horizontally, then vertically) against the golden trmv_spatial_pass() (filters/trmv/spatial.cpp) on random
// planes and on a rendered frame of the pillars scene (its visibility as (V, V, V), and its indirect diffuse light),
// for the paper's 31x31 with std 5, a 7x7 with std 1.5, radius 0 and std 0, with the validation layer on. Skipped,
// with a message, where no Vulkan device exists.
//
// Exact on every device: the pixels without a surface, and the whole plane for std 0 or radius 0 (each 1-D pass
// copies them). Elsewhere, with e = 2^-23 (an ulp of a float x is at most e |x|), C the largest input value (the
// inputs are >= 0), r the radius and n = 2r + 1 its taps, and
//   D = ln 2 sigma_n 2^-21 + 20 e   (the most one tap's weight G w_z w_n may differ by),
// |gpu - golden| <= 2 (2r D + (4n + 4) e) C. About 1.1e-2 for r = 15, sigma_n = 128 and C = 4.
// Derivation. Both sides do the same fp32 operations in the same order: the shader marks every result `precise`
// (no fma contraction, no reordering), and the C++ is built without fma (no -march, no -ffp-contract), so every
// test (covered, inside, sigma > 0), the tap offsets, k^2, 2 sigma^2, the depth weight's denominator and the
// normals' cosine are bit-identical. What differs: the divisions (Vulkan allows 2.5 ulp, C++ rounds correctly:
// 3 e apart, relative), and exp and pow, which libm gives within 1 ulp, and Vulkan within (3 + 2|x|) ulp (exp) and
// as exp2(y log2 x) (pow, log2 within 2^-21 absolute on [0.5, 2], else 3 ulp).
//   G = exp(-x), x = k^2 / (2 sigma^2) >= 0: x differs by 3 e x, so |dG| <= e^-x (3 x + 3 + 2 x + 1) e <= 4.1 e
//   (the maximum over x, at x = 0.2). w_z = exp(-a_z) likewise: 4.1 e.
//   w_n = 2^-t, t = sigma_n |log2 cos|: t differs by at most sigma_n 2^-21 + 4 e t, so
//   |dw_n| <= 2^-t (ln 2 (sigma_n 2^-21 + 4 e t) + (4 + 2 t) e) <= ln 2 sigma_n 2^-21 + 4.6 e.
//   w = (G w_z) w_n, all three in [0, 1]: the sum of the three, plus two roundings on each side: D above.
//   One 1-D pass: c'(p) = S / W with W = 1 + sum w >= 1 and S = c(p) + sum w c(q). With exact sums,
//   c' - c'' = sum (w - w'') (c(q) - c'') / W, so at most C sum |dw| <= 2r D C (the values lie in [0, C]). The
//   rounding of the n-term sums and products, at most 2n e C on each side, and the division (3 e C): (4n + 3) e C;
//   we round that up to (4n + 4) e C for the (1 + e) factors left out.
//   The vertical pass: a weighted mean of the horizontal pass's outputs inherits their difference and adds its
//   own, so the two passes together double it.
// sigma_n 2^-21 (Vulkan's log2) dominates; a device whose exp and log2 are within a few ulp, such as lavapipe,
// comes far below it (the measured worst differences are printed). A device that flushes subnormal floats to zero
// moves each result by under 2^-126, far below e C here.
#include "gpu/trmv_spatial_gpu.h"

#include "gpu/svgf_planes.h"
#include "gpu/svgf_shaders.h"

#include "core/error.h"
#include "filters/trmv/spatial.h"
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

// The banner's bound of the two 1-D passes, radius r, for inputs of largest value C (`cmax`).
double derived_bound(int radius, double sigma_n, double cmax) { return bilateral_bound(radius, sigma_n, cmax, 20.0); }

// The pixels that pass through (no surface) differ by nothing, on every device.
size_t uncovered_mismatches(const RgbPlane& a, const RgbPlane& b, const SurfacePlanes& s) {
  size_t n = 0;
  for (size_t i = 0; i < a.data.size(); ++i) n += s.mesh.data[i] == kInvalidId && a.data[i] != b.data[i];
  return n;
}

TrmvParams params_with(int radius, float sigma) {
  TrmvParams p;
  p.spatial_radius = radius;
  p.spatial_sigma = sigma;
  return p;
}

// Port and golden pass on the same inputs: exact where the banner says so, else within its bound.
void check_port(VulkanContext& context, const RgbPlane& c, const SurfacePlanes& s, const TrmvParams& params,
                const SvgfParams& edges, double* ms = nullptr) {
  const RgbPlane golden = trmv_spatial_pass(c, s, params.spatial_radius, params.spatial_sigma, edges);
  const RgbPlane gpu = trmv_spatial_vulkan(context, c, s, params.spatial_radius, params.spatial_sigma, edges, ms);
  REQUIRE(gpu.width == golden.width);
  REQUIRE(gpu.height == golden.height);
  const bool identity = params.spatial_radius == 0 || !(params.spatial_sigma > 0.0f);
  const double bound = identity ? 0.0 : derived_bound(params.spatial_radius, edges.sigma_n, max_value(c));
  const double measured = max_difference(gpu, golden);
  WARN("radius " << params.spatial_radius << ", std " << params.spatial_sigma << ": measured max |gpu - golden| "
                 << measured << " (bound " << bound << ") on " << context.device_name());
  CHECK(measured <= bound);
  CHECK(uncovered_mismatches(gpu, golden, s) == 0);
  if (identity) CHECK(max_difference(gpu, c) == 0.0);
}

}  // namespace

TEST_CASE("the TRMV spatial port matches trmv_spatial_pass on random planes of an odd size") {
  const auto context = validated_context();
  std::mt19937 rng(31);
  const int w = 41, h = 29;  // a multiple of neither workgroup shape: the last tiles overhang
  const SurfacePlanes s = random_bilateral_surface(rng, w, h, true);
  const RgbPlane c = random_plane(rng, w, h, 0.0f, 4.0f);
  const SvgfParams edges;
  // The paper's 31x31 with std 5, a 7x7, and the two identities: std 0 and radius 0.
  for (const auto& [radius, sigma] :
       {std::pair{15, 5.0f}, std::pair{3, 1.5f}, std::pair{15, 0.0f}, std::pair{0, 5.0f}}) {
    INFO("radius " << radius << ", std " << sigma);
    double ms = 0.0;
    check_port(*context, c, s, params_with(radius, sigma), edges, &ms);
    WARN("trmv_spatial, two dispatches " << ms << " ms (" << w << "x" << h << ") on " << context->device_name());
    CHECK(ms > 0.0);
  }
  // Looser normals: more of the weight w_n's range.
  SvgfParams soft;
  soft.sigma_n = 4.0f;
  soft.sigma_z = 4.0f;
  check_port(*context, c, s, params_with(15, 5.0f), soft, nullptr);
  // A std per pixel and axis (the penumbra filter, filters/trmv/penumbra.h), some 0 (that axis the identity).
  FloatPlane sigma_x(w, h), sigma_y(w, h);
  std::uniform_real_distribution<float> std_dev(0.0f, 5.0f);
  for (size_t i = 0; i < sigma_x.data.size(); ++i) {
    sigma_x.data[i] = i % 11 == 0 ? 0.0f : std_dev(rng);
    sigma_y.data[i] = std_dev(rng);
  }
  const RgbPlane golden = trmv_spatial_pass(c, s, 15, sigma_x, sigma_y, edges);
  const RgbPlane gpu = trmv_spatial_vulkan(*context, c, s, 15, 5.0f, edges, nullptr, sigma_x, sigma_y);
  const double measured = max_difference(gpu, golden), bound = derived_bound(15, edges.sigma_n, max_value(c));
  WARN("std per pixel and axis: measured max |gpu - golden| " << measured << " (bound " << bound << ")");
  CHECK(measured <= bound);
  CHECK(uncovered_mismatches(gpu, golden, s) == 0);
  check_no_validation_messages(*context);
}

TEST_CASE("the TRMV spatial port matches trmv_spatial_pass on a rendered pillars frame") {
  const auto context = validated_context();
  const int w = 64, h = 36;
  const Frame frame = render_frame(load_scene("pillars"), 4, w, h, {});
  const SurfacePlanes s = SurfacePlanes::from_frame(frame);
  // The method filters visibility as a scalar plane; the port takes it as (V, V, V).
  const FloatPlane& v = frame.float_channel("direct.visibility");
  RgbPlane visibility(w, h);
  for (size_t i = 0; i < v.data.size(); ++i) visibility.data[i] = glm::vec3(v.data[i]);
  const SvgfParams edges;
  for (const RgbPlane& c : {visibility, rgb_plane(frame, "indirect.diffuse")}) {
    check_port(*context, c, s, params_with(15, 5.0f), edges);
    check_port(*context, c, s, params_with(3, 1.5f), edges);
  }
  // The port's visibility, channel by channel, is the golden scalar pass's.
  const FloatPlane golden = trmv_spatial_pass(v, s, 15, 5.0f, edges);
  const RgbPlane gpu = trmv_spatial_vulkan(*context, visibility, s, 15, 5.0f, edges);
  double worst = 0.0;
  for (size_t i = 0; i < golden.data.size(); ++i)
    for (int k = 0; k < 3; ++k) worst = std::max(worst, double(std::abs(gpu.data[i][k] - golden.data[i])));
  CHECK(worst <= derived_bound(15, edges.sigma_n, 1.0));
  check_no_validation_messages(*context);
}

TEST_CASE("the TRMV spatial port rejects planes of different sizes and a negative radius") {
  const auto context = validated_context();
  const SurfacePlanes s = blank_surface(12, 12);
  CHECK_THROWS_AS(trmv_spatial_vulkan(*context, RgbPlane(12, 11), s, 15, 5.0f, SvgfParams{}), Error);
  CHECK_THROWS_AS(trmv_spatial_vulkan(*context, RgbPlane(12, 12), s, -1, 5.0f, SvgfParams{}), Error);
}

// The Vulkan TRMV filters its three components side by side, one dispatch per axis (filters/trmv/spatial_shared.h's
// kTrmvSpatialComponentsConstant, gpu/trmv_vulkan.cpp): each plane then gets exactly what it gets alone, since it
// does the same operations in the same order and only shares the taps' w_z and w_n. With one std everywhere (the
// spatial filter) and with each plane's own std per pixel (the clean-up's).
TEST_CASE("three planes filtered side by side give each plane's result alone, bit for bit") {
  const auto context = validated_context();
  std::mt19937 rng(11);
  const int w = 37, h = 23;
  const SurfacePlanes s = random_bilateral_surface(rng, w, h, true);
  const auto surface = plane_buffer(*context, w, h, TexelFormat::RGBA32F),
             depth_grad = plane_buffer(*context, w, h, TexelFormat::RG32F);
  pack_surface(s, *surface);
  pack_vec2(s.depth_grad, *depth_grad);
  std::unique_ptr<GpuBuffer> in[3], rows[3], out[3], alone[3];
  std::uniform_real_distribution<float> std_dev(0.0f, 3.0f);
  for (int m = 0; m < 3; ++m) {
    in[m] = plane_buffer(*context, w, h, TexelFormat::RGBA32F);
    rows[m] = plane_buffer(*context, w, h, TexelFormat::RGBA32F);
    out[m] = plane_buffer(*context, w, h, TexelFormat::RGBA32F);
    alone[m] = plane_buffer(*context, w, h, TexelFormat::RGBA32F);
    pack_rgb(random_plane(rng, w, h, 0.0f, 4.0f), *in[m]);
    // Each plane's own std per pixel, some 0 (the identity), read where has_sigma_plane.
    for (size_t i = 0; i < size_t(w) * size_t(h); ++i)
      in[m]->data()[4 * i + 3] = m == 1 && i % 7 == 0 ? 0.0f : std_dev(rng);
  }
  const SvgfShaders shaders(*context);
  for (const bool sigma_plane : {false, true}) {
    INFO("per-pixel std " << sigma_plane);
    const TrmvSpatialPush horizontal = trmv_spatial_push(w, h, kTrmvHorizontal, 4, sigma_plane, 2.5f, SvgfParams{});
    const TrmvSpatialPush vertical = trmv_spatial_push(w, h, kTrmvVertical, 4, sigma_plane, 2.5f, SvgfParams{});
    ComputeBatch batch(*context, 8);
    shaders.trmv_spatial(batch, {in[0].get(), in[1].get(), in[2].get()}, *surface, *depth_grad,
                         {rows[0].get(), rows[1].get(), rows[2].get()}, horizontal);
    shaders.trmv_spatial(batch, {rows[0].get(), rows[1].get(), rows[2].get()}, *surface, *depth_grad,
                         {out[0].get(), out[1].get(), out[2].get()}, vertical);
    batch.run();
    for (int m = 0; m < 3; ++m) {
      ComputeBatch one(*context, 2);
      shaders.trmv_spatial(one, {in[m].get()}, *surface, *depth_grad, {rows[m].get()}, horizontal);
      shaders.trmv_spatial(one, {rows[m].get()}, *surface, *depth_grad, {alone[m].get()}, vertical);
      one.run();
      CHECK(out[m]->download() == alone[m]->download());
    }
  }
  ComputeBatch two(*context, 1);
  CHECK_THROWS_AS(shaders.trmv_spatial(two, {in[0].get(), in[1].get()}, *surface, *depth_grad,
                                       {out[0].get(), out[1].get()}, trmv_spatial_push(w, h, kTrmvHorizontal, 4,
                                                                                        false, 2.5f, SvgfParams{})),
                  Error);
  check_no_validation_messages(*context);
}
