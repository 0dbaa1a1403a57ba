// The SVGF ports' compute pipelines, created once, and one function per pass that records its dispatch into a
// ComputeBatch. Every buffer is a plane in the layout of filters/svgf/planes_shared.h; the per-stream passes take the
// direct and the indirect stream together: in one illumination buffer, and as two moments planes (Streams). The shaders
// are filters/svgf/*.comp, filters/taa/taa.comp, filters/trmv/*.comp and filters/asvgf/*.comp; each pass's bindings
// are listed in its <stem>_shared.h.
#pragma once

#include "filters/asvgf/adaptive_alpha_shared.h"
#include "filters/asvgf/gradient_atrous_shared.h"
#include "filters/asvgf/gradient_image_shared.h"
#include "filters/svgf/atrous_shared.h"
#include "filters/svgf/svgf_params.h"
#include "filters/svgf/modulate_shared.h"
#include "filters/svgf/temporal_shared.h"
#include "filters/svgf/tonemap.h"
#include "filters/svgf/tonemap_shared.h"
#include "filters/svgf/variance_shared.h"
#include "filters/taa/taa.h"
#include "filters/taa/taa_shared.h"
#include "filters/trmv/cleanup_shared.h"
#include "filters/trmv/falloff_shared.h"
#include "filters/trmv/spatial_shared.h"
#include "filters/trmv/temporal_shared.h"
#include "filters/trmv/trmv_params.h"
#include "gpu/compute.h"

#include <cstdint>
#include <string>
#include <vector>

