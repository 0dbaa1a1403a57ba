// The Vulkan device every port runs on. See vulkan_context.h.
#include "gpu/vulkan_context.h"

#include "core/error.h"

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <initializer_list>
#include <string>

namespace rtdr {

namespace {

constexpr const char* kValidationLayer = "VK_LAYER_KHRONOS_validation";
constexpr uint32_t kNvidiaVendorId = 0x10DE;  // PCI vendor id of NVIDIA

// The debug messenger's callback: counts warnings and errors into the ValidationLog it was given.
VKAPI_ATTR VkBool32 VKAPI_CALL on_validation_message(VkDebugUtilsMessageSeverityFlagBitsEXT severity,
                                                     VkDebugUtilsMessageTypeFlagsEXT,
                                                     const VkDebugUtilsMessengerCallbackDataEXT* data,
                                                     void* user_data) {
  auto* log = static_cast<ValidationLog*>(user_data);
  if (severity & VK_DEBUG_UTILS_MESSAGE_SEVERITY_ERROR_BIT_EXT) ++log->errors;
  else ++log->warnings;
  log->messages.emplace_back(data->pMessage ? data->pMessage : "(no message)");
  return VK_FALSE;  // never abort the call that triggered the message
}

VkDebugUtilsMessengerCreateInfoEXT messenger_info(ValidationLog* log) {
  VkDebugUtilsMessengerCreateInfoEXT info{.sType = VK_STRUCTURE_TYPE_DEBUG_UTILS_MESSENGER_CREATE_INFO_EXT};
  info.messageSeverity =
      VK_DEBUG_UTILS_MESSAGE_SEVERITY_WARNING_BIT_EXT | VK_DEBUG_UTILS_MESSAGE_SEVERITY_ERROR_BIT_EXT;
  info.messageType = VK_DEBUG_UTILS_MESSAGE_TYPE_GENERAL_BIT_EXT | VK_DEBUG_UTILS_MESSAGE_TYPE_VALIDATION_BIT_EXT |
                     VK_DEBUG_UTILS_MESSAGE_TYPE_PERFORMANCE_BIT_EXT;
  info.pfnUserCallback = on_validation_message;
  info.pUserData = log;
  return info;
}

bool has_layer(const char* name) {
  uint32_t count = 0;
  vkEnumerateInstanceLayerProperties(&count, nullptr);
  std::vector<VkLayerProperties> layers(count);
  vkEnumerateInstanceLayerProperties(&count, layers.data());
  for (const auto& layer : layers)
    if (std::strcmp(layer.layerName, name) == 0) return true;
  return false;
}

// Vulkan 1.1: the version the shaders are compiled for (glslc --target-env=vulkan1.1, gpu/CMakeLists.txt).
VkInstance create_instance(bool validation, VkDebugUtilsMessengerCreateInfoEXT* messenger) {
  VkApplicationInfo app{.sType = VK_STRUCTURE_TYPE_APPLICATION_INFO};
  app.pApplicationName = "rtdr";
  app.apiVersion = VK_API_VERSION_1_1;
  VkInstanceCreateInfo info{.sType = VK_STRUCTURE_TYPE_INSTANCE_CREATE_INFO};
  info.pApplicationInfo = &app;
  const char* extension = VK_EXT_DEBUG_UTILS_EXTENSION_NAME;
  if (validation) {
    if (!has_layer(kValidationLayer))
      throw Error("Vulkan: validation asked for but VK_LAYER_KHRONOS_validation is not installed "
                  "(Debian package vulkan-validationlayers)");
    info.enabledLayerCount = 1;
    info.ppEnabledLayerNames = &kValidationLayer;
    info.enabledExtensionCount = 1;
    info.ppEnabledExtensionNames = &extension;
    info.pNext = messenger;  // also report on vkCreateInstance and vkDestroyInstance themselves
  }
  VkInstance instance = VK_NULL_HANDLE;
  vk_check(vkCreateInstance(&info, nullptr, &instance), "vkCreateInstance");
  return instance;
}

// The index of the first queue family with compute, or -1.
int compute_queue_family(VkPhysicalDevice device, uint32_t* timestamp_valid_bits = nullptr) {
  uint32_t count = 0;
  vkGetPhysicalDeviceQueueFamilyProperties(device, &count, nullptr);
  std::vector<VkQueueFamilyProperties> families(count);
  vkGetPhysicalDeviceQueueFamilyProperties(device, &count, families.data());
  for (uint32_t i = 0; i < count; ++i) {
    if (!(families[i].queueFlags & VK_QUEUE_COMPUTE_BIT)) continue;
    if (timestamp_valid_bits) *timestamp_valid_bits = families[i].timestampValidBits;
    return int(i);
  }
  return -1;
}

// $RTDR_VK_DEVICE's match, else the first NVIDIA device, else the first; only devices with compute count.
VkPhysicalDevice choose_device(VkInstance instance) {
  uint32_t count = 0;
  vkEnumeratePhysicalDevices(instance, &count, nullptr);
  std::vector<VkPhysicalDevice> devices(count);
  vkEnumeratePhysicalDevices(instance, &count, devices.data());
  const char* wanted = std::getenv("RTDR_VK_DEVICE");
  VkPhysicalDevice first = VK_NULL_HANDLE, nvidia = VK_NULL_HANDLE;
  std::string names;
  for (VkPhysicalDevice device : devices) {
    if (compute_queue_family(device) < 0) continue;
    VkPhysicalDeviceProperties properties;
    vkGetPhysicalDeviceProperties(device, &properties);
    names += std::string(names.empty() ? "" : ", ") + properties.deviceName;
    if (wanted && *wanted && std::strstr(properties.deviceName, wanted)) return device;
    if (!first) first = device;
    if (!nvidia && properties.vendorID == kNvidiaVendorId) nvidia = device;
  }
  if (wanted && *wanted)
    throw Error(std::string("Vulkan: no device name contains RTDR_VK_DEVICE=\"") + wanted + "\" (devices: " +
                (names.empty() ? "none" : names) + ")");
  if (!first) throw Error("Vulkan: no device with a compute queue");
  return nvidia ? nvidia : first;
}

// `wanted`, or where it is Auto and the environment variable `variable` is set, the kind that variable names
// (by `name`, one of `kinds`); Auto where neither says. Throws rtdr::Error for a name that is none of them.
template <class Kind>
Kind from_environment(Kind wanted, const char* variable, std::initializer_list<Kind> kinds,
                      const char* (*name)(Kind)) {
  const char* env = std::getenv(variable);
  if (wanted != Kind::Auto || !env || !*env) return wanted;
  std::string names;
  for (const Kind kind : kinds) {
    if (std::strcmp(env, name(kind)) == 0) return kind;
    names += std::string(names.empty() ? "" : " or ") + name(kind);
  }
  throw Error(std::string(variable) + " must be " + names + ", got \"" + env + "\"");
}

// VulkanOptions::inputs resolved for a device with `properties` and `features`.
ShaderInputs resolve_inputs(ShaderInputs wanted, const VkPhysicalDeviceProperties& properties,
                            const VkPhysicalDeviceFeatures& features) {
  const bool storage_fits = properties.limits.maxPerStageDescriptorStorageBuffers >= kStorageInputBindings;
  const bool texel_fits = properties.limits.maxPerStageDescriptorStorageImages >= kTexelInputBindings &&
                          features.shaderStorageImageExtendedFormats;
  wanted = from_environment(wanted, "RTDR_VK_INPUTS", {ShaderInputs::Texel, ShaderInputs::Storage},
                            shader_inputs_name);
  if (wanted == ShaderInputs::Auto)
    wanted = storage_fits && (properties.deviceType != VK_PHYSICAL_DEVICE_TYPE_CPU || !texel_fits)
                 ? ShaderInputs::Storage
                 : ShaderInputs::Texel;
  if (wanted == ShaderInputs::Storage && !storage_fits)
    throw Error(std::string("Vulkan: ") + properties.deviceName + " allows " +
                std::to_string(properties.limits.maxPerStageDescriptorStorageBuffers) +
                " storage buffers per stage; storage inputs need " + std::to_string(kStorageInputBindings));
  if (wanted == ShaderInputs::Texel && !texel_fits)
    throw Error(std::string("Vulkan: ") + properties.deviceName + " allows " +
                std::to_string(properties.limits.maxPerStageDescriptorStorageImages) +
                " storage texel buffers per stage" +
                (features.shaderStorageImageExtendedFormats ? "" : " and lacks shaderStorageImageExtendedFormats") +
                "; texel inputs need " + std::to_string(kTexelInputBindings) + " and that feature");
  return wanted;
}

}  // namespace

const char* shader_inputs_name(ShaderInputs inputs) {
  return inputs == ShaderInputs::Texel ? "texel" : inputs == ShaderInputs::Storage ? "storage" : "auto";
}

const char* illumination_records_name(IlluminationRecords records) {
  return records == IlluminationRecords::Fp32 ? "fp32" : records == IlluminationRecords::Fp16 ? "fp16" : "auto";
}

void vk_check(VkResult result, const char* what) {
  if (result != VK_SUCCESS)
    throw Error(std::string("Vulkan: ") + what + " failed (VkResult " + std::to_string(result) + ")");
}

bool VulkanContext::available(std::string* reason) {
  try {
    VkInstance instance = create_instance(false, nullptr);
    try {
      choose_device(instance);
    } catch (...) {
      vkDestroyInstance(instance, nullptr);
      throw;
    }
    vkDestroyInstance(instance, nullptr);
    return true;
  } catch (const Error& e) {
    if (reason) *reason = e.what();
    return false;
  }
}

VulkanContext::VulkanContext(const VulkanOptions& options) : log_(std::make_unique<ValidationLog>()) {
  VkDebugUtilsMessengerCreateInfoEXT messenger = messenger_info(log_.get());
  instance_ = create_instance(options.validation, &messenger);
  try {
    if (options.validation) {
      auto create = reinterpret_cast<PFN_vkCreateDebugUtilsMessengerEXT>(
          vkGetInstanceProcAddr(instance_, "vkCreateDebugUtilsMessengerEXT"));
      if (!create) throw Error("Vulkan: vkCreateDebugUtilsMessengerEXT is missing");
      vk_check(create(instance_, &messenger, nullptr, &messenger_), "vkCreateDebugUtilsMessengerEXT");
    }
    physical_device_ = choose_device(instance_);
    VkPhysicalDeviceProperties properties;
    vkGetPhysicalDeviceProperties(physical_device_, &properties);
    device_name_ = properties.deviceName;
    cpu_device_ = properties.deviceType == VK_PHYSICAL_DEVICE_TYPE_CPU;
    VkPhysicalDeviceFeatures features;
    vkGetPhysicalDeviceFeatures(physical_device_, &features);
    inputs_ = resolve_inputs(options.inputs, properties, features);
    illumination_ = from_environment(options.illumination, "RTDR_VK_ILLUMINATION",
                                     {IlluminationRecords::Fp32, IlluminationRecords::Fp16}, illumination_records_name);
    if (illumination_ == IlluminationRecords::Auto)
      illumination_ = cpu_device_ ? IlluminationRecords::Fp32 : IlluminationRecords::Fp16;
    timestamp_period_ns_ = properties.limits.timestampPeriod;
    const uint32_t family = uint32_t(compute_queue_family(physical_device_, &timestamp_valid_bits_));

    const float priority = 1.0f;
    VkDeviceQueueCreateInfo queue_info{.sType = VK_STRUCTURE_TYPE_DEVICE_QUEUE_CREATE_INFO};
    queue_info.queueFamilyIndex = family;
    queue_info.queueCount = 1;
    queue_info.pQueuePriorities = &priority;
    // Texel inputs read rg32f storage texels (core/shader_shared.h), which need this feature.
    VkPhysicalDeviceFeatures enabled{};
    enabled.shaderStorageImageExtendedFormats = inputs_ == ShaderInputs::Texel;
    VkDeviceCreateInfo device_info{.sType = VK_STRUCTURE_TYPE_DEVICE_CREATE_INFO};
    device_info.queueCreateInfoCount = 1;
    device_info.pQueueCreateInfos = &queue_info;
    device_info.pEnabledFeatures = &enabled;
    vk_check(vkCreateDevice(physical_device_, &device_info, nullptr, &device_), "vkCreateDevice");
    vkGetDeviceQueue(device_, family, 0, &queue_);

    VkCommandPoolCreateInfo pool_info{.sType = VK_STRUCTURE_TYPE_COMMAND_POOL_CREATE_INFO};
    pool_info.flags = VK_COMMAND_POOL_CREATE_RESET_COMMAND_BUFFER_BIT;
    pool_info.queueFamilyIndex = family;
    vk_check(vkCreateCommandPool(device_, &pool_info, nullptr, &command_pool_), "vkCreateCommandPool");
  } catch (...) {
    release();
    throw;
  }
}

VulkanContext::~VulkanContext() { release(); }

void VulkanContext::release() {
  if (command_pool_) vkDestroyCommandPool(device_, command_pool_, nullptr);
  if (device_) vkDestroyDevice(device_, nullptr);
  if (messenger_) {
    auto destroy = reinterpret_cast<PFN_vkDestroyDebugUtilsMessengerEXT>(
        vkGetInstanceProcAddr(instance_, "vkDestroyDebugUtilsMessengerEXT"));
    destroy(instance_, messenger_, nullptr);
  }
  if (instance_) vkDestroyInstance(instance_, nullptr);
  command_pool_ = VK_NULL_HANDLE;
  device_ = VK_NULL_HANDLE;
  messenger_ = VK_NULL_HANDLE;
  instance_ = VK_NULL_HANDLE;
}

uint32_t VulkanContext::memory_type(uint32_t type_bits, VkMemoryPropertyFlags properties) const {
  VkPhysicalDeviceMemoryProperties memory;
  vkGetPhysicalDeviceMemoryProperties(physical_device_, &memory);
  for (uint32_t i = 0; i < memory.memoryTypeCount; ++i)
    if ((type_bits & (1u << i)) && (memory.memoryTypes[i].propertyFlags & properties) == properties) return i;
  throw Error("Vulkan: no memory type with the requested properties on " + device_name_);
}

std::string VulkanContext::memory_summary() const {
  VkPhysicalDeviceMemoryProperties memory;
  vkGetPhysicalDeviceMemoryProperties(physical_device_, &memory);
  const VkMemoryPropertyFlags wanted = VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT | VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT;
  VkDeviceSize largest = 0;
  for (uint32_t i = 0; i < memory.memoryTypeCount; ++i)
    if ((memory.memoryTypes[i].propertyFlags & wanted) == wanted)
      largest = std::max(largest, memory.memoryHeaps[memory.memoryTypes[i].heapIndex].size);
  if (largest == 0) return "no mappable device-local memory";
  char text[64];
  std::snprintf(text, sizeof text, "mappable device-local heap %.1f GiB", double(largest) / (1u << 30));
  return text;
}

}  // namespace rtdr
