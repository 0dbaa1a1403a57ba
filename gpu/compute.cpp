// Buffers, pipelines and timed dispatches. See compute.h.
#include "gpu/compute.h"

#include "core/data_path.h"
#include "core/error.h"

#include <algorithm>
#include <cstring>
#include <fstream>

namespace rtdr {

namespace {

VkFormat vk_format(TexelFormat format) {
  switch (format) {
    case TexelFormat::R32F: return VK_FORMAT_R32_SFLOAT;
    case TexelFormat::RG32F: return VK_FORMAT_R32G32_SFLOAT;
    case TexelFormat::RGBA32F: return VK_FORMAT_R32G32B32A32_SFLOAT;
    case TexelFormat::RGBA16F: return VK_FORMAT_R16G16B16A16_SFLOAT;
    case TexelFormat::R32UI: return VK_FORMAT_R32_UINT;
    case TexelFormat::None: break;
  }
  return VK_FORMAT_UNDEFINED;
}

// The memory types a buffer of kind `memory` may live in, best first (compute.h's Memory). Always host-visible
// and host-coherent. Device: device-local where the host can map it, then host memory, which also serves a GPU
// whose mappable device-local heap (256 MiB without a resizable BAR) is full. Readback: host-cached first.
std::vector<uint32_t> mappable_memory_types(const VulkanContext& context, uint32_t type_bits, Memory memory) {
  const VkMemoryPropertyFlags mapped = VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT | VK_MEMORY_PROPERTY_HOST_COHERENT_BIT;
  const VkMemoryPropertyFlags preferred =
      memory == Memory::Device ? VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT : VK_MEMORY_PROPERTY_HOST_CACHED_BIT;
  std::vector<uint32_t> types;
  for (const VkMemoryPropertyFlags wanted : {mapped | preferred, mapped}) {
    try {
      const uint32_t type = context.memory_type(type_bits, wanted);
      if (std::find(types.begin(), types.end(), type) == types.end()) types.push_back(type);
    } catch (const Error&) {
      // no such type on this device: the next kind
    }
  }
  if (types.empty()) throw Error("Vulkan: no host-visible, host-coherent memory on " + context.device_name());
  return types;
}

}  // namespace

size_t texel_floats(TexelFormat format) {
  switch (format) {
    case TexelFormat::RGBA32F: return 4;
    case TexelFormat::RG32F:
    case TexelFormat::RGBA16F: return 2;
    default: return 1;
  }
}

GpuBuffer::GpuBuffer(VulkanContext& context, size_t floats, TexelFormat format, Memory memory)
    : device_(context.device()), floats_(floats), format_(format) {
  if (floats == 0) throw Error("GpuBuffer: a buffer needs at least one float");
  if (floats % texel_floats(format) != 0)
    throw Error("GpuBuffer: " + std::to_string(floats) + " floats are not whole texels of " +
                std::to_string(texel_floats(format)));
  try {
    VkBufferCreateInfo info{.sType = VK_STRUCTURE_TYPE_BUFFER_CREATE_INFO};
    info.size = floats * sizeof(float);
    info.usage = VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | VK_BUFFER_USAGE_STORAGE_TEXEL_BUFFER_BIT |
                 VK_BUFFER_USAGE_TRANSFER_SRC_BIT | VK_BUFFER_USAGE_TRANSFER_DST_BIT;
    info.sharingMode = VK_SHARING_MODE_EXCLUSIVE;
    vk_check(vkCreateBuffer(device_, &info, nullptr, &buffer_), "vkCreateBuffer");
    VkMemoryRequirements needs;
    vkGetBufferMemoryRequirements(device_, buffer_, &needs);
    VkMemoryAllocateInfo allocate{.sType = VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_INFO};
    allocate.allocationSize = needs.size;
    // Host-coherent: no flush after upload() nor invalidate before download(). A full heap moves on to the next
    // type; the last type's failure is the error.
    const std::vector<uint32_t> types = mappable_memory_types(context, needs.memoryTypeBits, memory);
    VkResult allocated = VK_ERROR_OUT_OF_DEVICE_MEMORY;
    for (size_t t = 0; t < types.size() && allocated != VK_SUCCESS; ++t) {
      allocate.memoryTypeIndex = types[t];
      allocated = vkAllocateMemory(device_, &allocate, nullptr, &memory_);
    }
    vk_check(allocated, "vkAllocateMemory");
    vk_check(vkBindBufferMemory(device_, buffer_, memory_, 0), "vkBindBufferMemory");
    void* mapped = nullptr;
    vk_check(vkMapMemory(device_, memory_, 0, VK_WHOLE_SIZE, 0, &mapped), "vkMapMemory");
    mapped_ = static_cast<float*>(mapped);
    if (format != TexelFormat::None) {
      VkBufferViewCreateInfo view{.sType = VK_STRUCTURE_TYPE_BUFFER_VIEW_CREATE_INFO};
      view.buffer = buffer_;
      view.format = vk_format(format);
      view.range = VK_WHOLE_SIZE;
      vk_check(vkCreateBufferView(device_, &view, nullptr, &view_), "vkCreateBufferView");
    }
  } catch (...) {
    release();
    throw;
  }
}

GpuBuffer::~GpuBuffer() { release(); }

void GpuBuffer::release() {
  vkDestroyBufferView(device_, view_, nullptr);  // destroying VK_NULL_HANDLE is a no-op
  if (mapped_) vkUnmapMemory(device_, memory_);
  vkFreeMemory(device_, memory_, nullptr);
  vkDestroyBuffer(device_, buffer_, nullptr);
  view_ = VK_NULL_HANDLE;
  mapped_ = nullptr;
  memory_ = VK_NULL_HANDLE;
  buffer_ = VK_NULL_HANDLE;
}

void GpuBuffer::upload(std::span<const float> values) {
  if (values.size() != floats_)
    throw Error("GpuBuffer::upload: " + std::to_string(values.size()) + " floats into a buffer of " +
                std::to_string(floats_));
  std::memcpy(mapped_, values.data(), floats_ * sizeof(float));
}

std::vector<float> GpuBuffer::download() const { return std::vector<float>(mapped_, mapped_ + floats_); }

std::vector<uint32_t> load_shader(const std::string& stem) {
  const std::string path = data_path("shaders", RTDR_SHADER_DIR) + "/" + stem + ".spv";
  std::ifstream file(path, std::ios::binary | std::ios::ate);
  if (!file)
    throw Error("cannot open shader " + path + " (built by the rtdr_shaders target, installed in share/rtdr/shaders)");
  const std::streamsize bytes = file.tellg();
  if (bytes <= 0 || bytes % 4 != 0)
    throw Error("shader " + path + " is not SPIR-V (size " + std::to_string(bytes) + ")");
  std::vector<uint32_t> words(size_t(bytes) / 4);
  file.seekg(0);
  file.read(reinterpret_cast<char*>(words.data()), bytes);
  return words;
}

namespace {

VkDescriptorType descriptor_type(Binding binding) {
  return binding == Binding::Texel ? VK_DESCRIPTOR_TYPE_STORAGE_TEXEL_BUFFER : VK_DESCRIPTOR_TYPE_STORAGE_BUFFER;
}

}  // namespace

ComputePipeline::ComputePipeline(VulkanContext& context, const std::vector<uint32_t>& spirv,
                                 std::vector<Binding> bindings, uint32_t push_bytes,
                                 const std::vector<int32_t>& specialization)
    : context_(context), bindings_(std::move(bindings)), push_bytes_(push_bytes) {
  VkDevice device = context.device();
  try {
    VkShaderModuleCreateInfo module_info{.sType = VK_STRUCTURE_TYPE_SHADER_MODULE_CREATE_INFO};
    module_info.codeSize = spirv.size() * sizeof(uint32_t);
    module_info.pCode = spirv.data();
    vk_check(vkCreateShaderModule(device, &module_info, nullptr, &module_), "vkCreateShaderModule");

    // Set 0: binding i of the kind bindings_[i], used by the compute stage.
    std::vector<VkDescriptorSetLayoutBinding> layout_bindings(bindings_.size());
    for (uint32_t i = 0; i < bindings_.size(); ++i)
      layout_bindings[i] = {i, descriptor_type(bindings_[i]), 1, VK_SHADER_STAGE_COMPUTE_BIT, nullptr};
    VkDescriptorSetLayoutCreateInfo set_info{.sType = VK_STRUCTURE_TYPE_DESCRIPTOR_SET_LAYOUT_CREATE_INFO};
    set_info.bindingCount = uint32_t(layout_bindings.size());
    set_info.pBindings = layout_bindings.data();
    vk_check(vkCreateDescriptorSetLayout(device, &set_info, nullptr, &set_layout_), "vkCreateDescriptorSetLayout");

    const VkPushConstantRange push_range{VK_SHADER_STAGE_COMPUTE_BIT, 0, push_bytes};
    VkPipelineLayoutCreateInfo layout_info{.sType = VK_STRUCTURE_TYPE_PIPELINE_LAYOUT_CREATE_INFO};
    layout_info.setLayoutCount = 1;
    layout_info.pSetLayouts = &set_layout_;
    layout_info.pushConstantRangeCount = push_bytes > 0 ? 1 : 0;
    layout_info.pPushConstantRanges = &push_range;
    vk_check(vkCreatePipelineLayout(device, &layout_info, nullptr, &layout_), "vkCreatePipelineLayout");

    // Specialization constant i (constant_id = i) takes specialization[i], a 32-bit int.
    std::vector<VkSpecializationMapEntry> entries(specialization.size());
    for (uint32_t i = 0; i < entries.size(); ++i) entries[i] = {i, uint32_t(i * sizeof(int32_t)), sizeof(int32_t)};
    const VkSpecializationInfo constants{uint32_t(entries.size()), entries.data(),
                                         specialization.size() * sizeof(int32_t), specialization.data()};

    VkComputePipelineCreateInfo pipeline_info{.sType = VK_STRUCTURE_TYPE_COMPUTE_PIPELINE_CREATE_INFO};
    pipeline_info.stage = {.sType = VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO};
    pipeline_info.stage.stage = VK_SHADER_STAGE_COMPUTE_BIT;
    pipeline_info.stage.module = module_;
    pipeline_info.stage.pName = "main";
    pipeline_info.stage.pSpecializationInfo = specialization.empty() ? nullptr : &constants;
    pipeline_info.layout = layout_;
    vk_check(vkCreateComputePipelines(device, VK_NULL_HANDLE, 1, &pipeline_info, nullptr, &pipeline_),
             "vkCreateComputePipelines");
  } catch (...) {
    release();
    throw;
  }
}

ComputePipeline::ComputePipeline(VulkanContext& context, const std::vector<uint32_t>& spirv, uint32_t buffer_count,
                                 uint32_t push_bytes)
    : ComputePipeline(context, spirv, std::vector<Binding>(buffer_count, Binding::Storage), push_bytes) {}

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

void ComputePipeline::dispatch(const std::vector<const GpuBuffer*>& buffers, const void* push, uint32_t groups_x,
                               uint32_t groups_y, double* ms) {
  ComputeBatch batch(context_, 1);
  batch.dispatch(*this, buffers, push, groups_x, groups_y, "dispatch");
  batch.run();
  batch.total_time(ms);
}

namespace {

// Every binding kind a batch's descriptor pool serves, and how many of each one dispatch may use at most.
constexpr uint32_t kMaxBindingsPerKind = 32;

}  // namespace

ComputeBatch::ComputeBatch(VulkanContext& context, uint32_t max_commands)
    : context_(context), max_commands_(max_commands) {
  VkDevice device = context.device();
  try {
    // One descriptor set per dispatch, all freed at once when the next batch begins.
    const VkDescriptorPoolSize sizes[2] = {
        {VK_DESCRIPTOR_TYPE_STORAGE_TEXEL_BUFFER, kMaxBindingsPerKind * max_commands},
        {VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, kMaxBindingsPerKind * max_commands}};
    VkDescriptorPoolCreateInfo pool_info{.sType = VK_STRUCTURE_TYPE_DESCRIPTOR_POOL_CREATE_INFO};
    pool_info.maxSets = max_commands;
    pool_info.poolSizeCount = 2;
    pool_info.pPoolSizes = sizes;
    vk_check(vkCreateDescriptorPool(device, &pool_info, nullptr, &descriptor_pool_), "vkCreateDescriptorPool");
    if (context.has_timestamps()) {
      // Two timestamps per command: before and after it.
      VkQueryPoolCreateInfo query_info{.sType = VK_STRUCTURE_TYPE_QUERY_POOL_CREATE_INFO};
      query_info.queryType = VK_QUERY_TYPE_TIMESTAMP;
      query_info.queryCount = 2 * max_commands;
      vk_check(vkCreateQueryPool(device, &query_info, nullptr, &query_pool_), "vkCreateQueryPool");
    }
    VkCommandBufferAllocateInfo command_info{.sType = VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO};
    command_info.commandPool = context.command_pool();
    command_info.level = VK_COMMAND_BUFFER_LEVEL_PRIMARY;
    command_info.commandBufferCount = 1;
    vk_check(vkAllocateCommandBuffers(device, &command_info, &commands_), "vkAllocateCommandBuffers");
    VkFenceCreateInfo fence_info{.sType = VK_STRUCTURE_TYPE_FENCE_CREATE_INFO};
    vk_check(vkCreateFence(device, &fence_info, nullptr, &fence_), "vkCreateFence");
    begin();
  } catch (...) {
    release();
    throw;
  }
}

ComputeBatch::~ComputeBatch() { release(); }

void ComputeBatch::release() {
  VkDevice device = context_.device();
  vkDestroyFence(device, fence_, nullptr);
  if (commands_) vkFreeCommandBuffers(device, context_.command_pool(), 1, &commands_);
  vkDestroyQueryPool(device, query_pool_, nullptr);
  vkDestroyDescriptorPool(device, descriptor_pool_, nullptr);
  fence_ = VK_NULL_HANDLE;
  commands_ = VK_NULL_HANDLE;
  query_pool_ = VK_NULL_HANDLE;
  descriptor_pool_ = VK_NULL_HANDLE;
}

void ComputeBatch::begin() {
  VkDevice device = context_.device();
  vk_check(vkResetDescriptorPool(device, descriptor_pool_, 0), "vkResetDescriptorPool");
  vk_check(vkResetCommandBuffer(commands_, 0), "vkResetCommandBuffer");
  VkCommandBufferBeginInfo begin_info{.sType = VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO};
  vk_check(vkBeginCommandBuffer(commands_, &begin_info), "vkBeginCommandBuffer");
  if (query_pool_) vkCmdResetQueryPool(commands_, query_pool_, 0, 2 * max_commands_);
  labels_.clear();
}

void ComputeBatch::dispatch(const ComputePipeline& pipeline, const std::vector<const GpuBuffer*>& buffers,
                            const void* push, uint32_t groups_x, uint32_t groups_y, const std::string& label) {
  const std::vector<Binding>& kinds = pipeline.bindings();
  if (buffers.size() != kinds.size())
    throw Error("ComputeBatch::dispatch (" + label + "): " + std::to_string(buffers.size()) + " buffers for " +
                std::to_string(kinds.size()) + " bindings");
  open_command(label, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, VK_ACCESS_SHADER_READ_BIT | VK_ACCESS_SHADER_WRITE_BIT);
  VkDevice device = context_.device();

  // One descriptor set: buffers[i] at binding i, as a texel-buffer view or as a whole storage buffer.
  VkDescriptorSetAllocateInfo set_info{.sType = VK_STRUCTURE_TYPE_DESCRIPTOR_SET_ALLOCATE_INFO};
  set_info.descriptorPool = descriptor_pool_;
  set_info.descriptorSetCount = 1;
  const VkDescriptorSetLayout set_layout = pipeline.set_layout();
  set_info.pSetLayouts = &set_layout;
  VkDescriptorSet set = VK_NULL_HANDLE;
  vk_check(vkAllocateDescriptorSets(device, &set_info, &set), "vkAllocateDescriptorSets");
  std::vector<VkDescriptorBufferInfo> infos(kinds.size());
  std::vector<VkBufferView> views(kinds.size());
  std::vector<VkWriteDescriptorSet> writes(kinds.size());
  for (size_t i = 0; i < kinds.size(); ++i) {
    writes[i] = {.sType = VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET};
    writes[i].dstSet = set;
    writes[i].dstBinding = uint32_t(i);
    writes[i].descriptorCount = 1;
    writes[i].descriptorType = descriptor_type(kinds[i]);
    if (kinds[i] == Binding::Texel) {
      views[i] = buffers[i]->view();
      if (!views[i])
        throw Error("ComputeBatch::dispatch (" + label + "): binding " + std::to_string(i) +
                    " is a texel buffer but its buffer has no texel format");
      writes[i].pTexelBufferView = &views[i];
    } else {
      infos[i] = {buffers[i]->handle(), 0, VK_WHOLE_SIZE};
      writes[i].pBufferInfo = &infos[i];
    }
  }
  vkUpdateDescriptorSets(device, uint32_t(writes.size()), writes.data(), 0, nullptr);

  vkCmdBindPipeline(commands_, VK_PIPELINE_BIND_POINT_COMPUTE, pipeline.handle());
  vkCmdBindDescriptorSets(commands_, VK_PIPELINE_BIND_POINT_COMPUTE, pipeline.layout(), 0, 1, &set, 0, nullptr);
  if (pipeline.push_bytes() > 0)
    vkCmdPushConstants(commands_, pipeline.layout(), VK_SHADER_STAGE_COMPUTE_BIT, 0, pipeline.push_bytes(), push);
  vkCmdDispatch(commands_, groups_x, groups_y, 1);
  close_command(label);
}

void ComputeBatch::copy(const GpuBuffer& from, GpuBuffer& to, const std::string& label) {
  if (from.floats() != to.floats())
    throw Error("ComputeBatch::copy (" + label + "): " + std::to_string(from.floats()) + " floats into a buffer of " +
                std::to_string(to.floats()));
  open_command(label, VK_PIPELINE_STAGE_TRANSFER_BIT, VK_ACCESS_TRANSFER_READ_BIT | VK_ACCESS_TRANSFER_WRITE_BIT);
  const VkBufferCopy region{0, 0, from.floats() * sizeof(float)};
  vkCmdCopyBuffer(commands_, from.handle(), to.handle(), 1, &region);
  close_command(label);
}

void ComputeBatch::open_command(const std::string& label, VkPipelineStageFlags stage, VkAccessFlags access) {
  if (labels_.size() == max_commands_)
    throw Error("ComputeBatch (" + label + "): more than " + std::to_string(max_commands_) + " commands in one batch");
  // Each command reads what the commands before it wrote.
  if (!labels_.empty()) {
    VkMemoryBarrier barrier{.sType = VK_STRUCTURE_TYPE_MEMORY_BARRIER};
    barrier.srcAccessMask = VK_ACCESS_SHADER_WRITE_BIT | VK_ACCESS_TRANSFER_WRITE_BIT;
    barrier.dstAccessMask = access;
    vkCmdPipelineBarrier(commands_, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT | VK_PIPELINE_STAGE_TRANSFER_BIT, stage, 0,
                         1, &barrier, 0, nullptr, 0, nullptr);
  }
  // The start timestamp is latched once every command before has finished (bottom of pipe), so that the
  // commands' times do not overlap and add up to the batch's time; a top-of-pipe stamp would be latched at
  // once on a GPU, while the command before still runs.
  if (query_pool_)
    vkCmdWriteTimestamp(commands_, VK_PIPELINE_STAGE_BOTTOM_OF_PIPE_BIT, query_pool_, 2 * uint32_t(labels_.size()));
}

void ComputeBatch::close_command(const std::string& label) {
  if (query_pool_)
    vkCmdWriteTimestamp(commands_, VK_PIPELINE_STAGE_BOTTOM_OF_PIPE_BIT, query_pool_,
                        2 * uint32_t(labels_.size()) + 1);
  labels_.push_back(label);
}

void ComputeBatch::run(int submits) {
  VkDevice device = context_.device();
  // Make the shaders' and copies' writes visible to the host's reads (the buffers are host-coherent).
  VkMemoryBarrier barrier{.sType = VK_STRUCTURE_TYPE_MEMORY_BARRIER};
  barrier.srcAccessMask = VK_ACCESS_SHADER_WRITE_BIT | VK_ACCESS_TRANSFER_WRITE_BIT;
  barrier.dstAccessMask = VK_ACCESS_HOST_READ_BIT;
  vkCmdPipelineBarrier(commands_, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT | VK_PIPELINE_STAGE_TRANSFER_BIT,
                       VK_PIPELINE_STAGE_HOST_BIT, 0, 1, &barrier, 0, nullptr, 0, nullptr);
  vk_check(vkEndCommandBuffer(commands_), "vkEndCommandBuffer");
  VkSubmitInfo submit{.sType = VK_STRUCTURE_TYPE_SUBMIT_INFO};
  submit.commandBufferCount = 1;
  submit.pCommandBuffers = &commands_;
  for (int i = 0; i < std::max(submits, 1); ++i) {
    vk_check(vkResetFences(device, 1, &fence_), "vkResetFences");
    vk_check(vkQueueSubmit(context_.queue(), 1, &submit, fence_), "vkQueueSubmit");
    vk_check(vkWaitForFences(device, 1, &fence_, VK_TRUE, UINT64_MAX), "vkWaitForFences");
  }

  times_.clear();
  if (query_pool_ && !labels_.empty()) {
    std::vector<uint64_t> ticks(2 * labels_.size());
    vk_check(vkGetQueryPoolResults(device, query_pool_, 0, uint32_t(ticks.size()), ticks.size() * sizeof(uint64_t),
                                   ticks.data(), sizeof(uint64_t), VK_QUERY_RESULT_64_BIT | VK_QUERY_RESULT_WAIT_BIT),
             "vkGetQueryPoolResults");
    for (size_t i = 0; i < labels_.size(); ++i)
      times_.emplace_back(labels_[i],
                          double(ticks[2 * i + 1] - ticks[2 * i]) * double(context_.timestamp_period_ns()) * 1e-6);
  }
  begin();
}

void ComputeBatch::total_time(double* ms) const {
  if (!ms || times_.empty()) return;
  *ms = 0.0;
  for (const auto& [label, time] : times_) *ms += time;
}

}  // namespace rtdr
