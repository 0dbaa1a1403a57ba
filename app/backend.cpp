// Choosing the back end a method runs on. See backend.h.
#include "app/backend.h"

#include "core/error.h"
#include "filters/svgf/svgf.h"
#include "gpu/svgf_vulkan.h"
#include "gpu/trmv_vulkan.h"

#include <sstream>

namespace rtdr {

BackendMethod make_backend_method(const std::string& backend, const std::string& method, const MethodParams& params) {
  BackendMethod m;
  if (backend == "cpu") {
    m.method = make_method(method, params);
  } else if (backend == "vulkan") {
    m.context = std::make_unique<VulkanContext>();
    m.method = make_vulkan_method(*m.context, method, params);
  } else {
    throw Error("--backend '" + backend + "' is not one of: cpu, vulkan");
  }
  return m;
}

std::unique_ptr<Method> make_vulkan_method(VulkanContext& context, const std::string& method,
                                           const MethodParams& params) {
  // SVGF's pipelines run on SvgfVulkan; the one method with a class of its own (filters/method.cpp's registry),
  // trmv, on TrmvVulkan.
  if (is_svgf_pipeline(method)) return std::make_unique<SvgfVulkan>(context, method_options(method, params));
  return std::make_unique<TrmvVulkan>(context, params);
}

std::unique_ptr<Method> SpecMethods::make(const MethodSpec& spec) {
  if (spec.backend == "cpu") return make_method(spec.name, spec_params(spec));
  is_svgf_pipeline(spec.name);  // checks the method's name before a Vulkan context is made
  std::unique_ptr<VulkanContext>& context = contexts_[spec.illumination];
  if (!context) {
    VulkanOptions vulkan;  // "" leaves the records Auto
    for (const IlluminationRecords records : {IlluminationRecords::Fp32, IlluminationRecords::Fp16})
      if (spec.illumination == illumination_records_name(records)) vulkan.illumination = records;
    context = std::make_unique<VulkanContext>(vulkan);
  }
  return make_vulkan_method(*context, spec.name, spec_params(spec));
}

Frame filter_with_dump(Method& method, const Frame& in) {
  Frame dump(in.width(), in.height());
  Frame out = method.filter(in, &dump);
  for (const auto& [name, plane] : dump.float_channels()) out.add_float(name).data = plane.data;
  return out;
}

std::vector<std::string> parse_backends(const std::string& text) {
  std::vector<std::string> backends;
  std::stringstream ss(text);
  for (std::string name; std::getline(ss, name, ',');) {
    if (name != "cpu" && name != "vulkan") throw Error("--backend '" + name + "' is not one of: cpu, vulkan");
    backends.push_back(name);
  }
  if (backends.empty()) throw Error("--backend is empty: give cpu, vulkan or cpu,vulkan");
  return backends;
}

}  // namespace rtdr
