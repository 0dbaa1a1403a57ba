// A-SVGF's passes on a Vulkan device [ASVGF18 Sec. 3.4, 3.5]: the twin of AsvgfStream (filters/asvgf/asvgf.h), for
// both streams. Per stream the gradient image, its reconstruction's iterations ping-ponging on the stratum grid,
// then lambda and (lambda_max, alpha_i, alpha_mu_i) per pixel (filters/asvgf/*.comp), recorded into the batch of the
// SVGF pipeline (gpu/svgf_vulkan.h), whose temporal port reads those weights (weights()). The alpha of `--alpha`
// goes: the flag, or filters/asvgf/asvgf.h's defaults -> record() -> the adaptive alpha port's push block (Eq. 15)
// -> the temporal port.
#pragma once

#include "core/frame.h"
#include "filters/asvgf/adaptive_alpha.h"
#include "filters/asvgf/asvgf_params.h"
#include "filters/asvgf/gradient_image.h"
#include "filters/image.h"
#include "filters/svgf/svgf_params.h"
#include "gpu/svgf_shaders.h"

#include <functional>
#include <memory>
#include <string>

namespace rtdr {

// The push constants of A-SVGF's three ports, filled from the golden passes' parameters: one function per block,
// which the pipeline (record() below) and the per-pass ports (gpu/asvgf_gradient_gpu.cpp, asvgf_atrous_gpu.cpp,
// asvgf_alpha_gpu.cpp) all call. `width` x `height` is the frame, `grid_width` x `grid_height` its stratum grid.
GradientImagePush gradient_image_push(int width, int height, int grid_width, int grid_height, int s,
                                      const GradientForm& form);
GradientAtrousPush gradient_atrous_push(int grid_width, int grid_height, int level, int s, const SvgfParams& params);
AdaptiveAlphaPush adaptive_alpha_push(int width, int height, int grid_width, int grid_height, int s,
                                      const AdaptiveAlphaParams& params);

class AsvgfVulkan {
 public:
  // Records a copy of `plane` for the dump, and what to make of it once the batch has run (gpu/svgf_vulkan.cpp).
  using DumpCopy =
      std::function<void(const GpuBuffer& plane, std::function<void(const GpuBuffer& readback, Frame& dump)> unpack)>;

  explicit AsvgfVulkan(VulkanContext& context);
  ~AsvgfVulkan();
  // The commands record() adds per frame, and its dump's copies.
  static uint32_t commands(const AsvgfParams& params);
  static uint32_t dump_commands(const AsvgfParams& params);

  // Packs this frame's inputs: each stream's 1-spp colour with its previous luminance (gradient.prev_<stream>, or
  // their sum for one stream), and gradient.source; the planes are (re)made for the frame's size and the stratum
  // size of its gradient samples. Throws rtdr::Error naming `method` for a frame without gradient samples.
  void upload(const Frame& in, const RgbPlane (&noisy)[2], const FloatPlane (&prev_luminance)[2],
              const std::string& method);
  // Records both streams' passes, reading the current G-buffer's surface records, depth gradient and mesh ids.
  // With `dump`, each pass's layers (filters/passes.h) as the golden AsvgfStream dumps them, for the streams named
  // in `names` (an empty name: not dumped).
  void record(ComputeBatch& batch, const SvgfShaders& shaders, const GpuBuffer& surface, const GpuBuffer& depth_grad,
              const GpuBuffer& mesh, const SvgfParams& svgf, const AsvgfParams& asvgf, const DumpCopy* dump,
              const std::string (&names)[2]) const;
  // The (lambda_max, alpha_i, alpha_mu_i, 0) records per pixel of each stream, what the temporal port reads.
  Streams weights() const;

 private:
  struct Buffers;  // the planes, for one frame size and stratum size
  VulkanContext& context_;
  std::unique_ptr<Buffers> buffers_;
};

}  // namespace rtdr
