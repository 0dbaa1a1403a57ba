// A-SVGF's passes on a Vulkan device. See asvgf_vulkan.h; the golden flow it follows is filters/asvgf/asvgf.cpp.
#include "gpu/asvgf_vulkan.h"

#include "filters/asvgf/asvgf.h"
#include "filters/passes.h"
#include "gpu/svgf_planes.h"

namespace rtdr {

using PlanePtr = std::unique_ptr<GpuBuffer>;

// A-SVGF's planes, per stream where they differ: made with the frame's size and the stratum size s of its gradient
// samples (a frame with another s remakes them).
struct AsvgfVulkan::Buffers {
  int width, height, s, grid_width, grid_height;
  // This frame's inputs: (C_i, gradient.prev_<stream>) per stream, gradient.source.
  PlanePtr noisy_prev[2], source;
  // Per stratum: the values (delta, Delta, l, Var), read and written in turn by the iterations, per stream; the
  // strata's geometry (the same for both streams) and the samples' count; lambda per stream.
  PlanePtr values[2][2], surface, depth_grad, mesh, samples, lambda[2];
  // Per pixel: (lambda_max, alpha_i, alpha_mu_i, 0) per stream, what the temporal pass reads.
  PlanePtr weights[2];

  Buffers(VulkanContext& context, int w, int h, int stratum_size)
      : width(w), height(h), s(stratum_size), grid_width((w + s - 1) / s), grid_height((h + s - 1) / s) {
    const int gw = grid_width, gh = grid_height;
    for (int k = 0; k < 2; ++k) {
      noisy_prev[k] = plane_buffer(context, w, h, TexelFormat::RGBA32F);
      for (PlanePtr& v : values[k]) v = plane_buffer(context, gw, gh, TexelFormat::RGBA32F);
      lambda[k] = plane_buffer(context, gw, gh, TexelFormat::R32F);
      weights[k] = plane_buffer(context, w, h, TexelFormat::RGBA32F);
    }
    source = plane_buffer(context, w, h, TexelFormat::R32UI);
    surface = plane_buffer(context, gw, gh, TexelFormat::RGBA32F);
    depth_grad = plane_buffer(context, gw, gh, TexelFormat::RG32F);
    mesh = plane_buffer(context, gw, gh, TexelFormat::R32UI);
    samples = plane_buffer(context, gw, gh, TexelFormat::R32UI);
  }
};

GradientImagePush gradient_image_push(int width, int height, int grid_width, int grid_height, int s,
                                      const GradientForm& form) {
  return GradientImagePush{.width = uint32_t(width),
                           .height = uint32_t(height),
                           .grid_width = uint32_t(grid_width),
                           .grid_height = uint32_t(grid_height),
                           .stratum_size = s,
                           .before = form.before ? 1u : 0u,
                           .absolute = form.absolute ? 1u : 0u,
                           .exponent = form.exponent,
                           .scale = form.scale};
}

GradientAtrousPush gradient_atrous_push(int grid_width, int grid_height, int level, int s, const SvgfParams& p) {
  return GradientAtrousPush{.grid_width = uint32_t(grid_width),
                            .grid_height = uint32_t(grid_height),
                            .level = level,
                            .stratum_size = s,
                            .sigma_z = p.sigma_z,
                            .sigma_n = p.sigma_n,
                            .sigma_l = p.sigma_l,
                            .epsilon = p.epsilon};
}

AdaptiveAlphaPush adaptive_alpha_push(int width, int height, int grid_width, int grid_height, int s,
                                      const AdaptiveAlphaParams& params) {
  return AdaptiveAlphaPush{.width = uint32_t(width),
                           .height = uint32_t(height),
                           .grid_width = uint32_t(grid_width),
                           .grid_height = uint32_t(grid_height),
                           .stratum_size = s,
                           .radius = params.radius,
                           .alpha = params.alpha,
                           .alpha_moments = params.alpha_moments,
                           .exponent = params.exponent,
                           .scale = params.scale};
}

AsvgfVulkan::AsvgfVulkan(VulkanContext& context) : context_(context) {}
AsvgfVulkan::~AsvgfVulkan() = default;

// Per stream: the gradient image, each iteration, and lambda with alpha.
uint32_t AsvgfVulkan::commands(const AsvgfParams& p) { return 2 * (2 + uint32_t(p.gradient_levels)); }
// Per stream: the gradient image, each iteration, lambda, and the weights.
uint32_t AsvgfVulkan::dump_commands(const AsvgfParams& p) { return commands(p) + 2; }

void AsvgfVulkan::upload(const Frame& in, const RgbPlane (&noisy)[2], const FloatPlane (&prev_luminance)[2],
                         const std::string& method) {
  const int w = in.width(), h = in.height(), s = frame_stratum_size(in, method);
  if (!buffers_ || buffers_->width != w || buffers_->height != h || buffers_->s != s)
    buffers_ = std::make_unique<Buffers>(context_, w, h, s);
  // (C_i, gradient.prev_<stream>) per stream, and gradient.source (trace/gradients.h).
  for (const int k : {kDirectStream, kIndirectStream}) {
    pack_rgb(noisy[k], *buffers_->noisy_prev[k]);
    float* records = buffers_->noisy_prev[k]->data();
    for (size_t i = 0; i < prev_luminance[k].data.size(); ++i) records[4 * i + 3] = prev_luminance[k].data[i];
  }
  pack_ids(in.uint_channel("gradient.source"), *buffers_->source);
}

Streams AsvgfVulkan::weights() const { return {buffers_->weights[0].get(), buffers_->weights[1].get()}; }

void AsvgfVulkan::record(ComputeBatch& batch, const SvgfShaders& shaders, const GpuBuffer& surface,
                         const GpuBuffer& depth_grad, const GpuBuffer& mesh, const SvgfParams& p,
                         const AsvgfParams& asvgf, const DumpCopy* dump_all, const std::string (&names)[2]) const {
  const Buffers& gb = *buffers_;
  const int w = gb.width, h = gb.height, s = gb.s, gw = gb.grid_width, gh = gb.grid_height;
  // A stratum plane's channel c, replicated to the frame's pixels as the golden dump does (gradient_image.h).
  const auto strata = [w, h, s, gw, gh](const GpuBuffer& r, int channels, int c) {
    return replicate_strata(unpack_channel(r, gw, gh, channels, c), s, w, h);
  };
  for (const int k : {kDirectStream, kIndirectStream}) {
    const std::string& name = names[k];
    const DumpCopy* dump = name.empty() ? nullptr : dump_all;
    // 1. The gradient image on the stratum grid [ASVGF18 Sec. 3.4, Eq. 3, Eq. 13]. Its samples' count is not read
    //    back: a rendered frame holds at most one sample per stratum (gradient_image.h; the per-pass port checks).
    const GradientImagePlanes in{gb.noisy_prev[k].get(), gb.source.get(), &surface, &depth_grad, &mesh};
    shaders.gradient_image(batch, in, *gb.values[k][0], *gb.surface, *gb.depth_grad, *gb.mesh, *gb.samples,
                           gradient_image_push(w, h, gw, gh, s, gradient_form(asvgf)));
    if (dump)
      (*dump)(*gb.values[k][0], [strata, name](const GpuBuffer& r, Frame& f) {
        dump_layer(&f, layers::kGradientDelta, name, -1, strata(r, 4, 0));
        dump_layer(&f, layers::kGradientNorm, name, -1, strata(r, 4, 1));
        dump_layer(&f, layers::kGradientLuminance, name, -1, strata(r, 4, 2));
        dump_layer(&f, layers::kGradientVariance, name, -1, strata(r, 4, 3));
      });
    // 2. Its reconstruction: iteration `level` reads values[level % 2] and writes the other [ASVGF18 Eq. 7-12].
    const int levels = asvgf.gradient_levels;
    for (int level = 0; level < levels; ++level) {
      const GpuBuffer& out = *gb.values[k][(level + 1) % 2];
      shaders.gradient_atrous(batch, *gb.values[k][level % 2], *gb.surface, *gb.depth_grad, *gb.mesh, out,
                              gradient_atrous_push(gw, gh, level, s, p));
      if (dump)
        (*dump)(out, [strata, name, level](const GpuBuffer& r, Frame& f) {
          dump_layer(&f, layers::kGradientLevelDelta, name, level, strata(r, 4, 0));
          dump_layer(&f, layers::kGradientLevelNorm, name, level, strata(r, 4, 1));
          dump_layer(&f, layers::kGradientLevelLuminance, name, level, strata(r, 4, 2));
          dump_layer(&f, layers::kGradientLevelVariance, name, level, strata(r, 4, 3));
        });
    }
    // 3. lambda, alpha_i and alpha_mu_i [ASVGF18 Eq. 14-15, Sec. 3.5], from the last iteration's values.
    shaders.adaptive_alpha(batch, *gb.values[k][levels % 2], *gb.weights[k], *gb.lambda[k],
                           adaptive_alpha_push(w, h, gw, gh, s, adaptive_alpha_params(p, asvgf)));
    if (dump) {
      (*dump)(*gb.lambda[k], [strata, name](const GpuBuffer& r, Frame& f) {
        dump_layer(&f, layers::kLambda, name, -1, strata(r, 1, 0));
      });
      (*dump)(*gb.weights[k], [w, h, name](const GpuBuffer& r, Frame& f) {  // (lambda_max, alpha_i, alpha_mu_i, 0)
        dump_layer(&f, layers::kAlpha, name, -1, unpack_channel(r, w, h, 4, 1));
      });
    }
  }
}

}  // namespace rtdr
