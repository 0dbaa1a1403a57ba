// Tests of gpu/gradient_select_gpu.cpp: the Vulkan ports of A-SVGF's gradient selection (trace/gradient_select.comp)
// and merge (trace/gradient_merge.comp) [ASVGF18 Sec. 3.3] against the golden select_gradient_source and
// gradient_winners (trace/gradients.cpp), on rendered frame pairs of the pillars scene and on random inputs, with
// the validation layer on. Skipped, with a message, where no Vulkan device exists.
//
// Bound: none, both are bit-identical. Selection 0 is integer work (the hash, core/sampler.glsl, and the stratum's
// pixel arithmetic); selection 1 compares fp32 sums of two luminances, each one correctly rounded addition on both
// sides (`precise` in the shader; Vulkan requires correct rounding of an addition), and the comparisons are exact.
// A device that flushes subnormal floats (Vulkan allows it without DenormPreserve) could tie two subnormal sums that
// C++ tells apart; the luminances here are 0 or far above 2^-126. The merge is integer work, and its atomicMins reach
// the same minimum in any order. Measured on lavapipe: identical on every stratum of every case, in all four builds
// (the WARN lines count them).
#include "gpu/gradient_select_gpu.h"

#include "core/error.h"
#include "scenes/gltf_loader.h"
#include "trace/gradient_select_shared.h"
#include "trace/gradients.h"

#include "gpu_fixtures.h"

#include <catch2/catch.hpp>

#include <cstdint>
#include <optional>
#include <random>
#include <vector>

using namespace rtdr;
using namespace rtdr::gpu_test;

