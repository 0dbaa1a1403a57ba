// A-SVGF's temporal gradient samples, the render side [ASVGF18 Sec. 3.1-3.3, Eq. 2-6].
//
// The temporal gradient of pixel jbar is the change of its shading between two frames at the SAME surface point
// and with the SAME random numbers [Eq. 2, 6]:
//   delta_{i,jbar} = f_i(G~_{i-1,j}, xi_{i-1,j}) - f_{i-1}(G_{i-1,j}, xi_{i-1,j}),
// where G_{i-1,j} is the surface sample frame i-1 saw at pixel j, G~ the same point at frame i's pose, and xi its
// seed. Frame i's render builds these samples [Sec. 3.3, Fig. 2]:
//   1. rasterize frame i as usual;
//   2. in each s x s stratum of frame i-1 pick one pixel j (select_gradient_source; steps 2-4: gradient_candidates);
//   3. forward project its surface sample into frame i (motion/forward_project.h);
//   4. discard it when frame i's depth buffer hides it, it lands off screen or behind the camera, or it lands
//      where frame i sees no surface or another instance;
//   5. keep at most one per stratum of frame i: the one with the smallest source index j (gradient_winners);
//   6. merge it into frame i's visibility buffer at jbar = floor(its screen position), with frame i-1's seed at
//      j [Eq. 6]: the G-buffer and motion are resolved from the merged buffer, so they describe G~ at jbar and
//      its motion points back to j;
//   7. trace every pixel of the merged buffer: jbar's result is f_i(G~, xi_{i-1,j}), a valid sample of frame i;
//   8. store frame i-1's luminance at j beside it (gradient.prev_direct, gradient.prev_indirect), so frame i
//      alone holds both terms of delta.
// The filter side (the gradient's reconstruction and the adaptive alpha [Sec. 3.4, 3.5]) is filters/asvgf/.
//
// Choices the paper leaves open (also in trace/README.md, "Deviations and choices"):
// - "Randomly" (step 2): the pixel is hash(global seed, frame i, stratum) modulo the number of pixels the stratum
//   has (strata at the right and bottom edges may be partial); when that pixel sees no surface, or (seed_chains 0)
//   was itself a gradient sample, the stratum offers none. selection 1 picks instead the brightest eligible pixel
//   (direct + indirect luminance), as Q2RTX does.
// - Step 5: the paper lets GPU atomics pick whichever sample arrives first, which is not deterministic. Here the
//   smallest source index j wins, which a GPU port reproduces with one atomicMin per stratum
//   (trace/gradient_merge.comp); the output is the same for any thread count.
// - A sample landing where frame i sees no surface crossed a silhouette: discarded, like an occluded one.
// - A sample landing where frame i sees another instance is discarded too. The depth test alone (1 % tolerance,
//   motion/forward_project.h) passes a surface just behind another: on falling-light, samples of the ceiling
//   replaced the pixels of the light panel 2 cm below it, and the frame lost the light's emission there (its mean
//   emission fell by 40 %, and every filter's brightness drifted by up to 40 %). Frame i sees the sample's own
//   instance wherever the sample is truly visible, except within a pixel of a silhouette.
// - Delta is taken per stream, on the luminance of the demodulated direct and indirect illumination: our SVGF
//   filters the two streams separately, and both samples see the same point, hence the same albedo.
// - The barycentrics of a merged pixel are those of j's centre in frame i-1: the point is G~, up to a pixel away
//   from jbar's centre (as in the paper, Fig. 2d).
// - Frame 0 has no previous frame, hence no gradient samples.
// - Light choice [Sec. 5.4]: our lights are chosen in proportion to their power, so when one light changes, the
//   same random number may pick another light at every pixel, and delta is noise far from the change. With
//   light_cdf 1 a re-shaded sample chooses its lights by the powers of the frame its seed was made in (recorded
//   per pixel in rng.seed_frame, since chained seeds may be older than one frame) and shades with this frame's
//   emission: the paper's suggestion of storing the light choice with the seed, made exact. Default 0, as the
//   paper renders.
#pragma once

#include "core/frame.h"
#include "filters/params.h"
#include "raster/gbuffer_frame.h"
#include "scenes/scene.h"
#include "trace/render_frame.h"

#include <cstdint>
#include <optional>
#include <vector>

// Every parameter of the gradient samples, declared once (filters/params.h):
// X(type, name, default, min, max, symbol, source)
#define RTDR_GRADIENT_PARAMS(X)                                                                                   \
  X(int, stratum_size, 3, 2, 8, "s", "ASVGF18 Sec. 3.3: one gradient sample per 3x3 stratum; 2 and 4 in Fig. 5") \
  X(int, selection, 0, 0, 1, "", "0: a random pixel of each stratum (ASVGF18 Sec. 3.3); 1: the brightest (Q2RTX)") \
  X(int, seed_reuse, 1, 0, 1, "", "1: re-shade with frame i-1's seed (ASVGF18 Eq. 6); 0: a new seed (Eq. 4-5)")    \
  X(int, seed_chains, 1, 0, 1, "", "1: a forwarded seed may be forwarded again (ASVGF18 Sec. 3.2); 0: never (Q2RTX)") \
  X(int, light_cdf, 0, 0, 1, "",                                                                                  \
    "lights of a re-shaded sample are chosen by the powers of 0: this frame (ASVGF18); 1: its seed's frame (Sec. 5.4)")

