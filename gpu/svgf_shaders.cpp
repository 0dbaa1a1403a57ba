// The SVGF ports' pipelines and their dispatches. See svgf_shaders.h.
#include "gpu/svgf_shaders.h"

#include "core/error.h"
#include "filters/svgf/atrous.h"

#include <algorithm>
#include <string>
#include <vector>

namespace rtdr {

namespace {

static_assert(kTemporalTexelBindings + kTemporalStorageBindings <= kStorageInputBindings,
              "VulkanContext picks storage inputs only where the device allows every port's bindings");
static_assert(kTemporalTexelBindings <= kTexelInputBindings,
              "VulkanContext picks texel inputs only where the device allows every port's texel bindings");
static_assert(kTrmvTemporalTexelBindings + kTrmvTemporalStorageBindings <= kStorageInputBindings &&
                  kTrmvTemporalTexelBindings <= kTexelInputBindings,
              "TRMV's temporal port fits the bindings VulkanContext chose its input kind for");
static_assert(kTrmvSpatialTexelBindings + kTrmvSpatialStorageBindings <= kStorageInputBindings &&
                  kTrmvSpatialTexelBindings <= kTexelInputBindings &&
                  kTrmvCleanupTexelBindings + kTrmvCleanupStorageBindings <= kStorageInputBindings &&
                  kTrmvCleanupTexelBindings <= kTexelInputBindings,
              "TRMV's spatial and clean-up ports fit the bindings VulkanContext chose its input kind for");
static_assert(kTrmvFalloffTexelBindings + kTrmvFalloffStorageBindings <= kStorageInputBindings &&
                  kTrmvFalloffTexelBindings <= kTexelInputBindings,
              "TRMV's falloff port fits the bindings VulkanContext chose its input kind for");
static_assert(kAdaptiveAlphaTexelBindings + kAdaptiveAlphaStorageBindings <= kStorageInputBindings &&
                  kAdaptiveAlphaTexelBindings <= kTexelInputBindings,
              "A-SVGF's adaptive alpha port fits the bindings VulkanContext chose its input kind for");
static_assert(kGradientImageTexelBindings + kGradientImageStorageBindings <= kStorageInputBindings &&
                  kGradientImageTexelBindings <= kTexelInputBindings,
              "A-SVGF's gradient image port fits the bindings VulkanContext chose its input kind for");
static_assert(kGradientAtrousTexelBindings + kGradientAtrousStorageBindings <= kStorageInputBindings &&
                  kGradientAtrousTexelBindings <= kTexelInputBindings,
              "A-SVGF's gradient reconstruction port fits the bindings VulkanContext chose its input kind for");

}  // namespace

// `texel` texel-buffer bindings followed by `storage` storage-buffer bindings, the order of every port; with
// storage inputs, all of them storage buffers.
std::vector<Binding> port_bindings(const VulkanContext& context, uint32_t texel, uint32_t storage) {
  if (context.shader_inputs() == ShaderInputs::Storage) return std::vector<Binding>(texel + storage, Binding::Storage);
  std::vector<Binding> kinds(texel, Binding::Texel);
  kinds.insert(kinds.end(), storage, Binding::Storage);
  return kinds;
}

// The SPIR-V of `stem` built for the context's illumination records and input kind (gpu/CMakeLists.txt).
std::vector<uint32_t> load_port(const VulkanContext& context, const std::string& stem) {
  const bool half = context.illumination_records() == IlluminationRecords::Fp16;
  const bool storage = context.shader_inputs() == ShaderInputs::Storage;
  return load_shader(stem + (half ? "_fp16" : "") + (storage ? "_storage" : ""));
}

TemporalPush temporal_push(uint32_t width, uint32_t height, uint32_t prev_width, uint32_t prev_height,
                           const SvgfParams& params) {
  const bool has_history = prev_width > 0 && prev_height > 0;
  return TemporalPush{.width = width,
                      .height = height,
                      .prev_width = prev_width,
                      .prev_height = prev_height,
                      .has_history = has_history ? 1u : 0u,
                      .max_history = uint32_t(params.max_history),
                      .alpha = params.alpha,
                      .alpha_moments = params.alpha_moments,
                      .temporal_depth_relative = params.temporal_depth_relative,
                      .temporal_normal_cosine = params.temporal_normal_cosine,
                      .adaptive = 0u,
                      .restart_history = 0u};
}

// The push constants of one 1-D pass along `axis` (trmv_spatial_axis's arguments).
TrmvSpatialPush trmv_spatial_push(int w, int h, glm::ivec2 axis, int radius, uint32_t sigma_plane, float sigma_all,
                                  const SvgfParams& edges) {
  return TrmvSpatialPush{.width = uint32_t(w),
                         .height = uint32_t(h),
                         .axis_x = axis.x,
                         .axis_y = axis.y,
                         .radius = radius,
                         .has_sigma_plane = sigma_plane,
                         .sigma = sigma_all,
                         .sigma_z = edges.sigma_z,
                         .sigma_n = edges.sigma_n,
                         .epsilon = edges.epsilon};
}

VariancePush variance_push(uint32_t width, uint32_t height, const SvgfParams& params) {
  return VariancePush{.width = width,
                      .height = height,
                      .variance_min_history = uint32_t(params.variance_min_history),
                      .sigma_z = params.sigma_z,
                      .sigma_n = params.sigma_n,
                      .epsilon = params.epsilon};
}

AtrousPush atrous_push(uint32_t width, uint32_t height, int level, const SvgfParams& params, bool keep_prefiltered) {
  return AtrousPush{.width = width,
                    .height = height,
                    .level = level,
                    .sigma_z = params.sigma_z,
                    .sigma_n = params.sigma_n,
                    .sigma_l = params.sigma_l,
                    .epsilon = params.epsilon,
                    .keep_prefiltered = keep_prefiltered ? 1u : 0u};
}

ModulatePush modulate_push(uint32_t width, uint32_t height) { return ModulatePush{.width = width, .height = height}; }

TonemapPush tonemap_push(uint32_t width, uint32_t height, const TonemapParams& params) {
  return TonemapPush{.width = width, .height = height, .exposure = params.exposure};
}

TaaPush taa_push(uint32_t width, uint32_t height, const TaaParams& params, const TaaJitter& jitter, bool has_history) {
  return TaaPush{.width = width,
                 .height = height,
                 .alpha = params.alpha,
                 .clip_history = params.clip_history ? 1u : 0u,
                 .jitter_current = jitter.current,
                 .jitter_previous = jitter.previous,
                 .has_history = has_history ? 1u : 0u,
                 .padding = 0};
}

TrmvTemporalPush trmv_temporal_push(uint32_t width, uint32_t height, uint32_t prev_width, uint32_t prev_height,
                                    bool has_reshaded, bool has_alpha, const TrmvParams& params,
                                    const SvgfParams& svgf) {
  return TrmvTemporalPush{.width = width,
                          .height = height,
                          .prev_width = prev_width,
                          .prev_height = prev_height,
                          .has_history = prev_width > 0 ? 1u : 0u,
                          .has_reshaded = has_reshaded ? 1u : 0u,
                          .has_alpha = has_alpha ? 1u : 0u,
                          .same_surface = params.history_test != 0 ? 1u : 0u,
                          .alpha = params.alpha,
                          .clamp_gamma = params.clamp_gamma,
                          .clamp_radius = params.clamp_radius,
                          .temporal_depth_relative = svgf.temporal_depth_relative,
                          .temporal_normal_cosine = svgf.temporal_normal_cosine};
}

TrmvCleanupPush trmv_cleanup_push(uint32_t width, uint32_t height, bool has_alpha_v, const TrmvParams& params) {
  return TrmvCleanupPush{.width = width,
                         .height = height,
                         .has_alpha_v = has_alpha_v ? 1u : 0u,
                         .alpha = params.alpha,
                         .cleanup_eps = params.cleanup_eps,
                         .cleanup_sigma_max = params.cleanup_sigma_max};
}

TrmvFalloffPush trmv_falloff_push(uint32_t width, uint32_t height, uint32_t prev_width, uint32_t prev_height,
                                  bool has_valid, const TrmvParams& params) {
  return TrmvFalloffPush{.width = width,
                         .height = height,
                         .prev_width = prev_width,
                         .prev_height = prev_height,
                         .has_prev = prev_width > 0 ? 1u : 0u,
                         .has_valid = has_valid ? 1u : 0u,
                         .alpha = params.alpha,
                         .falloff_sigma = params.falloff_sigma,
                         .falloff_carry = params.falloff_carry != 0 ? 1u : 0u};
}

SvgfShaders::SvgfShaders(VulkanContext& context)
    : group_width_(context.cpu_device() ? kSvgfCpuGroupSizeX : kSvgfGroupSizeX),
      group_height_(context.cpu_device() ? kSvgfCpuGroupSizeY : kSvgfGroupSizeY),
      temporal_(context, load_port(context, "temporal"),
                port_bindings(context, kTemporalTexelBindings, kTemporalStorageBindings), sizeof(TemporalPush),
                specialization()),
      variance_(context, load_port(context, "variance"), port_bindings(context, 5, 1), sizeof(VariancePush),
                specialization()),
      atrous_5x5_(context, load_port(context, "atrous"), port_bindings(context, 3, 2), sizeof(AtrousPush),
                  specialization({5})),
      atrous_3x3_(context, load_port(context, "atrous"), port_bindings(context, 3, 2), sizeof(AtrousPush),
                  specialization({3})),
      modulate_(context, load_port(context, "modulate"), port_bindings(context, 3, 1), sizeof(ModulatePush),
                specialization()),
      tonemap_(context, load_port(context, "tonemap"), port_bindings(context, 1, 1), sizeof(TonemapPush),
               specialization()),
      taa_(context, load_port(context, "taa"), port_bindings(context, 3, 1), sizeof(TaaPush), specialization()),
      trmv_temporal_(context, load_port(context, "trmv_temporal"),
                     port_bindings(context, kTrmvTemporalTexelBindings, kTrmvTemporalStorageBindings),
                     sizeof(TrmvTemporalPush), specialization()),
      trmv_spatial_(context, load_port(context, "trmv_spatial"),
                    port_bindings(context, kTrmvSpatialTexelBindings, kTrmvSpatialStorageBindings),
                    sizeof(TrmvSpatialPush), specialization({1})),
      trmv_spatial_3_(context, load_port(context, "trmv_spatial"),
                      port_bindings(context, kTrmvSpatialTexelBindings, kTrmvSpatialStorageBindings),
                      sizeof(TrmvSpatialPush), specialization({kTrmvSpatialMaxComponents})),
      trmv_cleanup_(context, load_port(context, "trmv_cleanup"),
                    port_bindings(context, kTrmvCleanupTexelBindings, kTrmvCleanupStorageBindings),
                    sizeof(TrmvCleanupPush), specialization()),
      trmv_falloff_(context, load_port(context, "trmv_falloff"),
                    port_bindings(context, kTrmvFalloffTexelBindings, kTrmvFalloffStorageBindings),
                    sizeof(TrmvFalloffPush), specialization()),
      asvgf_adaptive_alpha_(context, load_port(context, "asvgf_adaptive_alpha"),
                            port_bindings(context, kAdaptiveAlphaTexelBindings, kAdaptiveAlphaStorageBindings),
                            sizeof(AdaptiveAlphaPush), specialization()),
      asvgf_gradient_image_(context, load_port(context, "asvgf_gradient_image"),
                            port_bindings(context, kGradientImageTexelBindings, kGradientImageStorageBindings),
                            sizeof(GradientImagePush), specialization()),
      asvgf_gradient_atrous_(context, load_port(context, "asvgf_gradient_atrous"),
                             port_bindings(context, kGradientAtrousTexelBindings, kGradientAtrousStorageBindings),
                             sizeof(GradientAtrousPush), specialization()) {}

std::vector<int32_t> SvgfShaders::specialization(const std::vector<int32_t>& more) const {
  static_assert(kSvgfGroupSizeXConstant == 0 && kSvgfGroupSizeYConstant == 1 && kAtrousKernelSizeConstant == 2,
                "the specialization lists constant_id 0, 1, 2, ... in order");
  static_assert(kTaaGroupSizeXConstant == kSvgfGroupSizeXConstant && kTaaGroupSizeYConstant == kSvgfGroupSizeYConstant,
                "the TAA port takes the SVGF ports' workgroup shape");
  std::vector<int32_t> constants = {int32_t(group_width_), int32_t(group_height_)};
  constants.insert(constants.end(), more.begin(), more.end());
  return constants;
}

uint32_t SvgfShaders::groups_x(uint32_t width) const { return group_count(width, group_width_); }
uint32_t SvgfShaders::groups_y(uint32_t height) const { return group_count(height, group_height_); }

void SvgfShaders::temporal(ComputeBatch& batch, const GpuBuffer& noisy, const GBufferPlanes& g,
                           const HistoryPlanes& prev, const GpuBuffer& illumination_out, Streams moments_out,
                           Streams weights, const TemporalPush& push) const {
  batch.dispatch(temporal_,
                 {&noisy, g.surface, g.depth_grad, g.mesh, g.motion, prev.illumination, prev.moments.direct,
                  prev.moments.indirect, prev.surface, prev.mesh, &illumination_out, moments_out.direct,
                  moments_out.indirect, weights.direct, weights.indirect},
                 &push, groups_x(push.width), groups_y(push.height), "temporal");
}

void SvgfShaders::variance(ComputeBatch& batch, const GpuBuffer& illumination, Streams moments,
                           const GBufferPlanes& g, const GpuBuffer& out, const VariancePush& push) const {
  batch.dispatch(variance_, {&illumination, moments.direct, moments.indirect, g.surface, g.depth_grad, &out}, &push,
                 groups_x(push.width), groups_y(push.height), "variance");
}

void SvgfShaders::atrous(ComputeBatch& batch, const GpuBuffer& in, const GBufferPlanes& g, const GpuBuffer& out,
                         const GpuBuffer& prefiltered, const AtrousPush& push, int kernel_size) const {
  atrous_kernel(kernel_size);  // throws on a bad kernel_size, with the golden code's rule and message
  batch.dispatch(kernel_size == 5 ? atrous_5x5_ : atrous_3x3_, {&in, g.surface, g.depth_grad, &out, &prefiltered},
                 &push, groups_x(push.width), groups_y(push.height), "atrous");
}

void SvgfShaders::modulate(ComputeBatch& batch, const GpuBuffer& filtered, const GpuBuffer& albedo,
                           const GpuBuffer& emission, const GpuBuffer& colour, const ModulatePush& push) const {
  batch.dispatch(modulate_, {&filtered, &albedo, &emission, &colour}, &push, groups_x(push.width),
                 groups_y(push.height), "modulate");
}

void SvgfShaders::tonemap(ComputeBatch& batch, const GpuBuffer& colour, const GpuBuffer& display,
                          const TonemapPush& push) const {
  batch.dispatch(tonemap_, {&colour, &display}, &push, groups_x(push.width), groups_y(push.height), "tonemap");
}

void SvgfShaders::taa(ComputeBatch& batch, const GpuBuffer& current, const GpuBuffer& history, const GpuBuffer& motion,
                      const GpuBuffer& out, const TaaPush& push) const {
  batch.dispatch(taa_, {&current, &history, &motion, &out}, &push, groups_x(push.width), groups_y(push.height),
                 "taa");
}

void SvgfShaders::trmv_temporal(ComputeBatch& batch, const TrmvTemporalPlanes& in, const GpuBuffer& color_alpha_out,
                                const GpuBuffer& fetched_out, const GpuBuffer& clamped_out,
                                const TrmvTemporalPush& push) const {
  batch.dispatch(trmv_temporal_,
                 {in.filtered, in.mesh, in.surface, in.depth_grad, in.vector, in.reshaded, in.prev_color, in.prev_mesh,
                  in.prev_surface, in.alpha, &color_alpha_out, &fetched_out, &clamped_out},
                 &push, groups_x(push.width), groups_y(push.height), "trmv_temporal");
}

void SvgfShaders::trmv_spatial(ComputeBatch& batch, const std::vector<const GpuBuffer*>& in,
                               const GpuBuffer& surface, const GpuBuffer& depth_grad,
                               const std::vector<const GpuBuffer*>& out, const TrmvSpatialPush& push,
                               const char* label, const GpuBuffer* axis_sigma) const {
  static_assert(kTrmvSpatialComponentsConstant == kAtrousKernelSizeConstant, "constant_id 2 after the workgroup shape");
  if (in.size() != out.size() || (in.size() != 1 && in.size() != size_t(kTrmvSpatialMaxComponents)))
    throw Error("trmv_spatial: filters 1 or 3 planes, got " + std::to_string(in.size()) + " in and " +
                std::to_string(out.size()) + " out");
  // A plane beyond the pipeline's count is bound to the first one's buffer and never touched (spatial_shared.h).
  const auto plane = [](const std::vector<const GpuBuffer*>& planes, size_t m) {
    return m < planes.size() ? planes[m] : planes[0];
  };
  batch.dispatch(in.size() == 1 ? trmv_spatial_ : trmv_spatial_3_,
                 {plane(in, 0), plane(in, 1), plane(in, 2), &surface, &depth_grad,
                  axis_sigma ? axis_sigma : &depth_grad,  // none: an RG32F plane that is never read
                  plane(out, 0), plane(out, 1), plane(out, 2)},
                 &push, groups_x(push.width), groups_y(push.height), label);
}

void SvgfShaders::trmv_cleanup(ComputeBatch& batch, const GpuBuffer& color, const GpuBuffer& fetched_alpha_v,
                               const GpuBuffer& clamped, const GpuBuffer& color_sigma_out,
                               const GpuBuffer& weights_out, const TrmvCleanupPush& push) const {
  batch.dispatch(trmv_cleanup_, {&color, &fetched_alpha_v, &clamped, &color_sigma_out, &weights_out}, &push,
                 groups_x(push.width), groups_y(push.height), "trmv_cleanup");
}

void SvgfShaders::trmv_falloff(ComputeBatch& batch, const TrmvFalloffPlanes& in, const GpuBuffer& theta_alpha_out,
                               const TrmvFalloffPush& push) const {
  batch.dispatch(trmv_falloff_,
                 {in.position, in.normal, in.mesh, in.surface_motion, in.motion, in.valid, in.prev_position,
                  in.prev_normal, in.prev_mesh, &theta_alpha_out},
                 &push, groups_x(push.width), groups_y(push.height), "trmv_falloff");
}

void SvgfShaders::adaptive_alpha(ComputeBatch& batch, const GpuBuffer& gradient, const GpuBuffer& alpha_out,
                                 const GpuBuffer& lambda_out, const AdaptiveAlphaPush& push) const {
  // One invocation per pixel and per stratum (adaptive_alpha_shared.h).
  batch.dispatch(asvgf_adaptive_alpha_, {&gradient, &alpha_out, &lambda_out}, &push,
                 groups_x(std::max(push.width, push.grid_width)), groups_y(std::max(push.height, push.grid_height)),
                 "adaptive_alpha");
}

void SvgfShaders::gradient_image(ComputeBatch& batch, const GradientImagePlanes& in, const GpuBuffer& values_out,
                                 const GpuBuffer& surface_out, const GpuBuffer& depth_grad_out,
                                 const GpuBuffer& mesh_out, const GpuBuffer& samples_out,
                                 const GradientImagePush& push) const {
  // One invocation per stratum (gradient_image_shared.h).
  batch.dispatch(asvgf_gradient_image_,
                 {in.noisy_prev, in.source, in.surface, in.depth_grad, in.mesh, &values_out, &surface_out,
                  &depth_grad_out, &mesh_out, &samples_out},
                 &push, groups_x(push.grid_width), groups_y(push.grid_height), "gradient");
}

void SvgfShaders::gradient_atrous(ComputeBatch& batch, const GpuBuffer& values, const GpuBuffer& surface,
                                  const GpuBuffer& depth_grad, const GpuBuffer& mesh, const GpuBuffer& values_out,
                                  const GradientAtrousPush& push) const {
  // One invocation per stratum (gradient_atrous_shared.h).
  batch.dispatch(asvgf_gradient_atrous_, {&values, &surface, &depth_grad, &mesh, &values_out}, &push,
                 groups_x(push.grid_width), groups_y(push.grid_height), "gradient_atrous");
}

}  // namespace rtdr