namespace {

// Frames 11 and 12 of pillars at 94x53, each rendered with its gradient samples from the frame before: strata of 2,
// 3 and 4 leave a partial row (53 = 2 * 26 + 1 = 3 * 17 + 2 = 4 * 13 + 1), 3 and 4 a partial column too. Frame 11
// is frame i-1 (its gradient.source marks the pixels a chain-less selection skips), frame 12's rasterized geometry
// is frame i. Rendered once for the four builds of the shaders.
struct RenderedPair {
  Scene scene;
  PreviousFrame previous;
  FrameGeometry current;
  uint32_t seed = 0;
};

const RenderedPair& pillars_pair() {
  static const RenderedPair pair = [] {
    RenderedPair p;
    p.scene = load_scene("pillars");
    const int w = 94, h = 53;
    const Frame f10 = render_frame_with_gradients(p.scene, 10, w, h, {}, {}, nullptr);
    const Frame f11 = render_frame_with_gradients(p.scene, 11, w, h, {}, {}, &f10);
    p.previous = PreviousFrame::from_frame(f11);
    p.current = rasterize_frame(p.scene, 12, w, h);
    p.seed = RenderSettings{}.seed;
    return p;
  }();
  return pair;
}

GradientParams params_of(int s, int selection, int seed_chains) {
  GradientParams params;
  params.stratum_size = s;
  params.selection = selection;
  params.seed_chains = seed_chains;
  return params;
}

// select_gradient_source at every stratum of `prev`, row-major: what the port computes.
std::vector<uint32_t> golden_sources(const PreviousFrame& prev, const GradientParams& params, uint32_t seed,
                                     int frame_index) {
  const int s = params.stratum_size;
  const int strata_x = (prev.vis.width + s - 1) / s, strata_y = (prev.vis.height + s - 1) / s;
  std::vector<uint32_t> sources;
  for (int sy = 0; sy < strata_y; ++sy)
    for (int sx = 0; sx < strata_x; ++sx)
      sources.push_back(select_gradient_source(prev, sx, sy, params, seed, frame_index));
  return sources;
}

// Port and golden selection on the same inputs: identical. Returns the strata compared.
size_t check_selection(VulkanContext& context, const PreviousFrame& prev, const GradientParams& params,
                       uint32_t seed, int frame_index) {
  INFO("frame i-1 " << prev.vis.width << "x" << prev.vis.height << ", s " << params.stratum_size << ", selection "
                    << params.selection << ", seed_chains " << params.seed_chains << ", seed " << seed
                    << ", frame " << frame_index);
  const std::vector<uint32_t> golden = golden_sources(prev, params, seed, frame_index);
  double ms = 0.0;
  const std::vector<uint32_t> gpu = select_gradient_sources_vulkan(context, prev, params, seed, frame_index, &ms);
  REQUIRE(gpu.size() == golden.size());
  size_t differing = 0;
  for (size_t i = 0; i < golden.size(); ++i) differing += gpu[i] != golden[i];
  CHECK(differing == 0);
  CHECK(ms > 0.0);
  return golden.size();
}

// The strata of frame i that more than one candidate lands in: the collisions step 5 resolves.
size_t collisions(const std::vector<GradientCandidate>& candidates, int s, int strata_x, int strata_y) {
  std::vector<int> landed(size_t(strata_x) * size_t(strata_y), 0);
  for (const GradientCandidate& c : candidates)
    if (c.source != kInvalidId) ++landed[size_t(c.target.y / s) * size_t(strata_x) + size_t(c.target.x / s)];
  size_t n = 0;
  for (const int l : landed) n += l > 1;
  return n;
}

// Port and golden merge on the same candidates of a width x height frame i: identical winners, and each winner's
// j beside it. Returns the collisions resolved.
size_t check_merge(VulkanContext& context, const std::vector<GradientCandidate>& candidates, int width, int height,
                   int s) {
  INFO(candidates.size() << " candidates, frame i " << width << "x" << height << ", s " << s);
  const int strata_x = (width + s - 1) / s, strata_y = (height + s - 1) / s;
  const std::vector<uint32_t> golden = gradient_winners(candidates, s, strata_x, strata_y);
  double ms = 0.0;
  const GradientWinners gpu = gradient_winners_vulkan(context, candidates, width, height, s, &ms);
  REQUIRE(gpu.candidate.size() == golden.size());
  REQUIRE(gpu.source.size() == golden.size());
  size_t differing = 0;
  for (size_t i = 0; i < golden.size(); ++i) {
    differing += gpu.candidate[i] != golden[i];
    differing += gpu.source[i] != (golden[i] == kInvalidId ? kInvalidId : candidates[golden[i]].source);
  }
  CHECK(differing == 0);
  if (!candidates.empty()) CHECK(ms > 0.0);
  return collisions(candidates, s, strata_x, strata_y);
}

// A random frame i-1 of w x h pixels: a fifth sees no surface, a third were gradient samples, and the luminances
// take few values, so that the brightest pixel of a stratum is often tied (the first in row order wins).
PreviousFrame random_previous(std::mt19937& rng, int w, int h) {
  std::uniform_real_distribution<float> u(0.0f, 1.0f);
  PreviousFrame p;
  p.vis = VisibilityBuffer(w, h);
  const size_t n = size_t(w) * size_t(h);
  p.vis.instance.resize(n);
  p.luminance_direct.resize(n);
  p.luminance_indirect.resize(n);
  p.was_gradient.resize(n);
  for (size_t i = 0; i < n; ++i) {
    p.vis.instance[i] = u(rng) < 0.2f ? kInvalidId : uint32_t(u(rng) * 4.0f);
    p.was_gradient[i] = u(rng) < 0.3f;
    const bool tied = u(rng) < 0.5f;
    p.luminance_direct[i] = tied ? 0.25f * float(int(u(rng) * 4.0f)) : u(rng);
    p.luminance_indirect[i] = tied ? 0.25f * float(int(u(rng) * 2.0f)) : 0.1f * u(rng);
  }
  return p;
}

// `n` random candidates for a w x h frame i: sources j from [0, sources) (duplicates: the first in list order wins),
// a tenth none, targets inside a `spread_x` x `spread_y` corner of the frame (small: many collisions).
std::vector<GradientCandidate> random_candidates(std::mt19937& rng, int n, uint32_t sources, int spread_x,
                                                 int spread_y) {
  std::uniform_int_distribution<uint32_t> j(0, sources - 1);
  std::uniform_int_distribution<int> x(0, spread_x - 1), y(0, spread_y - 1);
  std::uniform_real_distribution<float> u(0.0f, 1.0f);
  std::vector<GradientCandidate> list(static_cast<size_t>(n));
  for (GradientCandidate& c : list) {
    c.source = u(rng) < 0.1f ? kInvalidId : j(rng);
    c.target = glm::ivec2(x(rng), y(rng));
  }
  return list;
}

}  // namespace

