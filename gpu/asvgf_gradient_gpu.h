// The Vulkan port of A-SVGF's gradient image [ASVGF18 Sec. 3.4, Eq. 3, Eq. 13]: filters/asvgf/gradient_image.comp
// run on the same planes as gradient_image().
//
//   in:  one stream's noisy (demodulated) colour, gradient.source, gradient.prev_<stream>, the G-buffer (depth,
//        depth gradient, normal, id.mesh), the stratum size s and the GradientForm; sizes and s as gradient_image
//        demands (throws
//        rtdr::Error with its messages, and for a stratum holding two gradient samples)
//   out: the GradientImage of gradient_image() (filters/asvgf/gradient_image.h): delta, Delta, l^(0), Var(l^(0))
//        and the representative pixel's geometry per stratum
// The bindings: filters/asvgf/gradient_image_shared.h.
#pragma once

#include "filters/asvgf/gradient_image.h"
#include "gpu/vulkan_context.h"

namespace rtdr {

// Writes the dispatch's device time in milliseconds to *ms (see ComputePipeline::dispatch).
GradientImage gradient_image_vulkan(VulkanContext& context, const RgbPlane& noisy, const UIntPlane& source,
                                    const FloatPlane& prev_luminance, const SurfacePlanes& surface, int s,
                                    const GradientForm& form = {}, double* ms = nullptr);

}  // namespace rtdr