namespace rtdr {

// One plane per stream: the moments.
struct Streams {
  const GpuBuffer* direct;
  const GpuBuffer* indirect;
};

// The current G-buffer: surface records, depth gradient, mesh ids, motion.
struct GBufferPlanes {
  const GpuBuffer* surface;
  const GpuBuffer* depth_grad;
  const GpuBuffer* mesh;
  const GpuBuffer* motion;
};

// What temporal accumulation reads of the previous frame.
struct HistoryPlanes {
  const GpuBuffer* illumination;  // C'_{i-1}
  Streams moments;                // mu1', mu2', n
  const GpuBuffer* surface;
  const GpuBuffer* mesh;
};

// What TRMV's temporal pass reads (filters/trmv/temporal_shared.h's bindings 0-9); an optional plane that is empty
// is one unread texel, and the push constants say so.
struct TrmvTemporalPlanes {
  const GpuBuffer* filtered;        // c~_i
  const GpuBuffer* mesh;            // id.mesh
  const GpuBuffer* surface;         // (n, z)
  const GpuBuffer* depth_grad;      // grad z
  const GpuBuffer* vector;          // (m, code): the motion, its validity and history test
  const GpuBuffer* reshaded;        // (re-shaded history, its validity)
  const GpuBuffer* prev_color;      // cbar_{i-1}
  const GpuBuffer* prev_mesh;       // the previous id.mesh
  const GpuBuffer* prev_surface;    // the previous (n, z)
  const GpuBuffer* alpha;           // the alpha plane, (theta, alpha^V)
};

// What TRMV's falloff pass reads (filters/trmv/falloff_shared.h's bindings 0-8); an optional plane that is empty
// is one unread texel, and the push constants say so.
struct TrmvFalloffPlanes {
  const GpuBuffer* position;       // s_i
  const GpuBuffer* normal;         // n(s_i)
  const GpuBuffer* mesh;           // id.mesh
  const GpuBuffer* surface_motion; // m, the surface motion
  const GpuBuffer* motion;         // m^V
  const GpuBuffer* valid;          // the shadow motion's validity
  const GpuBuffer* prev_position;  // the previous frame's position
  const GpuBuffer* prev_normal;    // the previous frame's geonormal
  const GpuBuffer* prev_mesh;      // the previous id.mesh
};

// What A-SVGF's gradient image port reads (filters/asvgf/gradient_image_shared.h's bindings 0-4).
struct GradientImagePlanes {
  const GpuBuffer* noisy_prev;  // (C_i, gradient.prev_<stream>)
  const GpuBuffer* source;      // gradient.source
  const GpuBuffer* surface;     // (n, z)
  const GpuBuffer* depth_grad;
  const GpuBuffer* mesh;        // id.mesh
};

class SvgfShaders;

// For every port's pipeline (these and the render side's, gpu/motion_*_gpu.cpp, gpu/gradient_*_gpu.cpp):
// `texel` texel-buffer bindings followed by `storage` storage-buffer bindings, the order of every port; with
// storage inputs, all of them storage buffers.
std::vector<Binding> port_bindings(const VulkanContext& context, uint32_t texel, uint32_t storage);
// The SPIR-V of `stem` built for the context's illumination records and input kind (gpu/CMakeLists.txt).
std::vector<uint32_t> load_port(const VulkanContext& context, const std::string& stem);

// The push constants of the three shaders that read SVGF's parameters, filled field by field from the golden
// pass's SvgfParams: one function per block, which the pipeline (svgf_vulkan.cpp) and the per-pass ports
// (temporal_gpu.cpp, variance_gpu.cpp, atrous_gpu.cpp) all call. `width` x `height` is the frame, `prev_width` x
// `prev_height` the previous frame's (0 x 0 without history). temporal_push is SVGF's constant alpha; A-SVGF sets
// its `adaptive` and `restart_history` after.
TemporalPush temporal_push(uint32_t width, uint32_t height, uint32_t prev_width, uint32_t prev_height,
                           const SvgfParams& params);
VariancePush variance_push(uint32_t width, uint32_t height, const SvgfParams& params);
AtrousPush atrous_push(uint32_t width, uint32_t height, int level, const SvgfParams& params, bool keep_prefiltered);
// The push constants of one 1-D pass of TRMV's joint bilateral along `axis` (trmv_spatial_axis's arguments): the
// spatial filter's sigma everywhere (`sigma_plane` 0), each pixel's own std in its record's w (1, the clean-up's), or
// in the std-per-axis plane (2, the penumbra filter's) (filters/trmv/spatial_shared.h).
TrmvSpatialPush trmv_spatial_push(int width, int height, glm::ivec2 axis, int radius, uint32_t sigma_plane,
                                  float sigma_all, const SvgfParams& edges);
// The other ports' push constants, one function per block likewise, which the pipelines (svgf_vulkan.cpp,
// trmv_vulkan.cpp) and the per-pass ports (modulate_gpu.cpp, tonemap_gpu.cpp, taa_gpu.cpp, trmv_*_gpu.cpp) all
// call. A previous frame of 0 x 0 means none: no history (TRMV's temporal pass and falloff, and TAA with
// `has_history`). The `has_*` flags say which optional planes the dispatch binds (filters/trmv/*_shared.h).
ModulatePush modulate_push(uint32_t width, uint32_t height);
TonemapPush tonemap_push(uint32_t width, uint32_t height, const TonemapParams& params);
TaaPush taa_push(uint32_t width, uint32_t height, const TaaParams& params, const TaaJitter& jitter, bool has_history);
TrmvTemporalPush trmv_temporal_push(uint32_t width, uint32_t height, uint32_t prev_width, uint32_t prev_height,
                                    bool has_reshaded, bool has_alpha, const TrmvParams& params,
                                    const SvgfParams& svgf);
TrmvCleanupPush trmv_cleanup_push(uint32_t width, uint32_t height, bool has_alpha_v, const TrmvParams& params);
TrmvFalloffPush trmv_falloff_push(uint32_t width, uint32_t height, uint32_t prev_width, uint32_t prev_height,
                                  bool has_valid, const TrmvParams& params);

// Runs one pass on its own (the per-pass ports of gpu/*_gpu.h): `record(shaders, batch)` records its dispatch,
// then the batch runs and waits, and *ms receives its device time (see ComputeBatch::total_time). `Shaders` is
// the pipelines' class: SvgfShaders, or TrmvShaders (gpu/trmv_shaders.h).
template <class Shaders = SvgfShaders, class Record>
void run_pass(VulkanContext& context, Record&& record, double* ms);

class SvgfShaders {
 public:
  explicit SvgfShaders(VulkanContext& context);

