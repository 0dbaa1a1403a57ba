// The TRMV filter on a Vulkan device. See trmv_vulkan.h; the golden pipeline it follows is filters/trmv/trmv.cpp.
#include "gpu/trmv_vulkan.h"

#include "core/error.h"
#include "filters/passes.h"
#include "filters/svgf/tonemap.h"
#include "filters/trmv/atrous.h"
#include "filters/trmv/spatial.h"
#include "filters/trmv/trmv.h"
#include "gpu/svgf_planes.h"
#include "gpu/trmv_temporal_gpu.h"

#include <chrono>
#include <string>

namespace rtdr {

namespace {

using PlanePtr = std::unique_ptr<GpuBuffer>;
using Clock = std::chrono::steady_clock;

enum Component { kVisibility = 0, kDiffuse = 1, kGlossy = 2 };

// Commands per frame: the falloff; the visibility's spatial filter (two 1-D dispatches); per component the temporal
// blend and the clean-up's strength; the clean-up's two 1-D dispatches; per component a copy of the history when it
// is taken after the clean-up, and the copy of the result into readback memory.
constexpr uint32_t kCommandsPerFrame = 1 + 2 + 3 * 2 + 2 + 3 * 2;

double ms_since(Clock::time_point t0) { return std::chrono::duration<double, std::milli>(Clock::now() - t0).count(); }

}  // namespace

// Every device plane. [parity] pairs alternate between frames: [frame parity] is written this frame, the other holds
// the previous frame's. [k]: the component (Component).
struct TrmvVulkan::Buffers {
  int width, height;
  // The G-buffer: (n, z) records, id.mesh, positions and geometric normals per parity (the previous ones are the
  // temporal pass's and the falloff's); depth gradients and the surface motion.
  PlanePtr surface[2], mesh[2], position[2], geonormal[2], depth_grad, surface_motion;
  // Per component: the noisy input (visibility as (V, V, V)), its (motion, code) records, c~_i, the temporal pass's
  // (cbar_i, alpha) (when the history is taken after the clean-up), the fetched history with the alpha-plane value,
  // the clamped history, the clean-up's (cbar_i, std) and (w_A, w_C, std), the cleaned colour and its readback
  // copy; the history (cbar_i, alpha) per parity.
  PlanePtr noisy[3], vector[3], filtered[3], temporal[3], fetched[3], clamped[3], color_sigma[3], weights[3],
      cleaned[3], readback[3], history[3][2];
  // The visibility's splatted shadow motion and where it landed (the falloff's), its std per axis (the penumbra
  // filter's), its (theta, alpha^V), the diffuse light's re-shaded history (r, g, b, valid), the 1-D passes'
  // intermediates (per component), and one unread texel of each kind for absent planes.
  PlanePtr shadow_motion, shadow_landed, axis_sigma, falloff, reshaded, rows[3], no_records, no_pairs;

