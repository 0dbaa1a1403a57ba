// What the Vulkan back end's methods share (gpu/svgf_vulkan.h, gpu/trmv_vulkan.h): each records a frame's
// dispatches into one ComputeBatch, which rtdr bench reads command by command and may submit several times.
#pragma once

#include "core/error.h"
#include "filters/method.h"
#include "gpu/compute.h"

#include <memory>
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

  // The device planes for `in`'s size: `buffers` as they are, or made anew (Buffers(context, width, height)) for
  // the first frame or after a reset. A sequence keeps its size: with history, another size throws rtdr::Error, as
  // the golden methods do.
  template <class Buffers>
  static Buffers& frame_buffers(std::unique_ptr<Buffers>& buffers, VulkanContext& context, const Frame& in,
                                bool has_history) {
    const int w = in.width(), h = in.height();
    if (buffers && has_history && (buffers->width != w || buffers->height != h))
      throw Error(in.source + ": frame size changed within the sequence (" + std::to_string(w) + "x" +
                  std::to_string(h) + ", was " + std::to_string(buffers->width) + "x" +
                  std::to_string(buffers->height) + ")");
    if (!buffers || buffers->width != w || buffers->height != h) buffers = std::make_unique<Buffers>(context, w, h);
    return *buffers;
  }

  ComputeBatch batch_;
  int submits_ = 1;
};

}  // namespace rtdr
