// The radiance layers of a frame: f(G, seed) at every pixel of the visibility buffer [SVGF17 Sec. 3].
//
// Pass: trace_layers(scene, geometry, settings) -> radiance layers of docs/buffers.md.
//   in:  the frame's geometry (raster/gbuffer_frame.h), the settings (spp, seed, bounces)
//   out: demodulated direct and indirect illumination and their components, TRMV's noise-free shading term
//        when asked (trace/shading.h, once per pixel), the per-pixel seed, the path record. With spp = 1 these are
//        the noisy inputs of every denoiser; with spp = N they are the mean of
//        N samples of the same estimator at the same time: the reference (ground truth).
//
// Seeds: pixel (x, y) of frame f has seed pixel_seed(settings.seed, f, x, y), new every frame; sample s of N
// uses Sampler(seed, s). Re-tracing pixel (x, y) with its stored `rng.seed` reproduces sample 0 exactly.
// Pixels are independent and rows run in parallel, so the layers are identical for any thread count.
#pragma once

#include "core/frame.h"
#include "raster/gbuffer_frame.h"
#include "scenes/scene.h"
#include "trace/path_tracer.h"

#include <cstdint>
#include <functional>
#include <vector>

namespace rtdr {

struct RenderSettings {
  int spp = 1;             // samples per pixel: 1 for denoiser input, e.g. 1024 for a reference. Range [1, 2^20].
  uint32_t seed = 0;       // the global seed every pixel seed derives from
  TraceOptions trace;
};

struct TraceStats {
  uint64_t rays = 0;       // BSDF and shadow rays traced
  double seconds = 0.0;    // wall time of the tracing alone
};

// Called with the number of rows finished since the last call (from worker threads), for progress bars.
using RowsDone = std::function<void(int rows)>;

// Seeds given per pixel, in place of pixel_seed: A-SVGF's gradient samples are traced with the previous frame's
// seeds (trace/gradients.h).
struct PixelSeeds {
  std::vector<uint32_t> seed;  // every pixel's seed, row-major
  // Per pixel, the frame whose light powers choose its lights (LightSet's choice pose) [ASVGF18 Sec. 5.4];
  // empty: every pixel chooses with this frame's.
  std::vector<int> light_choice_frame;
};

// Adds the radiance layers of `geometry`'s frame to `frame` (same size) and returns what it traced.
TraceStats trace_layers(const Scene& scene, const FrameGeometry& geometry, const RenderSettings& settings,
                        Frame& frame, const RowsDone& rows_done = {}, const PixelSeeds* seeds = nullptr);

// TRMV's motion vectors, after trace_layers has recorded each pixel's path: the shadow vector and its splat
// [TRMV21 Eq. 3], the dual vector [TRMV21 Eq. 6] and the glossy vector [TRMV21 Eq. 5] (motion/shadow.h,
// motion/dual.h, motion/glossy.h). `frame` holds the
// G-buffer, `motion` and the path.* layers of `geometry`'s frame.
void write_path_motion_layers(const Scene& scene, const FrameGeometry& geometry, Frame& frame);

// A whole frame: G-buffer, motion and radiance layers.
Frame render_frame(const Scene& scene, int frame_index, int width, int height, const RenderSettings& settings,
                   TraceStats* stats = nullptr, const RowsDone& rows_done = {});

}  // namespace rtdr
