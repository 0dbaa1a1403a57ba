// Buffers, pipelines and timed dispatches. See compute.h.
#include "gpu/compute.h"

#include "core/error.h"

#include <algorithm>
#include <cstring>
#include <fstream>

namespace rtdr {

GpuBuffer::GpuBuffer(VulkanContext& context, size_t floats) : device_(context.device()), floats_(floats) {
  if (floats == 0) throw Error("GpuBuffer: a buffer needs at least one float");
  VkBufferCreateInfo info{.sType = VK_STRUCTURE_TYPE_BUFFER_CREATE_INFO};
  info.size = floats * sizeof(float);
  info.usage = VK_BUFFER_USAGE_STORAGE_BUFFER_BIT;
  info.sharingMode = VK_SHARING_MODE_EXCLUSIVE;
  vk_check(vkCreateBuffer(device_, &info, nullptr, &buffer_), "vkCreateBuffer");
  VkMemoryRequirements needs;
  vkGetBufferMemoryRequirements(device_, buffer_, &needs);
  VkMemoryAllocateInfo allocate{.sType = VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_INFO};
  allocate.allocationSize = needs.size;
  try {
    // Host-coherent: no flush after upload() nor invalidate before download().
    allocate.memoryTypeIndex = context.memory_type(
        needs.memoryTypeBits, VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT | VK_MEMORY_PROPERTY_HOST_COHERENT_BIT);
    vk_check(vkAllocateMemory(device_, &allocate, nullptr, &memory_), "vkAllocateMemory");
    vk_check(vkBindBufferMemory(device_, buffer_, memory_, 0), "vkBindBufferMemory");
    void* mapped = nullptr;
    vk_check(vkMapMemory(device_, memory_, 0, VK_WHOLE_SIZE, 0, &mapped), "vkMapMemory");
    mapped_ = static_cast<float*>(mapped);
  } catch (...) {
    if (memory_) vkFreeMemory(device_, memory_, nullptr);
    vkDestroyBuffer(device_, buffer_, nullptr);
    throw;
  }
}

GpuBuffer::~GpuBuffer() {
  vkUnmapMemory(device_, memory_);
  vkFreeMemory(device_, memory_, nullptr);
  vkDestroyBuffer(device_, buffer_, nullptr);
}

void GpuBuffer::upload(std::span<const float> values) {
  if (values.size() != floats_)
    throw Error("GpuBuffer::upload: " + std::to_string(values.size()) + " floats into a buffer of " +
                std::to_string(floats_));
  std::memcpy(mapped_, values.data(), floats_ * sizeof(float));
}

std::vector<float> GpuBuffer::download() const { return std::vector<float>(mapped_, mapped_ + floats_); }

std::vector<uint32_t> load_shader(const std::string& stem) {
  const std::string path = std::string(RTDR_SHADER_DIR) + "/" + stem + ".spv";
  std::ifstream file(path, std::ios::binary | std::ios::ate);
  if (!file) throw Error("cannot open shader " + path + " (built by the rtdr_shaders target)");
  const std::streamsize bytes = file.tellg();
  if (bytes <= 0 || bytes % 4 != 0)
    throw Error("shader " + path + " is not SPIR-V (size " + std::to_string(bytes) + ")");
  std::vector<uint32_t> words(size_t(bytes) / 4);
  file.seekg(0);
  file.read(reinterpret_cast<char*>(words.data()), bytes);
  return words;
}

ComputePipeline::ComputePipeline(VulkanContext& context, const std::vector<uint32_t>& spirv,
                                 uint32_t buffer_count, uint32_t push_bytes)
    : context_(context), buffer_count_(buffer_count), push_bytes_(push_bytes) {
  VkDevice device = context.device();
  try {
    VkShaderModuleCreateInfo module_info{.sType = VK_STRUCTURE_TYPE_SHADER_MODULE_CREATE_INFO};
    module_info.codeSize = spirv.size() * sizeof(uint32_t);
    module_info.pCode = spirv.data();
    vk_check(vkCreateShaderModule(device, &module_info, nullptr, &module_), "vkCreateShaderModule");

    // Set 0: storage buffers at bindings 0..buffer_count-1, all read or written by the compute stage.
    std::vector<VkDescriptorSetLayoutBinding> bindings(buffer_count);
    for (uint32_t i = 0; i < buffer_count; ++i)
      bindings[i] = {i, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, 1, VK_SHADER_STAGE_COMPUTE_BIT, nullptr};
    VkDescriptorSetLayoutCreateInfo set_info{.sType = VK_STRUCTURE_TYPE_DESCRIPTOR_SET_LAYOUT_CREATE_INFO};
    set_info.bindingCount = buffer_count;
    set_info.pBindings = bindings.data();
    vk_check(vkCreateDescriptorSetLayout(device, &set_info, nullptr, &set_layout_), "vkCreateDescriptorSetLayout");

    const VkPushConstantRange push_range{VK_SHADER_STAGE_COMPUTE_BIT, 0, push_bytes};
    VkPipelineLayoutCreateInfo layout_info{.sType = VK_STRUCTURE_TYPE_PIPELINE_LAYOUT_CREATE_INFO};
    layout_info.setLayoutCount = 1;
    layout_info.pSetLayouts = &set_layout_;
    layout_info.pushConstantRangeCount = push_bytes > 0 ? 1 : 0;
    layout_info.pPushConstantRanges = &push_range;
    vk_check(vkCreatePipelineLayout(device, &layout_info, nullptr, &layout_), "vkCreatePipelineLayout");

    VkComputePipelineCreateInfo pipeline_info{.sType = VK_STRUCTURE_TYPE_COMPUTE_PIPELINE_CREATE_INFO};
    pipeline_info.stage = {.sType = VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO};
    pipeline_info.stage.stage = VK_SHADER_STAGE_COMPUTE_BIT;
    pipeline_info.stage.module = module_;
    pipeline_info.stage.pName = "main";
    pipeline_info.layout = layout_;
    vk_check(vkCreateComputePipelines(device, VK_NULL_HANDLE, 1, &pipeline_info, nullptr, &pipeline_),
             "vkCreateComputePipelines");
  } catch (...) {
    release();
    throw;
  }
}

ComputePipeline::~ComputePipeline() { release(); }

void ComputePipeline::release() {
  VkDevice device = context_.device();
  vkDestroyPipeline(device, pipeline_, nullptr);  // destroying VK_NULL_HANDLE is a no-op
  vkDestroyPipelineLayout(device, layout_, nullptr);
  vkDestroyDescriptorSetLayout(device, set_layout_, nullptr);
  vkDestroyShaderModule(device, module_, nullptr);
  pipeline_ = VK_NULL_HANDLE;
  layout_ = VK_NULL_HANDLE;
  set_layout_ = VK_NULL_HANDLE;
  module_ = VK_NULL_HANDLE;
}

namespace {

// The objects one dispatch creates, destroyed on every path out of dispatch().
struct DispatchObjects {
  VkDevice device;
  VkCommandPool command_pool;
  VkDescriptorPool descriptor_pool = VK_NULL_HANDLE;
  VkQueryPool query_pool = VK_NULL_HANDLE;
  VkCommandBuffer commands = VK_NULL_HANDLE;
  VkFence fence = VK_NULL_HANDLE;
  ~DispatchObjects() {
    vkDestroyFence(device, fence, nullptr);
    if (commands) vkFreeCommandBuffers(device, command_pool, 1, &commands);
    vkDestroyQueryPool(device, query_pool, nullptr);
    vkDestroyDescriptorPool(device, descriptor_pool, nullptr);
  }
};

}  // namespace

void ComputePipeline::dispatch(const std::vector<const GpuBuffer*>& buffers, const void* push, uint32_t groups_x,
                               uint32_t groups_y, double* ms) {
  if (buffers.size() != buffer_count_)
    throw Error("ComputePipeline::dispatch: " + std::to_string(buffers.size()) + " buffers for " +
                std::to_string(buffer_count_) + " bindings");
  VkDevice device = context_.device();
  DispatchObjects objects{device, context_.command_pool()};

  // One descriptor set: buffers[i] at binding i, whole buffer.
  const VkDescriptorPoolSize pool_size{VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, buffer_count_};
  VkDescriptorPoolCreateInfo pool_info{.sType = VK_STRUCTURE_TYPE_DESCRIPTOR_POOL_CREATE_INFO};
  pool_info.maxSets = 1;
  pool_info.poolSizeCount = 1;
  pool_info.pPoolSizes = &pool_size;
  vk_check(vkCreateDescriptorPool(device, &pool_info, nullptr, &objects.descriptor_pool), "vkCreateDescriptorPool");
  VkDescriptorSetAllocateInfo set_info{.sType = VK_STRUCTURE_TYPE_DESCRIPTOR_SET_ALLOCATE_INFO};
  set_info.descriptorPool = objects.descriptor_pool;
  set_info.descriptorSetCount = 1;
  set_info.pSetLayouts = &set_layout_;
  VkDescriptorSet set = VK_NULL_HANDLE;
  vk_check(vkAllocateDescriptorSets(device, &set_info, &set), "vkAllocateDescriptorSets");
  std::vector<VkDescriptorBufferInfo> infos(buffer_count_);
  std::vector<VkWriteDescriptorSet> writes(buffer_count_);
  for (uint32_t i = 0; i < buffer_count_; ++i) {
    infos[i] = {buffers[i]->handle(), 0, VK_WHOLE_SIZE};
    writes[i] = {.sType = VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET};
    writes[i].dstSet = set;
    writes[i].dstBinding = i;
    writes[i].descriptorCount = 1;
    writes[i].descriptorType = VK_DESCRIPTOR_TYPE_STORAGE_BUFFER;
    writes[i].pBufferInfo = &infos[i];
  }
  vkUpdateDescriptorSets(device, buffer_count_, writes.data(), 0, nullptr);

  const bool timed = context_.has_timestamps();
  if (timed) {
    VkQueryPoolCreateInfo query_info{.sType = VK_STRUCTURE_TYPE_QUERY_POOL_CREATE_INFO};
    query_info.queryType = VK_QUERY_TYPE_TIMESTAMP;
    query_info.queryCount = 2;
    vk_check(vkCreateQueryPool(device, &query_info, nullptr, &objects.query_pool), "vkCreateQueryPool");
  }

  VkCommandBufferAllocateInfo command_info{.sType = VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO};
  command_info.commandPool = objects.command_pool;
  command_info.level = VK_COMMAND_BUFFER_LEVEL_PRIMARY;
  command_info.commandBufferCount = 1;
  vk_check(vkAllocateCommandBuffers(device, &command_info, &objects.commands), "vkAllocateCommandBuffers");
  VkCommandBuffer commands = objects.commands;
  VkCommandBufferBeginInfo begin{.sType = VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO};
  begin.flags = VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT;
  vk_check(vkBeginCommandBuffer(commands, &begin), "vkBeginCommandBuffer");
  if (timed) vkCmdResetQueryPool(commands, objects.query_pool, 0, 2);
  vkCmdBindPipeline(commands, VK_PIPELINE_BIND_POINT_COMPUTE, pipeline_);
  vkCmdBindDescriptorSets(commands, VK_PIPELINE_BIND_POINT_COMPUTE, layout_, 0, 1, &set, 0, nullptr);
  if (push_bytes_ > 0) vkCmdPushConstants(commands, layout_, VK_SHADER_STAGE_COMPUTE_BIT, 0, push_bytes_, push);
  // The dispatch between two timestamps: the first once earlier work is done, the second when it is.
  if (timed) vkCmdWriteTimestamp(commands, VK_PIPELINE_STAGE_TOP_OF_PIPE_BIT, objects.query_pool, 0);
  vkCmdDispatch(commands, groups_x, groups_y, 1);
  if (timed) vkCmdWriteTimestamp(commands, VK_PIPELINE_STAGE_BOTTOM_OF_PIPE_BIT, objects.query_pool, 1);
  // Make the shader's writes visible to the host's reads (the buffers are host-coherent).
  VkMemoryBarrier barrier{.sType = VK_STRUCTURE_TYPE_MEMORY_BARRIER};
  barrier.srcAccessMask = VK_ACCESS_SHADER_WRITE_BIT;
  barrier.dstAccessMask = VK_ACCESS_HOST_READ_BIT;
  vkCmdPipelineBarrier(commands, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, VK_PIPELINE_STAGE_HOST_BIT, 0, 1, &barrier, 0,
                       nullptr, 0, nullptr);
  vk_check(vkEndCommandBuffer(commands), "vkEndCommandBuffer");

  VkFenceCreateInfo fence_info{.sType = VK_STRUCTURE_TYPE_FENCE_CREATE_INFO};
  vk_check(vkCreateFence(device, &fence_info, nullptr, &objects.fence), "vkCreateFence");
  VkSubmitInfo submit{.sType = VK_STRUCTURE_TYPE_SUBMIT_INFO};
  submit.commandBufferCount = 1;
  submit.pCommandBuffers = &commands;
  vk_check(vkQueueSubmit(context_.queue(), 1, &submit, objects.fence), "vkQueueSubmit");
  vk_check(vkWaitForFences(device, 1, &objects.fence, VK_TRUE, UINT64_MAX), "vkWaitForFences");

  if (timed && ms) {
    uint64_t ticks[2] = {0, 0};
    vk_check(vkGetQueryPoolResults(device, objects.query_pool, 0, 2, sizeof(ticks), ticks, sizeof(uint64_t),
                                   VK_QUERY_RESULT_64_BIT | VK_QUERY_RESULT_WAIT_BIT),
             "vkGetQueryPoolResults");
    *ms = double(ticks[1] - ticks[0]) * double(context_.timestamp_period_ns()) * 1e-6;
  }
}

}  // namespace rtdr
