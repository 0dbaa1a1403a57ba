// What the Vulkan back end's methods share (gpu/svgf_vulkan.h, gpu/trmv_vulkan.h): each records a frame's
// dispatches into one ComputeBatch, which rtdr bench reads command by command and may submit several times.
#pragma once

#include "filters/method.h"
#include "gpu/compute.h"

#include <string>
#include <utility>
#include <vector>

namespace rtdr {

class VulkanMethod : public Method {
 public:
  // The last frame's commands one by one, in order, with their device times in ms (empty without timestamps):
  // what pass_times() sums per pass, e.g. each a-trous level on its own.
  const std::vector<std::pair<std::string, double>>& command_times() const { return batch_.times(); }
  // Each frame's batch is submitted this many times (ComputeBatch::run; rtdr bench --submits). Default 1.
  void set_submits(int submits) { submits_ = submits; }

 protected:
  VulkanMethod(VulkanContext& context, uint32_t max_commands) : batch_(context, max_commands) {}
  ComputeBatch batch_;
  int submits_ = 1;
};

}  // namespace rtdr
