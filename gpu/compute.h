// Buffers, pipelines and timed dispatches: all a port needs to run compute shaders on planes.
//
// A GpuBuffer is a storage buffer mapped for its whole life (host-visible and host-coherent; where it lives:
// Memory, below): upload() and download() are plain copies. Given a texel format it also has a buffer view, so
// shaders can read it as an `imageBuffer` / `uimageBuffer` and imageLoad() whole texels.
//
// A ComputePipeline is one shader (SPIR-V compiled at build time into RTDR_SHADER_DIR, see gpu/CMakeLists.txt)
// whose set 0 holds one binding per entry of its Binding list, in order, plus one push-constant block:
//   Binding::Texel    a storage texel buffer, read with imageLoad (the buffer needs a texel format);
//   Binding::Storage  a storage buffer, read or written as an std430 array.
// Why texel buffers for inputs on lavapipe: a storage-buffer load runs one lane at a time and one 32-bit
// component at a time, while an image load gathers a whole texel for all lanes at once (3x faster measured on
// the remodulation shader). Storage texel buffers rather than uniform ones (texelFetch): lavapipe compiles a
// texelFetch of a float format into a call, and the shader spills its registers around each call; an unrolled
// a-trous level runs 10% fewer instructions with image loads, and 1.2x faster (docs/performance.md). On a GPU the
// ports read storage buffers (core/shader_shared.h).
//
// A ComputeBatch records several dispatches, and copies into readback buffers, into one command buffer, with a
// barrier between consecutive ones (each sees the previous ones' writes), submits them once and waits; each is
// timed by timestamp queries. ComputePipeline::dispatch is the batch of one.
#pragma once

#include "gpu/vulkan_context.h"

#include <cstddef>
#include <cstdint>
#include <span>
#include <string>
#include <utility>
#include <vector>

namespace rtdr {

// The texel formats a GpuBuffer can be viewed with: 1, 2 or 4 floats, 4 halves, or 1 uint, per texel.
enum class TexelFormat { None, R32F, RG32F, RGBA32F, RGBA16F, R32UI };
// 32-bit words per texel: 1, 2 or 4 (RGBA16F: 2; None: 1). A GpuBuffer counts its size in such words ("floats").
size_t texel_floats(TexelFormat format);

// Where a buffer's memory lives. Both kinds are mapped and host-coherent.
//   Device:   what the shaders read and write: device-local memory the host can map where the device has it
//             (lavapipe: all of it; a GPU with a resizable BAR), else host memory. The host writes it well
//             (write-combined, in order) but reads it slowly on a GPU: uncached, across the bus.
//   Readback: host-cached memory for results the host reads: ComputeBatch::copy fills it from a Device buffer.
enum class Memory { Device, Readback };

class GpuBuffer {
 public:
  // Room for `floats` floats (at least 1); with a format, a view of the whole buffer in that format (`floats`
  // must then be a multiple of the texel's size).
  GpuBuffer(VulkanContext& context, size_t floats, TexelFormat format = TexelFormat::None,
            Memory memory = Memory::Device);
  ~GpuBuffer();
  GpuBuffer(const GpuBuffer&) = delete;
  GpuBuffer& operator=(const GpuBuffer&) = delete;

  size_t floats() const { return floats_; }
  TexelFormat format() const { return format_; }
  VkBuffer handle() const { return buffer_; }
  VkBufferView view() const { return view_; }  // VK_NULL_HANDLE without a format
  void upload(std::span<const float> values);  // values.size() must equal floats()
  std::vector<float> download() const;
  // The mapped memory itself, for packing inputs in place and reading results without a copy. Valid for the
  // buffer's life; the device must not be using the buffer meanwhile.
  float* data() { return mapped_; }
  const float* data() const { return mapped_; }

 private:
  void release();

  VkDevice device_;
  size_t floats_;
  TexelFormat format_;
  VkBuffer buffer_ = VK_NULL_HANDLE;
  VkDeviceMemory memory_ = VK_NULL_HANDLE;
  VkBufferView view_ = VK_NULL_HANDLE;
  float* mapped_ = nullptr;
};

// The SPIR-V called `stem` (modulate -> shaders/modulate.spv of the build folder, or of <prefix>/share/rtdr once
// installed: core/data_path.h): a shader's file stem for SVGF's ports and
// for a shader named after its folder, else <folder>_<stem> (filters/trmv/temporal.comp -> trmv_temporal), as
// gpu/CMakeLists.txt names them.
std::vector<uint32_t> load_shader(const std::string& stem);

enum class Binding { Texel, Storage };

class ComputePipeline {
 public:
  // `specialization`: the values of the shader's int specialization constants, constant_id i = entry i.
  ComputePipeline(VulkanContext& context, const std::vector<uint32_t>& spirv, std::vector<Binding> bindings,
                  uint32_t push_bytes, const std::vector<int32_t>& specialization = {});
  // A shader whose `buffer_count` bindings are all storage buffers.
  ComputePipeline(VulkanContext& context, const std::vector<uint32_t>& spirv, uint32_t buffer_count,
                  uint32_t push_bytes);
  ~ComputePipeline();
  ComputePipeline(const ComputePipeline&) = delete;
  ComputePipeline& operator=(const ComputePipeline&) = delete;