namespace rtdr {

struct GradientParams {
  RTDR_GRADIENT_PARAMS(RTDR_PARAM_FIELD)
};

std::vector<ParamInfo> gradient_param_table();
std::vector<double> param_values(const GradientParams& params);
// Throws rtdr::Error naming the first parameter outside its range.
void validate(const GradientParams& params);
// Sets the row named `key`; false when there is none. Throws rtdr::Error for a value outside the row's range.
bool set_param(GradientParams& params, const std::string& key, double value);

// What frame i needs of frame i-1, read from its layers (docs/buffers.md): its visibility buffer (id.instance,
// id.triangle, bary.U/V, depth.Z), its seeds (rng.seed), the luminance of its demodulated direct and indirect
// illumination, which of its pixels were gradient samples themselves (gradient.source; none when absent), and the
// frame each seed was made in (rng.seed_frame; when absent, all in frame i-1).
struct PreviousFrame {
  VisibilityBuffer vis;
  std::vector<uint32_t> seed;
  std::vector<uint32_t> seed_frame;  // empty: every seed was made in frame i-1
  std::vector<float> luminance_direct, luminance_indirect;
  std::vector<bool> was_gradient;

  // Throws rtdr::Error naming the first missing layer.
  static PreviousFrame from_frame(const Frame& frame);
  // Checks every value that indexes the scene or memory, before any is used, for frame `frame_index`, which
  // continues this one: each id.instance is kInvalidId or an instance of `scene`, each id.triangle (where there
  // is an instance) a triangle of its mesh, the barycentrics there finite, each rng.seed_frame at most
  // frame_index - 1, and the luminance of direct and indirect finite. A frame read from a file can hold any value
  // (a frame of another scene, a damaged file), and an id beyond the scene would read past its arrays. Throws a
  // one-line rtdr::Error naming `source` (the file), the frames, the channel, the pixel and the value.
  void require_fits(const Scene& scene, int frame_index, const std::string& source) const;
};

// One gradient sample: frame i-1's pixel j carried to frame i's pixel jbar.
struct GradientSample {
  uint32_t source = 0;     // j, as the linear index y W + x in frame i-1
  glm::ivec2 target{0};    // jbar
  SurfaceSample sample;    // G_{i-1,j}: the same point at frame i's pose is G~
  float depth = 0.0f;      // its linear view depth at frame i
};

// A candidate for step 5: a source pixel j of frame i-1 that passed steps 2-4, and its target pixel jbar in frame i;
// source kInvalidId where there is none (its stratum of frame i-1 offered none, or steps 3-4 discarded it).
struct GradientCandidate {
  uint32_t source = kInvalidId;  // j, as the linear index y W + x in frame i-1
  glm::ivec2 target{0};          // jbar
};

// Step 2: the pixel of stratum (sx, sy) of frame i-1 that may become a gradient sample for frame `frame_index`,
// as a linear index of frame i-1; kInvalidId when the stratum offers none.
uint32_t select_gradient_source(const PreviousFrame& prev, int sx, int sy, const GradientParams& params,
                                uint32_t global_seed, int frame_index);

// Steps 2-4, per stratum of frame i-1 (ceil(W / s) x ceil(H / s), row-major): its selected source j forward
// projected into frame i and kept where frame i sees it, or none. `cur` is frame i's geometry as rasterized (not yet
// merged); `prev` must have its size (throws rtdr::Error otherwise).
std::vector<std::optional<GradientSample>> gradient_candidates(const Scene& scene, const FrameGeometry& cur,
                                                               const PreviousFrame& prev, const GradientParams& params,
                                                               uint32_t global_seed);
// The (j, jbar) of each candidate, in the same order: source kInvalidId where there is none.
std::vector<GradientCandidate> candidate_list(const std::vector<std::optional<GradientSample>>& candidates);

// Step 5: per stratum of frame i (strata_x x strata_y strata of s x s pixels, row-major), the index in `candidates`
// of the one that stays: of those whose target lies in the stratum, the one with the smallest source index j, the
// first in list order among equal j's; kInvalidId where none lands. Throws rtdr::Error for a target outside the grid.
std::vector<uint32_t> gradient_winners(const std::vector<GradientCandidate>& candidates, int stratum_size,
                                       int strata_x, int strata_y);

// Steps 2-5: frame i's gradient samples, at most one per stratum of frame i, ordered by target pixel's stratum:
// gradient_winners of gradient_candidates. `cur` is
// frame i's geometry as rasterized (not yet merged); `prev` must have its size.
std::vector<GradientSample> gradient_samples(const Scene& scene, const FrameGeometry& cur, const PreviousFrame& prev,
                                             const GradientParams& params, uint32_t global_seed);

// Steps 1-8: frame `frame_index` rendered with its gradient samples merged, with the layers of render_frame plus
// gradient.source (uint: j where the pixel is a gradient sample, else kInvalidId), gradient.prev_direct and
// gradient.prev_indirect (frame i-1's luminance at j; 0 elsewhere), rng.seed_frame (uint: the frame the pixel's
// seed was made in), and the render key of trace/render_key.h with rtdr.gradients = 1 and every parameter. `prev` is
// frame i-1 as this function rendered it, or null for the first frame; its header must hold the same key but for
// the frame index (the same scene content, size, seed, tracer settings and parameters), or rtdr::Error says which
// attribute differs. Needs settings.spp == 1: a gradient compares two 1-spp samples.
Frame render_frame_with_gradients(const Scene& scene, int frame_index, int width, int height,
                                  const RenderSettings& settings, const GradientParams& params, const Frame* prev,
                                  TraceStats* stats = nullptr, const RowsDone& rows_done = {});

// The share of a frame's pixels that are gradient samples (gradient.source); 0 for a frame without them. At most
// one sample per stratum, so at most 1/s^2 with strata of s x s where s divides the width and the height.
double gradient_sample_share(const Frame& frame);

}  // namespace rtdr
