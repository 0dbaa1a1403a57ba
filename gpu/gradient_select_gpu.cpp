// The Vulkan ports of A-SVGF's gradient selection and merge. See gradient_select_gpu.h; the shaders are
// trace/gradient_select.comp and trace/gradient_merge.comp.
#include "gpu/gradient_select_gpu.h"

#include "core/error.h"
#include "filters/svgf/planes_shared.h"
#include "gpu/svgf_planes.h"
#include "gpu/svgf_shaders.h"
#include "trace/gradient_merge_shared.h"
#include "trace/gradient_select_shared.h"

#include <bit>
#include <string>

namespace rtdr {

namespace {

// The uint written at texel i of a storage buffer (an R32UI plane or a std430 uint array).
uint32_t word(const GpuBuffer& buffer, size_t i) { return std::bit_cast<uint32_t>(buffer.data()[i]); }

// Fills a buffer of uints with kInvalidId: the slots the merge's atomicMins lower.
void fill_invalid(GpuBuffer& buffer) {
  for (size_t i = 0; i < buffer.floats(); ++i) buffer.data()[i] = std::bit_cast<float>(kInvalidId);
}

// Throws rtdr::Error naming the plane of `prev` whose size is not its visibility buffer's.
void check_previous(const PreviousFrame& prev) {
  const size_t pixels = size_t(prev.vis.width) * size_t(prev.vis.height);
  const auto check = [&](size_t size, const char* name) {
    if (size != pixels)
      throw Error(std::string("select_gradient_sources_vulkan: the previous frame's ") + name + " has " +
                  std::to_string(size) + " pixels, its visibility buffer " + std::to_string(pixels));
  };
  check(prev.vis.instance.size(), "id.instance");
  check(prev.was_gradient.size(), "was_gradient");
  check(prev.luminance_direct.size(), "direct luminance");
  check(prev.luminance_indirect.size(), "indirect luminance");
}

}  // namespace

std::vector<uint32_t> select_gradient_sources_vulkan(VulkanContext& context, const PreviousFrame& prev,
                                                     const GradientParams& params, uint32_t global_seed,
                                                     int frame_index, double* ms) {
  validate(params);
  check_previous(prev);
  const int w = prev.vis.width, h = prev.vis.height, s = params.stratum_size;
  const int strata_x = (w + s - 1) / s, strata_y = (h + s - 1) / s;  // as gradient_samples
  std::vector<uint32_t> sources(size_t(strata_x) * size_t(strata_y), kInvalidId);
  if (sources.empty()) return sources;

  // Frame i-1's planes: id.instance, was_gradient (1 or 0) and (direct, indirect) luminance.
  UIntPlane instance(w, h), was_gradient(w, h);
  Vec2Plane luminance(w, h);
  instance.data = prev.vis.instance;
  for (size_t i = 0; i < was_gradient.data.size(); ++i) {
    was_gradient.data[i] = prev.was_gradient[i] ? 1u : 0u;
    luminance.data[i] = glm::vec2(prev.luminance_direct[i], prev.luminance_indirect[i]);
  }
  const auto instance_buffer = plane_buffer(context, w, h, TexelFormat::R32UI),
             was_gradient_buffer = plane_buffer(context, w, h, TexelFormat::R32UI),
             luminance_buffer = plane_buffer(context, w, h, TexelFormat::RG32F),
             source_buffer = plane_buffer(context, strata_x, strata_y, TexelFormat::R32UI);
  pack_ids(instance, *instance_buffer);
  pack_ids(was_gradient, *was_gradient_buffer);
  pack_vec2(luminance, *luminance_buffer);

  // One invocation per stratum, in the SVGF ports' workgroup shape (filters/svgf/planes_shared.h).
  const uint32_t group_x = context.cpu_device() ? kSvgfCpuGroupSizeX : kSvgfGroupSizeX,
                 group_y = context.cpu_device() ? kSvgfCpuGroupSizeY : kSvgfGroupSizeY;
  const ComputePipeline pipeline(context, load_port(context, "trace_gradient_select"),
                                 port_bindings(context, kGradientSelectTexelBindings, kGradientSelectStorageBindings),
                                 sizeof(GradientSelectPush), {int32_t(group_x), int32_t(group_y)});
  const GradientSelectPush push{.width = uint32_t(w),
                                .height = uint32_t(h),
                                .strata_x = uint32_t(strata_x),
                                .strata_y = uint32_t(strata_y),
                                .stratum_size = s,
                                .selection = params.selection,
                                .seed_chains = params.seed_chains,
                                .global_seed = global_seed,
                                .frame_index = frame_index};
  ComputeBatch batch(context, 1);
  batch.dispatch(pipeline, {instance_buffer.get(), was_gradient_buffer.get(), luminance_buffer.get(),
                            source_buffer.get()},
                 &push, group_count(uint32_t(strata_x), group_x), group_count(uint32_t(strata_y), group_y),
                 "trace_gradient_select");
  batch.run();
  batch.total_time(ms);
  for (size_t i = 0; i < sources.size(); ++i) sources[i] = word(*source_buffer, i);
  return sources;
}

GradientWinners gradient_winners_vulkan(VulkanContext& context, const std::vector<GradientCandidate>& candidates,
                                        int width, int height, int s, double* ms) {
  if (s < 1 || width < 0 || height < 0)
    throw Error("gradient_winners_vulkan: needs s >= 1 and a size >= 0, got s " + std::to_string(s) + " and " +
                std::to_string(width) + "x" + std::to_string(height));
  const size_t max_candidates = size_t(kGradientMergeGroupSize) * 65535u;  // maxComputeWorkGroupCount[0] >= 65535
  if (candidates.size() > max_candidates)
    throw Error("gradient_winners_vulkan: " + std::to_string(candidates.size()) + " candidates, one dispatch covers " +
                std::to_string(max_candidates));
  const int strata_x = (width + s - 1) / s, strata_y = (height + s - 1) / s;
  const size_t strata = size_t(strata_x) * size_t(strata_y);
  GradientWinners out{std::vector<uint32_t>(strata, kInvalidId), std::vector<uint32_t>(strata, kInvalidId)};
  if (candidates.empty() || strata == 0) return out;

  // Each candidate's j and its target pixel jbar as a linear index of frame i.
  const int n = int(candidates.size());
  UIntPlane source(n, 1), target(n, 1);
  for (size_t k = 0; k < candidates.size(); ++k) {
    const GradientCandidate& c = candidates[k];
    source.data[k] = c.source;
    if (c.source == kInvalidId) continue;  // no candidate: its target is not read
    if (c.target.x < 0 || c.target.y < 0 || c.target.x >= width || c.target.y >= height)
      throw Error("gradient_winners_vulkan: candidate " + std::to_string(k) + " lands at (" +
                  std::to_string(c.target.x) + ", " + std::to_string(c.target.y) + "), outside the " +
                  std::to_string(width) + "x" + std::to_string(height) + " frame");
    target.data[k] = uint32_t(c.target.y) * uint32_t(width) + uint32_t(c.target.x);
  }
  const auto source_buffer = plane_buffer(context, n, 1, TexelFormat::R32UI),
             target_buffer = plane_buffer(context, n, 1, TexelFormat::R32UI),
             min_source_buffer = plane_buffer(context, strata_x, strata_y, TexelFormat::R32UI),
             winner_buffer = plane_buffer(context, strata_x, strata_y, TexelFormat::R32UI);
  pack_ids(source, *source_buffer);
  pack_ids(target, *target_buffer);
  // GPU only: the slots start at kInvalidId, written through the mapping, as gradient_winners starts each stratum
  // with none.
  fill_invalid(*min_source_buffer);
  fill_invalid(*winner_buffer);

  const ComputePipeline pipeline(context, load_port(context, "trace_gradient_merge"),
                                 port_bindings(context, kGradientMergeTexelBindings, kGradientMergeStorageBindings),
                                 sizeof(GradientMergePush));
  GradientMergePush push{.width = uint32_t(width),
                         .height = uint32_t(height),
                         .strata_x = uint32_t(strata_x),
                         .strata_y = uint32_t(strata_y),
                         .stratum_size = s,
                         .candidates = uint32_t(n),
                         .phase = kGradientMergeMinSource};
  const std::vector<const GpuBuffer*> buffers = {source_buffer.get(), target_buffer.get(), min_source_buffer.get(),
                                                 winner_buffer.get()};
  const uint32_t groups = group_count(uint32_t(n), kGradientMergeGroupSize);
  // Two dispatches, the second after the first's atomics (ComputeBatch's barrier); each reads its own copy of the
  // push constants, recorded with the dispatch.
  GradientMergePush winner_push = push;
  winner_push.phase = kGradientMergeWinner;
  ComputeBatch batch(context, 2);
  batch.dispatch(pipeline, buffers, &push, groups, 1, "trace_gradient_merge min j");
  batch.dispatch(pipeline, buffers, &winner_push, groups, 1, "trace_gradient_merge winner");
  batch.run();
  batch.total_time(ms);
  for (size_t i = 0; i < strata; ++i) {
    out.candidate[i] = word(*winner_buffer, i);
    out.source[i] = word(*min_source_buffer, i);
  }
  return out;
}

}  // namespace rtdr