  // [SVGF17 Sec. 4.1, 4.2]: noisy -> illumination C' (variance 0) and moments. `weights`: A-SVGF's
  // (lambda_max, alpha_i, alpha_mu_i, 0) per pixel and stream [ASVGF18 Eq. 15], read only with push.adaptive (else
  // any buffers, unread).
  void temporal(ComputeBatch& batch, const GpuBuffer& noisy, const GBufferPlanes& g, const HistoryPlanes& prev,
                const GpuBuffer& illumination_out, Streams moments_out, Streams weights,
                const TemporalPush& push) const;
  // [SVGF17 Sec. 4.2]: illumination C' and moments -> illumination (C', sigma'^2).
  void variance(ComputeBatch& batch, const GpuBuffer& illumination, Streams moments, const GBufferPlanes& g,
                const GpuBuffer& out, const VariancePush& push) const;
  // [SVGF17 Sec. 4.3, 4.4, Eq. 1-5]: one a-trous level with the kernel_size x kernel_size kernel (5 or 3: one
  // pipeline each, atrous.comp's specialization constant); `prefiltered` receives g3x3(Var) when
  // push.keep_prefiltered. Throws rtdr::Error for another kernel_size.
  void atrous(ComputeBatch& batch, const GpuBuffer& in, const GBufferPlanes& g, const GpuBuffer& out,
              const GpuBuffer& prefiltered, const AtrousPush& push, int kernel_size) const;
  // [SVGF17 Sec. 3]: colour = emission + albedo (direct + indirect).
  void modulate(ComputeBatch& batch, const GpuBuffer& filtered, const GpuBuffer& albedo, const GpuBuffer& emission,
                const GpuBuffer& colour, const ModulatePush& push) const;
  void tonemap(ComputeBatch& batch, const GpuBuffer& colour, const GpuBuffer& display, const TonemapPush& push) const;
  void taa(ComputeBatch& batch, const GpuBuffer& current, const GpuBuffer& history, const GpuBuffer& motion,
           const GpuBuffer& out, const TaaPush& push) const;
  // [TRMV21 Eq. 2, Sec. 5]: c~, motion and history -> (cbar_i, alpha), (the fetched history, alpha^V) and the
  // clamped history.
  void trmv_temporal(ComputeBatch& batch, const TrmvTemporalPlanes& in, const GpuBuffer& color_alpha_out,
                     const GpuBuffer& fetched_out, const GpuBuffer& clamped_out, const TrmvTemporalPush& push) const;
  // [TRMV21 Eq. 4]: the receiver, the shadow motion and the previous positions -> (theta, alpha^V)
  // (filters/trmv/falloff_shared.h).
  void trmv_falloff(ComputeBatch& batch, const TrmvFalloffPlanes& in, const GpuBuffer& theta_alpha_out,
                    const TrmvFalloffPush& push) const;
  // [TRMV21 Sec. 5]: one 1-D pass of the joint bilateral, (c, std) -> (c', std) (filters/trmv/spatial_shared.h),
  // of one plane, or of three side by side (`in` and `out` of one size, 1 or 3; throws rtdr::Error otherwise).
  // `label`: the pass its time counts to (the clean-up's bilateral is part of "trmv_cleanup"). `axis_sigma`: the
  // (sigma_x, sigma_y) plane that push.has_sigma_plane = 2 reads.
  void trmv_spatial(ComputeBatch& batch, const std::vector<const GpuBuffer*>& in, const GpuBuffer& surface,
                    const GpuBuffer& depth_grad, const std::vector<const GpuBuffer*>& out,
                    const TrmvSpatialPush& push, const char* label = "trmv_spatial",
                    const GpuBuffer* axis_sigma = nullptr) const;
  // [TRMV21 Eq. 7, Eq. 8, Sec. 5]: cbar_i and the histories -> (cbar_i, std) and (w_A, w_C, std)
  // (filters/trmv/cleanup_shared.h).
  void trmv_cleanup(ComputeBatch& batch, const GpuBuffer& color, const GpuBuffer& fetched_alpha_v,
                    const GpuBuffer& clamped, const GpuBuffer& color_sigma_out, const GpuBuffer& weights_out,
                    const TrmvCleanupPush& push) const;
  // A-SVGF [ASVGF18 Eq. 14-15, Sec. 3.5]: (delta^, Delta^) per stratum -> (lambda_max, alpha_i, alpha_mu_i, 0) per pixel and lambda
  // per stratum (filters/asvgf/adaptive_alpha_shared.h).
  void adaptive_alpha(ComputeBatch& batch, const GpuBuffer& gradient, const GpuBuffer& alpha_out,
                      const GpuBuffer& lambda_out, const AdaptiveAlphaPush& push) const;
  // A-SVGF [ASVGF18 Eq. 3, Eq. 13, Sec. 3.4]: noisy colour, gradient samples and G-buffer -> per stratum (delta,
  // Delta, l^(0), Var), the representative pixel's (n, z), depth gradient and id.mesh, and the samples' count
  // (filters/asvgf/gradient_image_shared.h).
  void gradient_image(ComputeBatch& batch, const GradientImagePlanes& in, const GpuBuffer& values_out,
                      const GpuBuffer& surface_out, const GpuBuffer& depth_grad_out, const GpuBuffer& mesh_out,
                      const GpuBuffer& samples_out, const GradientImagePush& push) const;
  // A-SVGF [ASVGF18 Eq. 7-12, Sec. 3.4]: one iteration of the gradient's reconstruction, per stratum (delta^, Delta^,
  // l^(k), Var) and the strata's (n, z), depth gradient and id.mesh -> (delta^, Delta^, l^(k+1), Var)
  // (filters/asvgf/gradient_atrous_shared.h).
  void gradient_atrous(ComputeBatch& batch, const GpuBuffer& values, const GpuBuffer& surface,
                       const GpuBuffer& depth_grad, const GpuBuffer& mesh, const GpuBuffer& values_out,
                       const GradientAtrousPush& push) const;

