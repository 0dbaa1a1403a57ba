// A-SVGF's temporal gradient samples, the render side [ASVGF18 Sec. 3.1-3.3, Eq. 2-6]. See gradients.h.
#include "trace/gradients.h"

#include "core/color.h"
#include "core/error.h"
#include "core/parallel.h"
#include "motion/backproject.h"
#include "motion/forward_project.h"
#include "trace/gradient_select_shared.h"
#include "trace/render_key.h"
#include "core/sampler.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <optional>
#include <string>

namespace rtdr {

std::vector<ParamInfo> gradient_param_table() { return {RTDR_GRADIENT_PARAMS(RTDR_PARAM_ROW)}; }
std::vector<double> param_values(const GradientParams& params) { return {RTDR_GRADIENT_PARAMS(RTDR_PARAM_VALUE)}; }
void validate(const GradientParams& p) { check_params("gradient", gradient_param_table(), param_values(p)); }

bool set_param(GradientParams& params, const std::string& key, double value) {
  RTDR_GRADIENT_PARAMS(RTDR_PARAM_SET)
  return false;
}

namespace {

// The luminance of a frame's demodulated stream `layer` ("direct" or "indirect") at every pixel.
std::vector<float> luminance_of(const Frame& frame, const std::string& layer) {
  const FloatPlane &r = frame.float_channel(layer + ".R"), &g = frame.float_channel(layer + ".G"),
                   &b = frame.float_channel(layer + ".B");
  std::vector<float> l(r.data.size());
  for (size_t i = 0; i < l.size(); ++i) l[i] = luminance(glm::vec3(r.data[i], g.data[i], b.data[i]));
  return l;
}

// Throws rtdr::Error unless `prev` is frame i-1 of the sequence whose frame i has the render key `key`: the same
// key in every attribute but the frame index (trace/render_key.h: the scene's content, size, seed, every setting of
// the tracer and every gradient parameter), and frame i-1's index.
void require_same_sequence(const Frame& prev, const Attributes& key, int frame_index) {
  const std::string what = prev.source.empty() ? std::string("the previous frame") : "'" + prev.source + "'";
  if (!prev.attributes.count("rtdr.renderer"))
    throw Error(what + " does not record how it was rendered (no rtdr.renderer in its header: another program, or "
                "an older rtdr); render the sequence from frame 0");
  if (prev.attributes.count("rtdr.gradients") && prev.attributes.at("rtdr.gradients") != "1")
    throw Error(what + " was not rendered with gradient samples; gradient samples continue one sequence");
  const std::string mismatch = key_mismatch(prev, key, {"rtdr.frame"});
  if (!mismatch.empty())
    throw Error(what + " does not continue this sequence (its header's " + mismatch + "); render the sequence from "
                "frame 0 with the same scene and settings");
  const auto it = prev.attributes.find("rtdr.frame");
  if (it == prev.attributes.end()) throw Error(what + " does not record its frame index (rtdr.frame)");
  if (it->second != std::to_string(frame_index - 1))
    throw Error(what + " is frame " + it->second + ", not frame " + std::to_string(frame_index - 1) +
                ", the one before frame " + std::to_string(frame_index));
}

}  // namespace

PreviousFrame PreviousFrame::from_frame(const Frame& frame) {
  PreviousFrame p;
  p.vis = VisibilityBuffer(frame.width(), frame.height());
  p.vis.instance = frame.uint_channel("id.instance").data;
  p.vis.triangle = frame.uint_channel("id.triangle").data;
  const FloatPlane &u = frame.float_channel("bary.U"), &v = frame.float_channel("bary.V");
  for (size_t i = 0; i < p.vis.bary.size(); ++i) p.vis.bary[i] = {u.data[i], v.data[i]};
  p.vis.depth = frame.float_channel("depth.Z").data;
  p.seed = frame.uint_channel("rng.seed").data;
  if (frame.uint_channels().count("rng.seed_frame")) p.seed_frame = frame.uint_channel("rng.seed_frame").data;
  p.luminance_direct = luminance_of(frame, "direct");
  p.luminance_indirect = luminance_of(frame, "indirect");
  p.was_gradient.assign(p.seed.size(), false);
  if (frame.uint_channels().count("gradient.source")) {
    const UIntPlane& source = frame.uint_channel("gradient.source");
    for (size_t i = 0; i < source.data.size(); ++i) p.was_gradient[i] = source.data[i] != kInvalidId;
  }
  return p;
}

void PreviousFrame::require_fits(const Scene& scene, int frame_index, const std::string& source) const {
  const std::string what = (source.empty() ? std::string("the previous frame") : "'" + source + "'") + " (frame " +
                           std::to_string(frame_index - 1) + ", which frame " + std::to_string(frame_index) +
                           " continues): ";
  const auto fail = [&](size_t i, const std::string& problem) {
    throw Error(what + problem + " at pixel (" + std::to_string(i % size_t(vis.width)) + ", " +
                std::to_string(i / size_t(vis.width)) + ")");
  };
  for (size_t i = 0; i < vis.instance.size(); ++i) {
    if (!std::isfinite(luminance_direct[i]) || !std::isfinite(luminance_indirect[i]))
      fail(i, "the luminance of direct or indirect is not finite");
    if (!seed_frame.empty() && seed_frame[i] >= uint32_t(std::max(frame_index, 0)))
      fail(i, "rng.seed_frame is " + std::to_string(seed_frame[i]) + ", not a frame before " +
                  std::to_string(frame_index));
    const uint32_t instance = vis.instance[i];
    if (instance == kInvalidId) continue;  // no surface: its triangle and barycentrics are never read
    if (instance >= scene.instances.size())
      fail(i, "id.instance is " + std::to_string(instance) + ", but scene '" + scene.name + "' has " +
                  std::to_string(scene.instances.size()) + " instances");
    const size_t triangles = scene.meshes[size_t(scene.instances[instance].mesh)].triangles.size();
    if (vis.triangle[i] >= triangles)
      fail(i, "id.triangle is " + std::to_string(vis.triangle[i]) + ", but instance " + std::to_string(instance) +
                  "'s mesh has " + std::to_string(triangles) + " triangles");
    if (!std::isfinite(vis.bary[i].x) || !std::isfinite(vis.bary[i].y)) fail(i, "bary.U or bary.V is not finite");
  }
}

uint32_t select_gradient_source(const PreviousFrame& prev, int sx, int sy, const GradientParams& params,
                                uint32_t global_seed, int frame_index) {
  const int s = params.stratum_size, width = prev.vis.width, height = prev.vis.height;
  // The stratum's pixels: s x s, fewer at the right and bottom edges.
  const int x0 = sx * s, y0 = sy * s;
  const int columns = std::min(s, width - x0), rows = std::min(s, height - y0);
  // A pixel may become a gradient sample when it sees a surface and, without chains, was not one itself.
  const auto eligible = [&](size_t j) {
    return prev.vis.instance[j] != kInvalidId && (params.seed_chains != 0 || !prev.was_gradient[j]);
  };
  if (params.selection == 0) {
    // Random [ASVGF18 Sec. 3.3]: one of the stratum's pixels, uniformly, by a hash of (seed, frame, stratum).
    const uint32_t salted = hash_u32(global_seed ^ kGradientSelectionSalt);  // trace/gradient_select_shared.h
    const uint32_t h =
        hash_combine(hash_combine(hash_combine(salted, uint32_t(frame_index)), uint32_t(sx)), uint32_t(sy));
    const int k = int(h % uint32_t(columns * rows));
    const size_t j = prev.vis.index(x0 + k % columns, y0 + k / columns);
    return eligible(j) ? uint32_t(j) : kInvalidId;
  }
  // Brightest (Q2RTX): the eligible pixel of largest direct + indirect luminance; the first in row order on ties.
  uint32_t best = kInvalidId;
  float best_luminance = 0.0f;
  for (int y = y0; y < y0 + rows; ++y)
    for (int x = x0; x < x0 + columns; ++x) {
      const size_t j = prev.vis.index(x, y);
      const float l = prev.luminance_direct[j] + prev.luminance_indirect[j];
      if (eligible(j) && (best == kInvalidId || l > best_luminance)) best = uint32_t(j), best_luminance = l;
    }
  return best;
}

std::vector<std::optional<GradientSample>> gradient_candidates(const Scene& scene, const FrameGeometry& cur,
                                                               const PreviousFrame& prev, const GradientParams& params,
                                                               uint32_t global_seed) {
  const int width = cur.vis.width, height = cur.vis.height, s = params.stratum_size;
  if (prev.vis.width != width || prev.vis.height != height)
    throw Error("gradient samples: the previous frame is " + std::to_string(prev.vis.width) + "x" +
                std::to_string(prev.vis.height) + " but frame " + std::to_string(cur.index) + " is " +
                std::to_string(width) + "x" + std::to_string(height));
  const int strata_x = (width + s - 1) / s, strata_y = (height + s - 1) / s;

  // Steps 2-4 [ASVGF18 Sec. 3.3], per stratum of frame i-1: pick j, forward project it, keep it where frame i sees
  // it. Stratum rows run in parallel; each writes only its own slots.
  std::vector<std::optional<GradientSample>> candidates(size_t(strata_x) * size_t(strata_y));
  parallel_rows(strata_y, [&](int sy) {
    for (int sx = 0; sx < strata_x; ++sx) {
      const uint32_t j = select_gradient_source(prev, sx, sy, params, global_seed, cur.index);
      if (j == kInvalidId) continue;
      const SurfaceSample sample = prev.vis.sample(int(j % uint32_t(width)), int(j / uint32_t(width)));
      // Step 3: the same point at frame i's pose, seen by frame i's camera [ASVGF18 Sec. 3.1].
      const ForwardProjection f = forward_project(scene, cur.pose, cur.view, cur.vis, sample);
      // Step 4: off screen or behind the camera, hidden by frame i's depth buffer, where frame i sees nothing, or
      // where it sees another instance (gradients.h: a surface just behind another passes the depth test).
      if (!f.on_screen || f.occluded) continue;
      const uint32_t seen = cur.vis.instance[cur.vis.index(f.pixel.x, f.pixel.y)];
      if (seen == kInvalidId || seen != sample.instance) continue;
      candidates[size_t(sy) * size_t(strata_x) + size_t(sx)] = GradientSample{j, f.pixel, sample, f.depth};
    }
  });
  return candidates;
}

std::vector<GradientSample> gradient_samples(const Scene& scene, const FrameGeometry& cur, const PreviousFrame& prev,
                                             const GradientParams& params, uint32_t global_seed) {
  const std::vector<std::optional<GradientSample>> candidates =
      gradient_candidates(scene, cur, prev, params, global_seed);
  const int s = params.stratum_size;
  const int strata_x = (cur.vis.width + s - 1) / s, strata_y = (cur.vis.height + s - 1) / s;
  // Step 5: at most one per stratum of frame i, the smallest source index winning (gradient_winners).
  std::vector<GradientSample> samples;
  for (const uint32_t k : gradient_winners(candidate_list(candidates), s, strata_x, strata_y))
    if (k != kInvalidId) samples.push_back(*candidates[k]);
  return samples;
}

std::vector<GradientCandidate> candidate_list(const std::vector<std::optional<GradientSample>>& candidates) {
  std::vector<GradientCandidate> list(candidates.size());
  for (size_t k = 0; k < candidates.size(); ++k)
    if (candidates[k]) list[k] = GradientCandidate{candidates[k]->source, candidates[k]->target};
  return list;
}

std::vector<uint32_t> gradient_winners(const std::vector<GradientCandidate>& candidates, int s, int strata_x,
                                       int strata_y) {
  // [ASVGF18 Sec. 3.3]: the paper keeps whichever sample reaches a stratum first, a race on the GPU. Here the
  // smallest j wins, the first in list order among equal j's: the same for any thread count, and what a GPU port
  // gets from an atomicMin on j, then one on the candidate's index among those holding that j
  // (trace/gradient_merge.comp).
  std::vector<uint32_t> winner(size_t(strata_x) * size_t(strata_y), kInvalidId);
  for (size_t k = 0; k < candidates.size(); ++k) {
    const GradientCandidate& c = candidates[k];
    if (c.source == kInvalidId) continue;
    const int sx = c.target.x / s, sy = c.target.y / s;  // the target's stratum of frame i
    if (c.target.x < 0 || c.target.y < 0 || sx >= strata_x || sy >= strata_y)
      throw Error("gradient_winners: candidate " + std::to_string(k) + " lands at (" + std::to_string(c.target.x) +
                  ", " + std::to_string(c.target.y) + "), outside the " + std::to_string(strata_x) + "x" +
                  std::to_string(strata_y) + " strata of " + std::to_string(s) + " pixels");
    uint32_t& w = winner[size_t(sy) * size_t(strata_x) + size_t(sx)];
    if (w == kInvalidId || c.source < candidates[w].source) w = uint32_t(k);
  }
  return winner;
}

Frame render_frame_with_gradients(const Scene& scene, int frame_index, int width, int height,
                                  const RenderSettings& settings, const GradientParams& params, const Frame* prev,
                                  TraceStats* stats, const RowsDone& rows_done) {
  validate(params);
  if (settings.spp != 1)
    throw Error("gradient samples compare two 1-spp samples: render them with --spp 1, not " +
                std::to_string(settings.spp));
  // Step 1: frame i as usual.
  FrameGeometry g = rasterize_frame(scene, frame_index, width, height);
  const size_t pixels = size_t(width) * size_t(height);
  PixelSeeds seeds;
  seeds.seed.resize(pixels);
  std::vector<uint32_t> seed_frame(pixels, uint32_t(frame_index));  // the frame each pixel's seed was made in
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x) seeds.seed[g.vis.index(x, y)] = pixel_seed(settings.seed, frame_index, x, y);

