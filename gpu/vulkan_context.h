// The Vulkan device every port runs on: instance, physical device, one compute queue, one command pool.
//
// Device choice: the device whose name contains $RTDR_VK_DEVICE when that is set; else the first NVIDIA GPU;
// else the first device (on a machine with no GPU: lavapipe, "llvmpipe", mesa-vulkan-drivers). The shaders'
// input kind: VulkanOptions::inputs.
// With `validation`, the instance loads VK_LAYER_KHRONOS_validation and a VK_EXT_debug_utils messenger that
// counts the warnings and errors it reports and keeps their text, so tests can assert there were none.
// Failures throw rtdr::Error; available() says beforehand whether a context can be made at all.
#pragma once

#include <vulkan/vulkan.h>

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

namespace rtdr {

// How the ports read their input planes (core/shader_shared.h's RTDR_INPUT_*): as texel buffers, which lavapipe
// reads fastest, or as storage buffers, which a GPU reads fastest (docs/performance.md).
enum class ShaderInputs { Auto, Texel, Storage };
// "auto", "texel" or "storage": the spelling of $RTDR_VK_INPUTS and of reports.
const char* shader_inputs_name(ShaderInputs inputs);

// How the SVGF ports store illumination records, the planes the a-trous taps gather (filters/svgf/planes_shared.h):
// four floats (16 bytes), or four halves (8 bytes), which halve the bytes those taps pull through a GPU's caches
// at the cost of one rounding to 11 significant bits per store (docs/performance.md, "Packed illumination").
enum class IlluminationRecords { Auto, Fp32, Fp16 };
// "auto", "fp32" or "fp16": the spelling of $RTDR_VK_ILLUMINATION and of reports.
const char* illumination_records_name(IlluminationRecords records);

struct VulkanOptions {
  bool validation = false;  // load VK_LAYER_KHRONOS_validation and count its messages
  // Auto: $RTDR_VK_INPUTS (texel or storage) when set; else texel on a CPU device (lavapipe), storage on a GPU
  // that allows kStorageInputBindings storage buffers per shader stage (the Vulkan minimum is 4), else texel.
  // Texel inputs need kTexelInputBindings storage texel buffers per stage and the
  // shaderStorageImageExtendedFormats feature (for rg32f texels); the context throws when the kind asked for does
  // not fit the device.
  ShaderInputs inputs = ShaderInputs::Auto;
  // Auto: $RTDR_VK_ILLUMINATION (fp32 or fp16) when set; else fp32 on a CPU device, where bandwidth is not what
  // bounds the ports and the records then hold the golden passes' values exactly, and fp16 on a GPU.
  IlluminationRecords illumination = IlluminationRecords::Auto;
};

// The most storage buffers a port binds with storage inputs: the temporal pass's 15 planes (temporal_shared.h).
inline constexpr uint32_t kStorageInputBindings = 15;
// The most storage texel buffers a port binds with texel inputs: the temporal pass's 10 input planes.
inline constexpr uint32_t kTexelInputBindings = 10;

// What the validation layer said: warnings and errors only (info and verbose are not kept).
struct ValidationLog {
  int warnings = 0;
  int errors = 0;
  std::vector<std::string> messages;
};

class VulkanContext {
 public:
  explicit VulkanContext(const VulkanOptions& options = {});
  ~VulkanContext();
  VulkanContext(const VulkanContext&) = delete;
  VulkanContext& operator=(const VulkanContext&) = delete;

  // True when an instance and a device with a compute queue can be created; otherwise false, and `reason`
  // (when given) says why, for tests to print when they skip.
  static bool available(std::string* reason = nullptr);

  VkDevice device() const { return device_; }
  VkQueue queue() const { return queue_; }
  VkCommandPool command_pool() const { return command_pool_; }
  const std::string& device_name() const { return device_name_; }
  bool cpu_device() const { return cpu_device_; }  // a CPU implementation such as lavapipe, not a GPU
  ShaderInputs shader_inputs() const { return inputs_; }  // Texel or Storage, never Auto
  IlluminationRecords illumination_records() const { return illumination_; }  // Fp32 or Fp16, never Auto

  // Timestamp queries: supported when the compute queue has valid bits; a tick lasts timestamp_period_ns.
  bool has_timestamps() const { return timestamp_valid_bits_ > 0; }
  float timestamp_period_ns() const { return timestamp_period_ns_; }

  // The validation layer's warnings and errors so far (all zero without `validation`).
  const ValidationLog& validation_log() const { return *log_; }

  // A memory type index among `type_bits` with all of `properties`; throws rtdr::Error when there is none.
  uint32_t memory_type(uint32_t type_bits, VkMemoryPropertyFlags properties) const;

  // Where mapped buffers live, for benchmark reports: the size of the largest device-local heap the host can
  // map, e.g. "mappable device-local heap 80.0 GiB", or "no mappable device-local memory".
  std::string memory_summary() const;

 private:
  void release();  // destroys whatever was created, in reverse order; the destructor and a failed constructor

  std::unique_ptr<ValidationLog> log_;  // on the heap: the messenger keeps its address
  VkInstance instance_ = VK_NULL_HANDLE;
  VkDebugUtilsMessengerEXT messenger_ = VK_NULL_HANDLE;
  VkPhysicalDevice physical_device_ = VK_NULL_HANDLE;
  VkDevice device_ = VK_NULL_HANDLE;
  VkQueue queue_ = VK_NULL_HANDLE;
  VkCommandPool command_pool_ = VK_NULL_HANDLE;
  std::string device_name_;
  bool cpu_device_ = false;
  ShaderInputs inputs_ = ShaderInputs::Texel;
  IlluminationRecords illumination_ = IlluminationRecords::Fp32;
  uint32_t timestamp_valid_bits_ = 0;
  float timestamp_period_ns_ = 0.0f;
};

// Throws rtdr::Error naming `what` when `result` is not VK_SUCCESS.
void vk_check(VkResult result, const char* what);

}  // namespace rtdr