 private:
  // The specialization constants every SVGF port takes (the workgroup shape), then `more` (the a-trous kernel
  // size). Needs group_width_ and group_height_, which are initialized before the pipelines.
  std::vector<int32_t> specialization(const std::vector<int32_t>& more = {}) const;
  // Workgroups covering a frame `width` (`height`) pixels wide (high).
  uint32_t groups_x(uint32_t width) const;
  uint32_t groups_y(uint32_t height) const;

  // The SVGF ports' workgroup shape on this device (planes_shared.h): 32x2 on a CPU device, else 8x8.
  uint32_t group_width_, group_height_;
  ComputePipeline temporal_, variance_, atrous_5x5_, atrous_3x3_, modulate_, tonemap_, taa_, trmv_temporal_;
  // TRMV's 1-D bilateral filtering one plane, and three side by side (kTrmvSpatialComponentsConstant).
  ComputePipeline trmv_spatial_, trmv_spatial_3_, trmv_cleanup_;
  ComputePipeline trmv_falloff_;
  // A-SVGF's ports.
  ComputePipeline asvgf_adaptive_alpha_, asvgf_gradient_image_, asvgf_gradient_atrous_;
};

template <class Shaders, class Record>
void run_pass(VulkanContext& context, Record&& record, double* ms) {
  const Shaders shaders(context);
  ComputeBatch batch(context, 1);
  record(shaders, batch);
  batch.run();
  batch.total_time(ms);
}

}  // namespace rtdr
