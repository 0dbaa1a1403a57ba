// The SVGF pipeline on a Vulkan device. See svgf_vulkan.h; the golden pipeline it follows is filters/svgf/svgf.cpp.
#include "gpu/svgf_vulkan.h"

#include "core/error.h"
#include "filters/passes.h"
#include "filters/svgf/variance.h"
#include "gpu/asvgf_vulkan.h"
#include "gpu/svgf_planes.h"

#include <chrono>
#include <functional>
#include <string>
#include <string_view>
#include <vector>

namespace rtdr {

namespace {

using PlanePtr = std::unique_ptr<GpuBuffer>;

// Commands per frame: A-SVGF's passes (gpu/asvgf_vulkan.h), the dispatches (temporal, variance, the levels,
// modulate, tonemap, TAA) and the two copies of the results into readback memory.
uint32_t commands_per_frame(const SvgfOptions& o) {
  return (o.adaptive ? AsvgfVulkan::commands(o.asvgf) : 0) + 5 + uint32_t(o.svgf.atrous_levels) + 2;
}

// The streams the dump names (filters/passes.h): both, or with streams = 1 the first alone, "combined" (the second
// stream then filters zeros, GPU only: the golden SvgfFilter does not run it).
struct DumpStreams {
  std::vector<int> streams;
  std::string name[2];
};
DumpStreams dump_streams(const SvgfParams& p) {
  const std::vector<std::string> names = svgf_streams(p);
  DumpStreams d;
  for (size_t k = 0; k < names.size(); ++k) {
    d.streams.push_back(int(k));
    d.name[k] = names[k];
  }
  return d;
}

}  // namespace

// The copies behind filter()'s dump. copy() records a copy of a plane into a readback buffer, with what to make of
// it; once the batch has run, unpack() makes the layers. The readback buffers are kept for the next frame's dump.
class SvgfVulkan::Dump {
 public:
  using Unpack = std::function<void(const GpuBuffer& readback, Frame& dump)>;

  explicit Dump(VulkanContext& context) : context_(context) {}
  // Copies per frame: A-SVGF's (gpu/asvgf_vulkan.h), the temporal output, the two moments planes, the variance, each
  // level's output and prefiltered variance, the filtered output and the tone-mapped colour.
  static uint32_t commands(const SvgfOptions& o) {
    return (o.adaptive ? AsvgfVulkan::dump_commands(o.asvgf) : 0) + 6 + 2 * uint32_t(o.svgf.atrous_levels);
  }

  void begin() { unpacks_.clear(); }
  void copy(ComputeBatch& batch, const GpuBuffer& plane, Unpack unpack) {
    const size_t used = unpacks_.size();  // readback buffers in use this frame
    PlanePtr& readback = used < readbacks_.size() ? readbacks_[used] : readbacks_.emplace_back();
    // The plane's format too: unpacking reads it (an illumination plane's fp16 or fp32 records).
    if (!readback || readback->floats() != plane.floats() || readback->format() != plane.format())
      readback = std::make_unique<GpuBuffer>(context_, plane.floats(), plane.format(), Memory::Readback);
    batch.copy(plane, *readback, "dump");
    unpacks_.push_back(std::move(unpack));
  }
  void unpack(Frame& dump) const {
    for (size_t i = 0; i < unpacks_.size(); ++i) unpacks_[i](*readbacks_[i], dump);
  }

 private:
  VulkanContext& context_;
  std::vector<PlanePtr> readbacks_;
  std::vector<Unpack> unpacks_;  // this frame's copies: unpacks_[i] reads readbacks_[i]
};

// Every device plane. [parity] pairs alternate between frames: [frame parity] is written this frame, the other
// holds the previous frame's (the history). [stream]: 0 direct, 1 indirect; an illumination plane holds both.
struct SvgfVulkan::Buffers {
  int width, height;
  // This frame's inputs, packed by the host.
  PlanePtr noisy, albedo, emission, depth_grad, motion;
  // Histories and the G-buffer they were made on.
  PlanePtr surface[2], mesh[2], moments[2][2], history[2], display[2];
  // This frame's intermediates.
  PlanePtr temporal, variance, level[2], colour, tonemapped, prefiltered;
  // The results, copied where the host reads them fast (compute.h's Memory::Readback).
  PlanePtr colour_readback, display_readback;

