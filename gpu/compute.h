// Buffers, pipelines and timed dispatches: all a port needs to run one compute shader on planes.
//
// A GpuBuffer is a host-visible, host-coherent storage buffer, mapped for its whole life: upload() and
// download() are plain copies. A ComputePipeline is one shader (SPIR-V compiled at build time into
// RTDR_SHADER_DIR, see gpu/CMakeLists.txt) whose set 0 holds `buffer_count` storage buffers at bindings
// 0..buffer_count-1, plus one push-constant block. dispatch() records, submits and waits, and times the
// dispatch alone with two timestamp queries.
#pragma once

#include "gpu/vulkan_context.h"

#include <cstddef>
#include <cstdint>
#include <span>
#include <string>
#include <vector>

namespace rtdr {

class GpuBuffer {
 public:
  GpuBuffer(VulkanContext& context, size_t floats);  // room for `floats` floats (at least 1)
  ~GpuBuffer();
  GpuBuffer(const GpuBuffer&) = delete;
  GpuBuffer& operator=(const GpuBuffer&) = delete;

  size_t floats() const { return floats_; }
  VkBuffer handle() const { return buffer_; }
  void upload(std::span<const float> values);  // values.size() must equal floats()
  std::vector<float> download() const;

 private:
  VkDevice device_;
  size_t floats_;
  VkBuffer buffer_ = VK_NULL_HANDLE;
  VkDeviceMemory memory_ = VK_NULL_HANDLE;
  float* mapped_ = nullptr;
};

// The SPIR-V of the shader with file stem `stem` (modulate -> RTDR_SHADER_DIR/modulate.spv).
std::vector<uint32_t> load_shader(const std::string& stem);

class ComputePipeline {
 public:
  ComputePipeline(VulkanContext& context, const std::vector<uint32_t>& spirv, uint32_t buffer_count,
                  uint32_t push_bytes);
  ~ComputePipeline();
  ComputePipeline(const ComputePipeline&) = delete;
  ComputePipeline& operator=(const ComputePipeline&) = delete;

  // Runs groups_x * groups_y workgroups with buffers[i] at binding i and `push` (push_bytes long) as the
  // push constants, and waits. Writes the dispatch's device time in milliseconds to *ms when the queue has
  // timestamps (leaves it untouched otherwise). Host reads of the buffers are safe when it returns.
  void dispatch(const std::vector<const GpuBuffer*>& buffers, const void* push, uint32_t groups_x,
                uint32_t groups_y, double* ms = nullptr);

 private:
  void release();  // destroys whatever was created; the destructor and a failed constructor

  VulkanContext& context_;
  uint32_t buffer_count_;
  uint32_t push_bytes_;
  VkShaderModule module_ = VK_NULL_HANDLE;
  VkDescriptorSetLayout set_layout_ = VK_NULL_HANDLE;
  VkPipelineLayout layout_ = VK_NULL_HANDLE;
  VkPipeline pipeline_ = VK_NULL_HANDLE;
};

}  // namespace rtdr
