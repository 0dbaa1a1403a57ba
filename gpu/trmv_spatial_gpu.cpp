// The Vulkan ports of TRMV's spatial filter and clean-up. See trmv_spatial_gpu.h; the shaders are
// filters/trmv/spatial.comp and filters/trmv/cleanup.comp.
#include "gpu/trmv_spatial_gpu.h"

#include "core/error.h"
#include "filters/trmv/spatial.h"
#include "gpu/svgf_planes.h"
#include "gpu/svgf_shaders.h"

#include <memory>
#include <string>

namespace rtdr {

namespace {

// The ports' own check: a radius the shader's loop can run.
void check_radius(int radius, const char* what) {
  if (radius < 0) throw Error(std::string(what) + ": the radius must be >= 0, got " + std::to_string(radius));
}

// Channel w of record i of a buffer of 4-float records (pack_rgb wrote 0 there).
void set_w(GpuBuffer& records, size_t i, float w) { records.data()[4 * i + 3] = w; }

// The G-buffer planes the 1-D passes read: surface records and depth gradients.
struct Guides {
  std::unique_ptr<GpuBuffer> surface, depth_grad;
};

Guides pack_guides(VulkanContext& context, const SurfacePlanes& s, int w, int h) {
  Guides g{plane_buffer(context, w, h, TexelFormat::RGBA32F), plane_buffer(context, w, h, TexelFormat::RG32F)};
  pack_surface(s, *g.surface);
  pack_vec2(s.depth_grad, *g.depth_grad);
  return g;
}

}  // namespace

RgbPlane trmv_spatial_vulkan(VulkanContext& context, const RgbPlane& c, const SurfacePlanes& s, int radius,
                             float sigma, const SvgfParams& edges, double* ms, const FloatPlane& sigma_x,
                             const FloatPlane& sigma_y) {
  const int w = c.width, h = c.height;
  check_trmv_surface_sizes(w, h, s, "trmv spatial filter");
  check_radius(radius, "trmv_spatial_vulkan");
  const bool per_axis = sigma_x.width != 0;
  if (per_axis && (!has_size(sigma_x, w, h) || !has_size(sigma_y, w, h)))
    throw Error("trmv spatial filter: the std planes are not the frame's size");
  if (c.data.empty()) return RgbPlane(w, h);
  const Guides g = pack_guides(context, s, w, h);
  const auto input = plane_buffer(context, w, h, TexelFormat::RGBA32F),
             rows = plane_buffer(context, w, h, TexelFormat::RGBA32F),
             out = plane_buffer(context, w, h, TexelFormat::RGBA32F),
             axis_sigma = plane_buffer(context, per_axis ? w : 1, per_axis ? h : 1, TexelFormat::RG32F);
  pack_rgb(c, *input);
  if (per_axis)
    for (size_t i = 0; i < sigma_x.data.size(); ++i)
      axis_sigma->data()[2 * i] = sigma_x.data[i], axis_sigma->data()[2 * i + 1] = sigma_y.data[i];
  // Horizontal, then vertical: the separable form of the 31x31 joint bilateral [TRMV21 Sec. 5]
  // (trmv_spatial_pass), `sigma` everywhere or each pixel's std per axis.
  const uint32_t mode = per_axis ? 2u : 0u;
  const TrmvSpatialPush horizontal = trmv_spatial_push(w, h, kTrmvHorizontal, radius, mode, sigma, edges);
  const TrmvSpatialPush vertical = trmv_spatial_push(w, h, kTrmvVertical, radius, mode, sigma, edges);
  const SvgfShaders shaders(context);
  ComputeBatch batch(context, 2);
  shaders.trmv_spatial(batch, {input.get()}, *g.surface, *g.depth_grad, {rows.get()}, horizontal, "trmv_spatial",
                       axis_sigma.get());
  shaders.trmv_spatial(batch, {rows.get()}, *g.surface, *g.depth_grad, {out.get()}, vertical, "trmv_spatial",
                       axis_sigma.get());
  batch.run();
  batch.total_time(ms);
  return unpack_rgb(*out, w, h);
}

TrmvCleanupOutput trmv_cleanup_vulkan(VulkanContext& context, const TrmvTemporalOutput& temporal,
                                      const FloatPlane& alpha_v, const SurfacePlanes& s, const TrmvParams& params,
                                      const SvgfParams& edges, double* ms) {
  const int w = temporal.color.width, h = temporal.color.height;
  check_trmv_cleanup_sizes(temporal, alpha_v);  // trmv_cleanup_pass's checks
  check_trmv_surface_sizes(w, h, s, "trmv spatial filter");
  const int radius = (params.cleanup_size - 1) / 2;
  check_radius(radius, "trmv_cleanup_vulkan");
  TrmvCleanupOutput out{RgbPlane(w, h), FloatPlane(w, h), FloatPlane(w, h), FloatPlane(w, h)};
  if (out.sigma.data.empty()) return out;

  const bool has_alpha_v = alpha_v.width != 0;
  const auto color = plane_buffer(context, w, h, TexelFormat::RGBA32F),
             fetched_alpha_v = plane_buffer(context, w, h, TexelFormat::RGBA32F),
             clamped = plane_buffer(context, w, h, TexelFormat::RGBA32F);
  pack_rgb(temporal.color, *color);
  // (cbar_{i-1}, alpha^V): alpha^V in w where there is one.
  pack_rgb(temporal.fetched, *fetched_alpha_v);
  if (has_alpha_v)
    for (size_t i = 0; i < alpha_v.data.size(); ++i) set_w(*fetched_alpha_v, i, alpha_v.data[i]);
  pack_rgb(temporal.clamped, *clamped);
  const Guides g = pack_guides(context, s, w, h);
  // (cbar_i, std), then after each 1-D pass (c', std); and (w_A, w_C, std, 0).
  const auto color_sigma = plane_buffer(context, w, h, TexelFormat::RGBA32F),
             rows = plane_buffer(context, w, h, TexelFormat::RGBA32F),
             filtered = plane_buffer(context, w, h, TexelFormat::RGBA32F),
             weights = plane_buffer(context, w, h, TexelFormat::RGBA32F);

  const TrmvCleanupPush push = trmv_cleanup_push(uint32_t(w), uint32_t(h), has_alpha_v, params);
  // Eq. 7-8 at every pixel, then the 9x9 separable joint bilateral with each pixel's std (trmv_cleanup_pass).
  const TrmvSpatialPush horizontal = trmv_spatial_push(w, h, kTrmvHorizontal, radius, 1u, 0.0f, edges);
  const TrmvSpatialPush vertical = trmv_spatial_push(w, h, kTrmvVertical, radius, 1u, 0.0f, edges);
  const SvgfShaders shaders(context);
  ComputeBatch batch(context, 3);
  shaders.trmv_cleanup(batch, *color, *fetched_alpha_v, *clamped, *color_sigma, *weights, push);
  shaders.trmv_spatial(batch, {color_sigma.get()}, *g.surface, *g.depth_grad, {rows.get()}, horizontal,
                       "trmv_cleanup");
  shaders.trmv_spatial(batch, {rows.get()}, *g.surface, *g.depth_grad, {filtered.get()}, vertical, "trmv_cleanup");
  batch.run();
  batch.total_time(ms);

  out.color = unpack_rgb(*filtered, w, h);
  out.w_a = unpack_channel(*weights, w, h, 4, 0);
  out.w_c = unpack_channel(*weights, w, h, 4, 1);
  out.sigma = unpack_channel(*weights, w, h, 4, 2);
  return out;
}

}  // namespace rtdr