  // Steps 2-5, then 6: merge each sample and its seed into the visibility buffer at jbar [Fig. 2d, Eq. 6].
  PreviousFrame previous;
  std::vector<GradientSample> samples;
  const Attributes key = render_key(scene, frame_index, width, height, settings, &params);
  if (prev) {
    require_same_sequence(*prev, key, frame_index);
    previous = PreviousFrame::from_frame(*prev);
    previous.require_fits(scene, frame_index, prev->source);
    samples = gradient_samples(scene, g, previous, params, settings.seed);
  }
  for (const GradientSample& s : samples) {
    const size_t i = g.vis.index(s.target.x, s.target.y);
    g.vis.instance[i] = s.sample.instance;
    g.vis.triangle[i] = s.sample.triangle;
    g.vis.bary[i] = s.sample.bary;
    g.vis.depth[i] = s.depth;
    // delta is a random variable of both frames' random numbers [ASVGF18 Eq. 3]. With independent seeds its
    // variance is the sum of both samples' [ASVGF18 Eq. 4] [ASVGF18 Eq. 5]; with the previous seed they share
    // their random numbers and most of the noise cancels: xi_{i,jbar} := xi_{i-1,j} [ASVGF18 Eq. 6].
    if (params.seed_reuse != 0) {
      seeds.seed[i] = previous.seed[s.source];
      seed_frame[i] = previous.seed_frame.empty() ? uint32_t(frame_index - 1) : previous.seed_frame[s.source];
    }
  }
  // The same random numbers choose the same light only under the same light powers [ASVGF18 Sec. 5.4].
  if (params.light_cdf == 1) seeds.light_choice_frame.assign(seed_frame.begin(), seed_frame.end());