  Buffers(VulkanContext& context, int w, int h) : width(w), height(h) {
    const auto rgba = [&] { return plane_buffer(context, w, h, TexelFormat::RGBA32F); };
    // Illumination records: RGBA32F, or RGBA16F with IlluminationRecords::Fp16 (planes_shared.h).
    const auto illumination = [&] { return illumination_buffer(context, w, h); };
    for (int s = 0; s < 2; ++s) {
      surface[s] = rgba();
      mesh[s] = plane_buffer(context, w, h, TexelFormat::R32UI);
      display[s] = rgba();
      history[s] = illumination();
      level[s] = illumination();
      for (int k = 0; k < 2; ++k) moments[s][k] = rgba();
    }
    noisy = illumination();
    temporal = illumination();
    variance = illumination();
    albedo = rgba();
    emission = rgba();
    colour = rgba();
    tonemapped = rgba();
    depth_grad = plane_buffer(context, w, h, TexelFormat::RG32F);
    motion = plane_buffer(context, w, h, TexelFormat::RG32F);
    prefiltered = plane_buffer(context, w, h, TexelFormat::RG32F);
    colour_readback = std::make_unique<GpuBuffer>(context, colour->floats(), TexelFormat::None, Memory::Readback);
    display_readback = std::make_unique<GpuBuffer>(context, colour->floats(), TexelFormat::None, Memory::Readback);
  }
  static Streams streams(const PlanePtr (&planes)[2]) { return {planes[0].get(), planes[1].get()}; }
};

SvgfVulkan::SvgfVulkan(VulkanContext& context, const SvgfOptions& options)
    : VulkanMethod(context, commands_per_frame(options) + Dump::commands(options)),
      context_(context),
      options_(options),
      shaders_(context) {
  if (options_.adaptive) asvgf_ = std::make_unique<AsvgfVulkan>(context);
  // Without A-SVGF the temporal port binds two unread weights records (svgf_shaders.h).
  unread_weights_ = plane_buffer(context, 1, 1, TexelFormat::RGBA32F);
  validate(options_.svgf);
  validate(options_.asvgf);
  validate(options_.tonemap);
  validate(options_.taa_params);
  if (!options_.temporal || options_.spatial != SpatialFilter::Atrous || !options_.taa)
    throw Error("method " + options_.name + " has no Vulkan port: --backend vulkan runs svgf, asvgf and trmv");
}

SvgfVulkan::~SvgfVulkan() = default;

void SvgfVulkan::reset() { frames_ = 0; }

Frame SvgfVulkan::filter(const Frame& in, Frame* dump) {
  times_.clear();
  const int w = in.width(), h = in.height();
  Buffers& b = frame_buffers(buffers_, context_, in, frames_ > 0);
  // With a dump, each intermediate plane is copied out after the dispatch that writes it (Dump).
  Dump* d = nullptr;
  if (dump) {
    if (!dump_) dump_ = std::make_unique<Dump>(context_);
    d = dump_.get();
    d->begin();
    if (dump->width() != w || dump->height() != h) *dump = Frame(w, h);
  }
  const int cur = frames_ & 1, prev = cur ^ 1;
  const bool has_history = frames_ > 0;

  // 1. Upload: the host packs this frame's planes into the device's records.
  const auto t0 = std::chrono::steady_clock::now();
  const SurfacePlanes surface = SurfacePlanes::from_frame(in);
  // [kDirectStream], [kIndirectStream]; with streams = 1 their sum and zeros (filters/svgf/svgf.h's one_stream), and
  // with A-SVGF each stream's gradient.prev_<stream>.
  RgbPlane noisy[2];
  FloatPlane prev_luminance[2];
  if (options_.svgf.streams == 2) {
    noisy[0] = rgb_plane(in, "direct");
    noisy[1] = rgb_plane(in, "indirect");
    if (asvgf_) prev_luminance[0] = in.float_channel("gradient.prev_direct");
    if (asvgf_) prev_luminance[1] = in.float_channel("gradient.prev_indirect");
  } else {
    OneStream one = one_stream(in, options_.adaptive);
    noisy[0] = std::move(one.illumination);
    noisy[1] = RgbPlane(w, h);
    prev_luminance[0] = std::move(one.prev_luminance);
    prev_luminance[1] = FloatPlane(w, h);
  }
  for (const int s : {kDirectStream, kIndirectStream}) pack_illumination(s, noisy[s], nullptr, *b.noisy);
  pack_rgb(rgb_plane(in, "albedo"), *b.albedo);
  pack_rgb(rgb_plane(in, "emission"), *b.emission);
  pack_surface(surface, *b.surface[cur]);
  pack_ids(surface.mesh, *b.mesh[cur]);
  pack_vec2(surface.depth_grad, *b.depth_grad);
  pack_vec2(surface.motion, *b.motion);
  if (asvgf_) asvgf_->upload(in, noisy, prev_luminance, options_.name);  // the gradient samples (trace/gradients.h)
  const auto t1 = std::chrono::steady_clock::now();

  // 2. One batch of dispatches, in SvgfFilter's order [SVGF17 Sec. 3, 4].
  const SvgfParams& p = options_.svgf;
  const DumpStreams ds = dump_streams(p);
  const uint32_t uw = uint32_t(w), uh = uint32_t(h);
  // 2a. A-SVGF: each stream's alpha_i from its gradient samples [ASVGF18 Sec. 3.4, 3.5] (gpu/asvgf_vulkan.h).
  if (asvgf_) {
    const AsvgfVulkan::DumpCopy copy = [&](const GpuBuffer& plane, Dump::Unpack unpack) {
      d->copy(batch_, plane, std::move(unpack));
    };
    asvgf_->record(batch_, shaders_, *b.surface[cur], *b.depth_grad, *b.mesh[cur], options_.svgf, options_.asvgf,
                   d ? &copy : nullptr, ds.name);
  }
  const GBufferPlanes g{b.surface[cur].get(), b.depth_grad.get(), b.mesh[cur].get(), b.motion.get()};
  const HistoryPlanes history{b.history[prev].get(), Buffers::streams(b.moments[prev]), b.surface[prev].get(),
                              b.mesh[prev].get()};
  // The colour history is the output of level history_level, or the temporal output when that level is not run.
  const bool history_from_levels = p.history_level < p.atrous_levels;
  const GpuBuffer& temporal_out = history_from_levels ? *b.temporal : *b.history[cur];
  TemporalPush temporal = temporal_push(uw, uh, has_history ? uw : 0u, has_history ? uh : 0u, p);
  temporal.adaptive = options_.adaptive ? 1u : 0u;  // [ASVGF18 Eq. 15] per pixel; the history rule of temporal.h
  temporal.restart_history = options_.adaptive && options_.asvgf.history_rule == 0 ? 1u : 0u;
  shaders_.temporal(batch_, *b.noisy, g, history, temporal_out, Buffers::streams(b.moments[cur]),
                    asvgf_ ? asvgf_->weights() : Streams{unread_weights_.get(), unread_weights_.get()}, temporal);
  if (d) {
    d->copy(batch_, temporal_out, [w, h, ds](const GpuBuffer& r, Frame& f) {
      for (const int s : ds.streams)
        dump_layer(&f, layers::kTemporal, ds.name[s], -1, unpack_illumination(r, w, h, s));
    });
    for (const int s : ds.streams)
      d->copy(batch_, *b.moments[cur][s], [w, h, s, ds, mesh = surface.mesh, p](const GpuBuffer& r, Frame& f) {
        // (mu1', mu2', n, 0); and which variance the variance port takes at each pixel: the golden pass's test of
        // n (variance_is_spatial), which the port makes on the same n.
        const FloatPlane n = unpack_channel(r, w, h, 4, 2);
        dump_layer(&f, layers::kMoment1, ds.name[s], -1, unpack_channel(r, w, h, 4, 0));
        dump_layer(&f, layers::kMoment2, ds.name[s], -1, unpack_channel(r, w, h, 4, 1));
        dump_layer(&f, layers::kHistoryLength, ds.name[s], -1, n);
        dump_layer(&f, layers::kVarianceSpatial, ds.name[s], -1, variance_spatial_plane(n, mesh, p));
      });
  }
  shaders_.variance(batch_, temporal_out, Buffers::streams(b.moments[cur]), g, *b.variance,
                    variance_push(uw, uh, p));
  if (d)
    d->copy(batch_, *b.variance, [w, h, ds](const GpuBuffer& r, Frame& f) {
      for (const int s : ds.streams) dump_layer(&f, layers::kVariance, ds.name[s], -1, unpack_variance(r, w, h, s));
    });
  const GpuBuffer* filtered = p.atrous_levels > 0 ? b.variance.get() : &temporal_out;
  for (int level = 0; level < p.atrous_levels; ++level) {
    const GpuBuffer* out = level == p.history_level ? b.history[cur].get() : b.level[level & 1].get();
    shaders_.atrous(batch_, *filtered, g, *out, *b.prefiltered,
                    atrous_push(uw, uh, level, p, d != nullptr),
                    p.kernel_size);
    filtered = out;
    if (d) {
      d->copy(batch_, *out, [w, h, level, ds](const GpuBuffer& r, Frame& f) {
        for (const int s : ds.streams) {
          dump_layer(&f, layers::kLevel, ds.name[s], level, unpack_illumination(r, w, h, s));
          dump_layer(&f, layers::kLevelVariance, ds.name[s], level, unpack_variance(r, w, h, s));
        }
      });
      d->copy(batch_, *b.prefiltered, [w, h, level, ds](const GpuBuffer& r, Frame& f) {  // (direct, indirect)
        for (const int s : ds.streams)
          dump_layer(&f, layers::kLevelPrefiltered, ds.name[s], level, unpack_channel(r, w, h, 2, s));
      });
    }
  }
  if (d)
    d->copy(batch_, *filtered, [w, h, ds](const GpuBuffer& r, Frame& f) {
      for (const int s : ds.streams) dump_layer(&f, layers::kFiltered, ds.name[s], -1, unpack_illumination(r, w, h, s));
    });
  shaders_.modulate(batch_, *filtered, *b.albedo, *b.emission, *b.colour, modulate_push(uw, uh));
  shaders_.tonemap(batch_, *b.colour, *b.tonemapped, tonemap_push(uw, uh, options_.tonemap));
  if (d)
    d->copy(batch_, *b.tonemapped, [w, h](const GpuBuffer& r, Frame& f) {
      dump_layer(&f, layers::kTonemapped, {}, -1, unpack_rgb(r, w, h));
    });
  // Without a TAA history the TAA shader returns its input: the first frame's display is the tone-mapped colour.
  const TaaParams& t = options_.taa_params;
  shaders_.taa(batch_, *b.tonemapped, *b.display[prev], *b.motion, *b.display[cur],
               taa_push(uw, uh, t, TaaJitter{}, has_history));
  // The results into readback memory: on a GPU the host reads device memory across the bus, uncached.
  batch_.copy(*b.colour, *b.colour_readback, kTransferPass);
  batch_.copy(*b.display[cur], *b.display_readback, kTransferPass);
  batch_.run(submits_);
  ++frames_;
  for (const auto& [pass, ms] : batch_.times()) times_[pass] += ms;

  // 3. Download.
  const auto t2 = std::chrono::steady_clock::now();
  Frame out(w, h);
  out.source = in.source;
  set_rgb_plane(out, layer_name(layers::kColor), unpack_rgb(*b.colour_readback, w, h));
  set_rgb_plane(out, layer_name(layers::kDisplay), unpack_rgb(*b.display_readback, w, h));
  const auto t3 = std::chrono::steady_clock::now();
  // "transfer": the copies' device time and the host's packing and unpacking.
  times_[kTransferPass] += std::chrono::duration<double, std::milli>((t1 - t0) + (t3 - t2)).count();
  if (d) d->unpack(*dump);
  return out;
}

Probe SvgfVulkan::probe(const std::string&, int, int, const std::string&, int) const {
  throw Error("rtdr probe runs the golden passes: use --backend cpu");
}

}  // namespace rtdr