TEST_CASE("the selection port matches select_gradient_source on a rendered frame, strata 2 to 4, both rules") {
  const RenderedPair& pair = pillars_pair();
  const auto context = validated_context();
  size_t strata = 0, none = 0, skipped_chained = 0;
  for (const int s : {2, 3, 4})
    for (const int selection : {0, 1})
      for (const int chains : {0, 1}) {
        const GradientParams params = params_of(s, selection, chains);
        for (const uint32_t seed : {pair.seed, 0x9e3779b9u})
          strata += check_selection(*context, pair.previous, params, seed, 12);
        const std::vector<uint32_t> golden = golden_sources(pair.previous, params, pair.seed, 12);
        for (const uint32_t j : golden) none += j == kInvalidId;
        if (chains == 0) {
          // The chain-less rule is exercised: some stratum that offers a pixel with chains offers none without.
          const std::vector<uint32_t> chained =
              golden_sources(pair.previous, params_of(s, selection, 1), pair.seed, 12);
          for (size_t i = 0; i < golden.size(); ++i)
            skipped_chained += golden[i] == kInvalidId && chained[i] != kInvalidId;
        }
      }
  WARN("selection: " << strata << " strata identical on " << context->device_name() << " (" << none
                     << " offering none, " << skipped_chained << " skipped for seed chains 0)");
  CHECK(none > 0);
  CHECK(skipped_chained > 0);
  check_no_validation_messages(*context);
}

TEST_CASE("the selection port matches select_gradient_source on random frames: ties, partial strata, any seed") {
  const auto context = validated_context();
  std::mt19937 rng(33);
  size_t strata = 0;
  // A single partial stratum (5x3 under s >= 5), partial edges, a 1x1 frame, and strata of 2 to 8 (the range).
  struct Case {
    int w, h;
  };
  for (const Case c : {Case{1, 1}, Case{5, 3}, Case{41, 23}}) {
    const PreviousFrame prev = random_previous(rng, c.w, c.h);
    for (const int s : {2, 3, 5, 8})
      for (const int selection : {0, 1})
        for (const int chains : {0, 1}) {
          const uint32_t seed = std::uniform_int_distribution<uint32_t>()(rng);
          const int frame = std::uniform_int_distribution<int>(0, 1 << 30)(rng);
          strata += check_selection(*context, prev, params_of(s, selection, chains), seed, frame);
        }
  }
  // The hash's extremes: seeds 0 and 2^32 - 1, frames 0 and INT_MAX, the salt itself as the seed.
  const PreviousFrame prev = random_previous(rng, 41, 23);
  for (const uint32_t seed : {0u, 0xFFFFFFFFu, kGradientSelectionSalt})
    for (const int frame : {0, 2147483647}) strata += check_selection(*context, prev, params_of(4, 0, 1), seed, frame);
  WARN("selection, random frames: " << strata << " strata identical");
  check_no_validation_messages(*context);
}