  const std::vector<Binding>& bindings() const { return bindings_; }
  uint32_t push_bytes() const { return push_bytes_; }
  VkPipeline handle() const { return pipeline_; }
  VkPipelineLayout layout() const { return layout_; }
  VkDescriptorSetLayout set_layout() const { return set_layout_; }

  // Runs groups_x * groups_y workgroups with buffers[i] at binding i and `push` (push_bytes long) as the
  // push constants, and waits. Writes the dispatch's device time in milliseconds to *ms when the queue has
  // timestamps (leaves it untouched otherwise). Host reads of the buffers are safe when it returns.
  void dispatch(const std::vector<const GpuBuffer*>& buffers, const void* push, uint32_t groups_x,
                uint32_t groups_y, double* ms = nullptr);

 private:
  void release();  // destroys whatever was created; the destructor and a failed constructor

  VulkanContext& context_;
  std::vector<Binding> bindings_;
  uint32_t push_bytes_;
  VkShaderModule module_ = VK_NULL_HANDLE;
  VkDescriptorSetLayout set_layout_ = VK_NULL_HANDLE;
  VkPipelineLayout layout_ = VK_NULL_HANDLE;
  VkPipeline pipeline_ = VK_NULL_HANDLE;
};

// Workgroups of `group` invocations along an axis of `pixels`: enough to cover it, the last one overhanging.
inline uint32_t group_count(uint32_t pixels, uint32_t group) { return (pixels + group - 1) / group; }

class ComputeBatch {
 public:
  // Room for up to `max_commands` dispatches and copies per run().
  ComputeBatch(VulkanContext& context, uint32_t max_commands);
  ~ComputeBatch();
  ComputeBatch(const ComputeBatch&) = delete;
  ComputeBatch& operator=(const ComputeBatch&) = delete;

  // Records one dispatch, after every one recorded before it (a barrier orders their memory accesses). `label`
  // names its time in times(). The buffers must outlive run().
  void dispatch(const ComputePipeline& pipeline, const std::vector<const GpuBuffer*>& buffers, const void* push,
                uint32_t groups_x, uint32_t groups_y, const std::string& label);
  // Records a copy of all of `from` into `to` (the same size), after every dispatch recorded before it: how
  // results reach a Memory::Readback buffer. Timed like a dispatch, under `label`.
  void copy(const GpuBuffer& from, GpuBuffer& to, const std::string& label);
  // Submits what was recorded, waits, and makes the writes visible to the host; then starts a new batch. With
  // submits > 1 the same commands run that many times back to back, each after the last has finished, and times()
  // are the last run's: for timing a GPU at its working clock. Only for commands whose reruns give the same
  // result: a frame of SvgfVulkan or TrmvVulkan reads only its inputs, the last frame's histories and what the
  // batch wrote before, and overwrites none of them later in the batch.
  void run(int submits = 1);
  // Each dispatch of the last run(): its label and device time in milliseconds (empty without timestamps).
  const std::vector<std::pair<std::string, double>>& times() const { return times_; }
  // Writes the last run's device time in milliseconds, summed over its dispatches, to *ms; leaves *ms untouched
  // without timestamps (or when ms is null).
  void total_time(double* ms) const;

 private:
  void begin();
  void release();
  // Checks there is room for one more command and orders it after the ones before (`stage`, `access`: what it
  // does); then writes its start timestamp.
  void open_command(const std::string& label, VkPipelineStageFlags stage, VkAccessFlags access);
  void close_command(const std::string& label);  // its end timestamp

  VulkanContext& context_;
  uint32_t max_commands_;
  VkDescriptorPool descriptor_pool_ = VK_NULL_HANDLE;
  VkQueryPool query_pool_ = VK_NULL_HANDLE;
  VkCommandBuffer commands_ = VK_NULL_HANDLE;
  VkFence fence_ = VK_NULL_HANDLE;
  std::vector<std::string> labels_;
  std::vector<std::pair<std::string, double>> times_;
};

}  // namespace rtdr
