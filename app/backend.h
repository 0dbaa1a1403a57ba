// Where a method runs: `--backend cpu` (the golden passes, filters/) or `--backend vulkan` (the shader ports:
// gpu/svgf_vulkan.h for svgf and asvgf, gpu/trmv_vulkan.h for trmv). rtdr filter, compare and bench choose through here, and rtdr eval through
// SpecMethods, by each method spec's backend=.
#pragma once

#include "eval/experiment.h"
#include "filters/method.h"
#include "gpu/vulkan_context.h"

#include <map>
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
BackendMethod make_backend_method(const std::string& backend, const std::string& method, const MethodParams& params);

// The Vulkan port of `method` on `context`: TrmvVulkan for trmv, SvgfVulkan for the others (which throws for a
// method whose stages have no port). Throws rtdr::Error for an unknown method.
std::unique_ptr<Method> make_vulkan_method(VulkanContext& context, const std::string& method,
                                           const MethodParams& params);

// The method's output frame for `in` with its dump's layers (every intermediate buffer, docs/buffers.md) added:
// what `rtdr filter --dump-passes` writes and `rtdr compare` compares.
Frame filter_with_dump(Method& method, const Frame& in);

// The methods of rtdr eval's specs (eval/experiment.h), each on the back end it names: EvalConfig::make_method.
// The Vulkan contexts, one per kind of illumination records asked for, are made when a spec first needs one;
// every method made must be gone before this is.
class SpecMethods {
 public:
  // Throws rtdr::Error like make_backend_method.
  std::unique_ptr<Method> make(const MethodSpec& spec);

 private:
  std::map<std::string, std::unique_ptr<VulkanContext>> contexts_;  // by MethodSpec::illumination
};

// "cpu", "vulkan", or a comma-separated list of them (rtdr bench); throws rtdr::Error on anything else.
std::vector<std::string> parse_backends(const std::string& text);

}  // namespace rtdr
