// Where a method runs: `--backend cpu` (the golden passes, filters/) or `--backend vulkan` (the shader ports,
// gpu/svgf_vulkan.h; svgf only). rtdr filter and rtdr bench --stage filter both choose through here.
#pragma once

#include "filters/method.h"
#include "gpu/vulkan_context.h"

#include <memory>
#include <string>
#include <vector>

namespace rtdr {

// A method and, for vulkan, the device it runs on (declared first, so it outlives the method).
struct BackendMethod {
  std::unique_ptr<VulkanContext> context;
  std::unique_ptr<Method> method;
};

// Throws rtdr::Error for an unknown back end or method, a method without a Vulkan port, or no Vulkan device.
BackendMethod make_backend_method(const std::string& backend, const std::string& method, const SvgfParams& params);

// The method's output frame for `in` with its dump's layers (every intermediate buffer, docs/buffers.md) added:
// what `rtdr filter --dump-passes` writes and `rtdr compare` compares.
Frame filter_with_dump(Method& method, const Frame& in);

// "cpu", "vulkan", or a comma-separated list of them (rtdr bench); throws rtdr::Error on anything else.
std::vector<std::string> parse_backends(const std::string& text);

}  // namespace rtdr