  Buffers(VulkanContext& context, int w, int h) : width(w), height(h) {
    const auto rgba = [&] { return plane_buffer(context, w, h, TexelFormat::RGBA32F); };
    const auto rg = [&] { return plane_buffer(context, w, h, TexelFormat::RG32F); };
    for (int s = 0; s < 2; ++s) {
      surface[s] = rgba(), position[s] = rgba(), geonormal[s] = rgba();
      mesh[s] = plane_buffer(context, w, h, TexelFormat::R32UI);
    }
    depth_grad = rg(), surface_motion = rg();
    for (int k = 0; k < 3; ++k) {
      noisy[k] = rgba(), vector[k] = rgba(), filtered[k] = rgba(), temporal[k] = rgba(), fetched[k] = rgba();
      clamped[k] = rgba(), color_sigma[k] = rgba(), weights[k] = rgba(), cleaned[k] = rgba(), rows[k] = rgba();
      readback[k] = std::make_unique<GpuBuffer>(context, cleaned[k]->floats(), TexelFormat::None, Memory::Readback);
      for (PlanePtr& history : history[k]) history = rgba();
    }
    shadow_motion = rg(), axis_sigma = rg(), falloff = rg(), reshaded = rgba();
    shadow_landed = plane_buffer(context, w, h, TexelFormat::R32UI);
    no_records = plane_buffer(context, 1, 1, TexelFormat::RGBA32F);
    no_pairs = plane_buffer(context, 1, 1, TexelFormat::RG32F);
  }
};

TrmvVulkan::TrmvVulkan(VulkanContext& context, const MethodParams& params)
    : VulkanMethod(context, kCommandsPerFrame),
      context_(context),
      params_(params),
      shaders_(context),
      cone_layout_(make_cone_layout(params.trmv.cone_half_angle)) {
  validate(params_.trmv);
  validate(params_.svgf);
  validate(params_.tonemap);
}

TrmvVulkan::~TrmvVulkan() = default;

void TrmvVulkan::reset() {
  frames_ = 0;
  cones_ = {};
}

InputChannels TrmvVulkan::inputs() const { return trmv_input_channels(); }

std::vector<std::string> TrmvVulkan::dump_channels() const { return trmv_dump_channels(params_.trmv); }

void TrmvVulkan::record_components(const GpuBuffer* alpha_v, bool per_axis_sigma) {
  Buffers& b = *buffers_;
  const TrmvParams& p = params_.trmv;
  const SvgfParams& edges = params_.svgf;
  const TrmvWindows win = trmv_windows(p, b.height);
  const int w = b.width, h = b.height, cur = frames_ & 1, prev = cur ^ 1;
  const bool has_history = frames_ > 0;
  const auto planes = [](const PlanePtr (&buffers)[3]) {
    return std::vector<const GpuBuffer*>{buffers[0].get(), buffers[1].get(), buffers[2].get()};
  };
  // 1. The visibility's spatial filter, horizontal then vertical: c~_i [TRMV21 Sec. 5], the fixed 31x31 or the
  //    penumbra's std per pixel and axis (penumbra.h).
  const uint32_t mode = per_axis_sigma ? 2u : 0u;
  shaders_.trmv_spatial(batch_, {b.noisy[kVisibility].get()}, *b.surface[cur], *b.depth_grad,
                        {b.rows[kVisibility].get()},
                        trmv_spatial_push(w, h, kTrmvHorizontal, win.shadow_radius, mode, win.shadow_sigma, edges),
                        "trmv_spatial", b.axis_sigma.get());
  shaders_.trmv_spatial(batch_, {b.rows[kVisibility].get()}, *b.surface[cur], *b.depth_grad,
                        {b.filtered[kVisibility].get()},
                        trmv_spatial_push(w, h, kTrmvVertical, win.shadow_radius, mode, win.shadow_sigma, edges),
                        "trmv_spatial", b.axis_sigma.get());
  // The temporal pass's output: next frame's history unless that is taken after the clean-up
  // (history_after_cleanup).
  const auto temporal = [&](int k) -> const GpuBuffer& {
    return p.history_after_cleanup != 0 ? *b.temporal[k] : *b.history[k][cur];
  };
  TrmvParams cleanup = p;
  cleanup.cleanup_size = 2 * win.cleanup_radius + 1;
  for (const int k : {kVisibility, kDiffuse, kGlossy}) {
    // 2-3. The history along the component's motion, tested, clamped, blended [TRMV21 Eq. 2, Sec. 5]; alpha^V for
    //      the visibility.
    const GpuBuffer* alpha = k == kVisibility ? alpha_v : nullptr;
    const bool reshaded = k == kDiffuse && trmv_uses_dual(p.motion) && p.cones != 0;
    const TrmvTemporalPlanes in{b.filtered[k].get(),
                                b.mesh[cur].get(),
                                b.surface[cur].get(),
                                b.depth_grad.get(),
                                b.vector[k].get(),
                                reshaded ? b.reshaded.get() : b.no_records.get(),
                                b.history[k][prev].get(),
                                b.mesh[prev].get(),
                                b.surface[prev].get(),
                                alpha ? alpha : b.no_pairs.get()};
    shaders_.trmv_temporal(batch_, in, temporal(k), *b.fetched[k], *b.clamped[k],
                           trmv_temporal_push(uint32_t(w), uint32_t(h), has_history ? uint32_t(w) : 0u,
                                              has_history ? uint32_t(h) : 0u, reshaded, alpha != nullptr, p, edges));
    // 4. The clean-up's strength, as Eq. 4 and the clamp moved the blend [TRMV21 Eq. 7-8]; alpha^V rides in the
    //    fetched history's w.
    shaders_.trmv_cleanup(batch_, temporal(k), *b.fetched[k], *b.clamped[k], *b.color_sigma[k], *b.weights[k],
                          trmv_cleanup_push(uint32_t(w), uint32_t(h), alpha != nullptr, cleanup));
  }
  // Then its 9x9 (scaled) bilateral with each pixel's std, the three components side by side.
  const int radius = win.cleanup_radius;
  shaders_.trmv_spatial(batch_, planes(b.color_sigma), *b.surface[cur], *b.depth_grad, planes(b.rows),
                        trmv_spatial_push(w, h, kTrmvHorizontal, radius, 1u, 0.0f, edges), "trmv_cleanup");
  shaders_.trmv_spatial(batch_, planes(b.rows), *b.surface[cur], *b.depth_grad, planes(b.cleaned),
                        trmv_spatial_push(w, h, kTrmvVertical, radius, 1u, 0.0f, edges), "trmv_cleanup");
  for (const int k : {kVisibility, kDiffuse, kGlossy}) {
    if (p.history_after_cleanup != 0) batch_.copy(*b.cleaned[k], *b.history[k][cur], "trmv_cleanup");
    // The result where the host reads it fast (compute.h's Memory::Readback).
    batch_.copy(*b.cleaned[k], *b.readback[k], kTransferPass);
  }
}

// The golden passes that have no port in this batch (trmv_vulkan.h): the penumbra and the splat, the motions'
// records, the diffuse light's a-trous, the glossy light's lobe filter and the cones; uploaded into `b`. Returns the
// re-shaded history (empty without the cones), for the dump.
RgbPlane TrmvVulkan::host_passes(const Frame& in, Buffers& b, const SurfacePlanes& surface, const TrmvWindows& win) {
  const TrmvParams& p = params_.trmv;
  const SvgfParams& edges = params_.svgf;
  const bool penumbra = p.shadow_filter == 1;
  TrmvSplatOutput& splat = host_.splat;
  splat = {};
  {
    const auto h0 = Clock::now();
    if (penumbra) host_.penumbra = trmv_penumbra_pass(TrmvPenumbraInputs::from_frame(in));
    if (trmv_uses_splat(p))
      splat = trmv_splat_pass(trmv_splat_planes(in, surface, penumbra ? host_.penumbra.width : FloatPlane()),
                              win.splat_size);
    if (penumbra) {
      FloatPlane &sigma_x = host_.sigma_x, &sigma_y = host_.sigma_y;
      trmv_penumbra_sigmas(splat.carried, host_.penumbra.metres, kTrmvPenumbraSigmaFloor, win.shadow_sigma, sigma_x,
                           sigma_y);
      for (size_t i = 0; i < sigma_x.data.size(); ++i)
        b.axis_sigma->data()[2 * i] = sigma_x.data[i], b.axis_sigma->data()[2 * i + 1] = sigma_y.data[i];
    }
    times_["trmv_splat"] += ms_since(h0);
  }
  const TrmvMotion vis_motion = trmv_visibility_motion(splat, surface.motion, p);
  pack_trmv_vector(vis_motion, *b.vector[kVisibility]);
  if (trmv_uses_shadow(p.motion)) {
    pack_vec2(vis_motion.motion, *b.shadow_motion);
    pack_ids(splat.landed, *b.shadow_landed);
  }
  const TrmvMotion diffuse_motion = trmv_diffuse_motion(in, surface.motion, p);
  pack_trmv_vector(diffuse_motion, *b.vector[kDiffuse]);
  pack_trmv_vector(trmv_glossy_motion(in, surface.motion, p), *b.vector[kGlossy]);
  {
    const auto a0 = Clock::now();
    const RgbPlane diffuse = rgb_plane(in, "indirect.diffuse");
    pack_rgb(p.diffuse_filter == 1 ? trmv_atrous_pass(diffuse, surface, win.atrous_levels, edges)
                                   : trmv_spatial_pass(diffuse, surface, win.shadow_radius, win.shadow_sigma, edges),
             *b.filtered[kDiffuse]);
    times_["trmv_atrous"] += ms_since(a0);
    const auto r0 = Clock::now();
    const RgbPlane glossy = rgb_plane(in, "indirect.glossy");
    pack_rgb(p.glossy_filter == 1
                 ? trmv_reflection_pass(glossy, surface, TrmvFootprint::from_frame(in), win.glossy_radius, edges)
                 : trmv_spatial_pass(glossy, surface, win.shadow_radius, win.shadow_sigma, edges),
             *b.filtered[kGlossy]);
    times_["trmv_reflection"] += ms_since(r0);
  }
  // The cone re-shading [TRMV21 Sec. 4.3, Eq. 9-11]: its re-shaded history is uploaded with the rest.
  seen_cones_ = std::move(cones_);  // replaced below by this frame's
  RgbPlane reshaded;
  if (trmv_uses_dual(p.motion) && p.cones != 0) {
    const auto r0 = Clock::now();
    const TrmvMotion dual_planes{xy_plane(in, "motion.dual"), in.uint_channel("motion.dual.valid"), {}, {}, {}};
    const TrmvConeFilter filter{p.diffuse_filter == 1, win.atrous_levels, win.shadow_radius, win.shadow_sigma};
    TrmvReshadeOutput r = trmv_reshade_pass(TrmvConeInputs::from_frame(in), surface, dual_planes, seen_cones_,
                                            cone_layout_, filter, p, edges);
    cones_ = std::move(r.history);
    reshaded = std::move(r.reshaded);
    TrmvMotion with_reshaded;
    with_reshaded.reshaded = reshaded;
    with_reshaded.reshaded_valid = std::move(r.reshaded_valid);
    pack_trmv_reshaded(with_reshaded, *b.reshaded);
    times_["trmv_reshade"] += ms_since(r0);
  }
  return reshaded;
}

Frame TrmvVulkan::filter(const Frame& in, Frame* dump) {
  times_.clear();
  const int w = in.width(), h = in.height();
  Buffers& b = frame_buffers(buffers_, context_, in, frames_ > 0);
  const TrmvParams& p = params_.trmv;
  const TrmvWindows win = trmv_windows(p, h);
  const int cur = frames_ & 1;

  // 1. Upload: the host packs this frame's planes into the device's records.
  const auto t0 = Clock::now();
  const SurfacePlanes surface = SurfacePlanes::from_frame(in);
  pack_surface(surface, *b.surface[cur]);
  pack_vec2(surface.depth_grad, *b.depth_grad);
  pack_vec2(surface.motion, *b.surface_motion);
  pack_ids(surface.mesh, *b.mesh[cur]);
  pack_rgb(xyz_plane(in, "position"), *b.position[cur]);
  pack_rgb(xyz_plane(in, "geonormal"), *b.geonormal[cur]);
  // The visibility, one value a pixel, travelling as (V, V, V).
  const FloatPlane& v = in.float_channel("direct.visibility");
  float* grey = b.noisy[kVisibility]->data();
  for (size_t i = 0; i < v.data.size(); ++i) {
    grey[4 * i] = grey[4 * i + 1] = grey[4 * i + 2] = v.data[i];
    grey[4 * i + 3] = 0.0f;
  }
  times_[kTransferPass] += ms_since(t0);

  // 2. On the host, the golden passes that have no port (filters/trmv/README.md); their results are uploaded.
  const RgbPlane reshaded = host_passes(in, b, surface, win);
  const bool shadow = trmv_uses_shadow(p.motion), dual = trmv_uses_dual(p.motion);

  // 3. One batch of dispatches, in TrmvFilter's order [TRMV21 Sec. 5].
  const uint32_t uw = uint32_t(w), uh = uint32_t(h);
  if (shadow) {  // alpha^V from the shadow motion and the previous positions [TRMV21 Eq. 4]
    const bool has_prev = frames_ > 0;
    const TrmvFalloffPlanes planes{b.position[cur].get(),      b.geonormal[cur].get(),  b.mesh[cur].get(),
                                   b.surface_motion.get(),     b.shadow_motion.get(),   b.shadow_landed.get(),
                                   b.position[cur ^ 1].get(),  b.geonormal[cur ^ 1].get(), b.mesh[cur ^ 1].get()};
    shaders_.trmv_falloff(batch_, planes, *b.falloff,
                          trmv_falloff_push(uw, uh, has_prev ? uw : 0u, has_prev ? uh : 0u, true, p));
  }
  record_components(shadow ? b.falloff.get() : nullptr, p.shadow_filter == 1);
  batch_.run(submits_);
  ++frames_;
  for (const auto& [pass, ms] : batch_.times()) times_[pass] += ms;

  // 4. Download the three cleaned components; remodulate and tone map on the host (trmv_vulkan.h).
  const auto t1 = Clock::now();
  const RgbPlane vis = unpack_rgb(*b.readback[kVisibility], w, h), diffuse = unpack_rgb(*b.readback[kDiffuse], w, h),
                 glossy = unpack_rgb(*b.readback[kGlossy], w, h);
  times_[kTransferPass] += ms_since(t1);
  RgbPlane color, display;
  time_pass("modulate", [&] { color = trmv_remodulate(in, vis, diffuse, glossy); });
  time_pass("tonemap", [&] { display = tonemap(color, params_.tonemap); });

  Frame out(w, h);
  out.source = in.source;
  set_rgb_plane(out, layer_name(layers::kColor), color);
  set_rgb_plane(out, layer_name(layers::kDisplay), display);  // no TAA: the tone-mapped colour
  if (dump) {
    if (dump->width() != w || dump->height() != h) *dump = Frame(w, h);
    this->dump(in, *dump, display);
    if (dual && p.cones != 0) dump_layer(dump, layers::kTrmvDiffuseReshaded, {}, -1, reshaded);
  }
  return out;
}

// TrmvFilter's dump layers, read from this frame's device planes (mapped; each component has its own).
void TrmvVulkan::dump(const Frame& in, Frame& out, const RgbPlane& tonemapped) const {
  using namespace layers;
  const Buffers& b = *buffers_;
  const TrmvParams& p = params_.trmv;
  const int w = in.width(), h = in.height(), cur = (frames_ - 1) & 1;
  const auto first = [&](const PlanePtr& plane) { return unpack_channel(*plane, w, h, 4, 0); };
  const auto rgb = [&](const PlanePtr& plane) { return unpack_rgb(*plane, w, h); };
  const auto temporal = [&](int k) -> const PlanePtr& {
    return p.history_after_cleanup != 0 ? b.temporal[k] : b.history[k][cur];
  };
  Frame* d = &out;
  if (p.shadow_filter == 1) {  // the host's penumbra and the std it gave each axis
    dump_layer(d, kTrmvPenumbraWidth, {}, -1, host_.penumbra.width);
    dump_layer(d, kTrmvSigmaX, {}, -1, host_.sigma_x);
    dump_layer(d, kTrmvSigmaY, {}, -1, host_.sigma_y);
  }
  if (trmv_uses_splat(p)) {  // the host's splat
    FloatPlane x(w, h), y(w, h), landed(w, h);
    for (size_t i = 0; i < x.data.size(); ++i) {
      x.data[i] = host_.splat.motion.data[i].x;
      y.data[i] = host_.splat.motion.data[i].y;
      landed.data[i] = float(host_.splat.landed.data[i]);
    }
    dump_layer(d, kTrmvSplatX, {}, -1, x);
    dump_layer(d, kTrmvSplatY, {}, -1, y);
    dump_layer(d, kTrmvSplatLanded, {}, -1, landed);
  }
  dump_layer(d, kTrmvVisibilitySpatial, {}, -1, first(b.filtered[kVisibility]));
  dump_layer(d, kTrmvDiffuseSpatial, {}, -1, rgb(b.filtered[kDiffuse]));
  dump_layer(d, kTrmvGlossySpatial, {}, -1, rgb(b.filtered[kGlossy]));
  if (trmv_uses_shadow(p.motion)) {
    dump_layer(d, kTrmvTheta, {}, -1, unpack_channel(*b.falloff, w, h, 2, 0));
    dump_layer(d, kTrmvAlphaV, {}, -1, unpack_channel(*b.falloff, w, h, 2, 1));
  }
  dump_layer(d, kTrmvWeightA, {}, -1, unpack_channel(*b.weights[kVisibility], w, h, 4, 0));
  dump_layer(d, kTrmvVisibilityTemporal, {}, -1, first(temporal(kVisibility)));
  dump_layer(d, kTrmvVisibilityClamped, {}, -1, first(b.clamped[kVisibility]));
  dump_layer(d, kTrmvDiffuseTemporal, {}, -1, rgb(temporal(kDiffuse)));
  dump_layer(d, kTrmvDiffuseClamped, {}, -1, rgb(b.clamped[kDiffuse]));
  dump_layer(d, kTrmvGlossyTemporal, {}, -1, rgb(temporal(kGlossy)));
  dump_layer(d, kTrmvGlossyClamped, {}, -1, rgb(b.clamped[kGlossy]));
  dump_layer(d, kTrmvVisibilityWeightC, {}, -1, unpack_channel(*b.weights[kVisibility], w, h, 4, 1));
  dump_layer(d, kTrmvDiffuseWeightC, {}, -1, unpack_channel(*b.weights[kDiffuse], w, h, 4, 1));
  dump_layer(d, kTrmvGlossyWeightC, {}, -1, unpack_channel(*b.weights[kGlossy], w, h, 4, 1));
  dump_layer(d, kTrmvVisibilityCleaned, {}, -1, first(b.cleaned[kVisibility]));
  dump_layer(d, kTrmvDiffuseCleaned, {}, -1, rgb(b.cleaned[kDiffuse]));
  dump_layer(d, kTrmvGlossyCleaned, {}, -1, rgb(b.cleaned[kGlossy]));
  dump_layer(d, kTonemapped, {}, -1, tonemapped);
}

Probe TrmvVulkan::probe(const std::string&, int, int, const std::string&, int) const {
  throw Error("rtdr probe runs the golden passes: use --backend cpu");
}

}  // namespace rtdr