TEST_CASE("the merge port matches gradient_winners and gradient_samples on a rendered frame pair") {
  const RenderedPair& pair = pillars_pair();
  const auto context = validated_context();
  const int w = pair.current.vis.width, h = pair.current.vis.height;
  size_t candidates_total = 0, collided = 0, squeezed_collided = 0;
  for (const int s : {2, 3, 4})
    for (const int selection : {0, 1})
      for (const int chains : {0, 1}) {
        const GradientParams params = params_of(s, selection, chains);
        const std::vector<std::optional<GradientSample>> found =
            gradient_candidates(pair.scene, pair.current, pair.previous, params, pair.seed);
        const std::vector<GradientCandidate> list = candidate_list(found);
        candidates_total += list.size();
        collided += check_merge(*context, list, w, h, s);
        // The winners are gradient_samples' samples, in its order (by target stratum).
        const GradientWinners gpu = gradient_winners_vulkan(*context, list, w, h, s);
        const std::vector<GradientSample> samples =
            gradient_samples(pair.scene, pair.current, pair.previous, params, pair.seed);
        std::vector<GradientCandidate> winners;
        for (const uint32_t k : gpu.candidate)
          if (k != kInvalidId) winners.push_back(list[k]);
        REQUIRE(winners.size() == samples.size());
        for (size_t i = 0; i < samples.size(); ++i) {
          CHECK(winners[i].source == samples[i].source);
          CHECK(winners[i].target == samples[i].target);
        }
        // The same candidates squeezed into the top-left ninth of the frame (targets divided by 3): many land in
        // one stratum.
        std::vector<GradientCandidate> squeezed = list;
        for (GradientCandidate& c : squeezed) c.target /= 3;
        squeezed_collided += check_merge(*context, squeezed, w, h, s);
      }
  WARN("merge, rendered: " << candidates_total << " candidate slots, " << collided << " strata with collisions as "
                           << "rendered, " << squeezed_collided << " squeezed; identical");
  CHECK(squeezed_collided > 100);
  check_no_validation_messages(*context);
}

TEST_CASE("the merge port matches gradient_winners on random candidate lists with many collisions") {
  const auto context = validated_context();
  std::mt19937 rng(51);
  size_t collided = 0, lists = 0;
  // Lists shorter than, as long as and longer than a workgroup (64), and long ones; sources from a small range
  // (duplicate j's) and a large one; targets over the whole frame and crowded into a corner.
  for (const int n : {1, 63, 64, 65, 700, 5000})
    for (const int s : {2, 3, 4})
      for (const uint32_t sources : {50u, 1u << 20}) {
        const int w = 37, h = 23;
        collided += check_merge(*context, random_candidates(rng, n, sources, w, h), w, h, s);
        collided += check_merge(*context, random_candidates(rng, n, sources, 5, 4), w, h, s);
        lists += 2;
      }
  // No candidate, or only "none" entries: no stratum has a winner.
  check_merge(*context, {}, 37, 23, 3);
  const std::vector<GradientCandidate> nothing(100);
  check_merge(*context, nothing, 37, 23, 3);
  const GradientWinners empty = gradient_winners_vulkan(*context, nothing, 37, 23, 3);
  for (const uint32_t k : empty.candidate) CHECK(k == kInvalidId);
  WARN("merge, random: " << lists << " lists, " << collided << " strata with collisions; identical");
  check_no_validation_messages(*context);
}

TEST_CASE("the gradient selection and merge ports reject bad parameters and targets outside the frame") {
  const auto context = validated_context();
  std::mt19937 rng(7);
  const PreviousFrame prev = random_previous(rng, 12, 9);
  CHECK_THROWS_AS(select_gradient_sources_vulkan(*context, prev, params_of(1, 0, 1), 0u, 1), Error);
  CHECK_THROWS_AS(select_gradient_sources_vulkan(*context, prev, params_of(3, 2, 1), 0u, 1), Error);
  PreviousFrame short_planes = prev;
  short_planes.luminance_direct.pop_back();
  CHECK_THROWS_AS(select_gradient_sources_vulkan(*context, short_planes, params_of(3, 1, 1), 0u, 1), Error);
  const std::vector<GradientCandidate> outside = {{5u, glm::ivec2(12, 0)}};
  CHECK_THROWS_AS(gradient_winners_vulkan(*context, outside, 12, 9, 3), Error);
  CHECK_THROWS_AS(gradient_winners(outside, 3, 4, 3), Error);
  const std::vector<GradientCandidate> negative = {{5u, glm::ivec2(0, -1)}};
  CHECK_THROWS_AS(gradient_winners_vulkan(*context, negative, 12, 9, 3), Error);
  CHECK_THROWS_AS(gradient_winners_vulkan(*context, {}, 12, 9, 0), Error);
}