  // Step 7: the G-buffer, motion and shading of the merged buffer; jbar's shading is f_i(G~, xi_{i-1,j}).
  Frame frame(width, height);
  write_gbuffer_layers(scene, g, frame);
  write_motion_layers(scene, g, frame);
  const TraceStats traced = trace_layers(scene, g, settings, frame, rows_done, &seeds);
  write_path_motion_layers(scene, g, frame);
  if (stats) *stats = traced;
  frame.add_uint("rng.seed_frame").data = seed_frame;

  // Step 8: the source pixel, and f_{i-1}(G, xi_{i-1,j}) as luminance, beside each gradient sample [ASVGF18 Eq. 2].
  UIntPlane& source = frame.add_uint("gradient.source", kInvalidId);
  FloatPlane& prev_direct = frame.add_float("gradient.prev_direct");
  FloatPlane& prev_indirect = frame.add_float("gradient.prev_indirect");
  for (const GradientSample& s : samples) {
    const size_t i = g.vis.index(s.target.x, s.target.y);
    source.data[i] = s.source;
    prev_direct.data[i] = previous.luminance_direct[s.source];
    prev_indirect.data[i] = previous.luminance_indirect[s.source];
  }
  stamp_render_header(frame, key);  // trace/render_key.h
  return frame;
}

double gradient_sample_share(const Frame& frame) {
  if (!frame.has("gradient.source")) return 0.0;
  const std::vector<uint32_t>& source = frame.uint_channel("gradient.source").data;
  size_t samples = 0;
  for (const uint32_t s : source) samples += s != kInvalidId;
  return source.empty() ? 0.0 : double(samples) / double(source.size());
}

}  // namespace rtdr
