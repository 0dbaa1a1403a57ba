// The table of port_bounds.h. Each number is derived, or chosen as a guard, in the banner of the test named beside it.
#include "gpu/port_bounds.h"

#include <fnmatch.h>

namespace rtdr {
namespace {

// SVGF's colour bound [tests/gpu_svgf_test.cpp]: the a-trous levels' 5e-5 each, carried by the colour history
// at 0.8 a frame, and room for the weights' second-order effect (fp32 records); 7 stores into halves (fp16).
constexpr double kSvgfColour = 2e-3, kSvgfColourFp16 = 2e-2;

}  // namespace

const std::vector<PortBound>& port_bounds() {
  static const std::vector<PortBound> table = {
      // method, channels,                 relative, fp32,  fp16,  derived, test
      {"svgf", "color.[RGB]", true, kSvgfColour, kSvgfColourFp16, true, "tests/gpu_svgf_test.cpp"},
      // The dump's colours (temporal, each level, filtered, tone mapped) and mu1', convex combinations of the same
      // inputs; mu2', of squared luminances: the square of that bound; the history length: exact.
      {"svgf", "filter.*.[RGB]", true, kSvgfColour, kSvgfColourFp16, true, "tests/gpu_svgf_test.cpp"},
      {"svgf", "filter.*.moments.mu1", true, kSvgfColour, kSvgfColourFp16, true, "tests/gpu_svgf_test.cpp"},
      {"svgf", "filter.*.moments.mu2", true, (1 + kSvgfColour) * (1 + kSvgfColour) - 1,
       (1 + kSvgfColourFp16) * (1 + kSvgfColourFp16) - 1, true, "tests/gpu_svgf_test.cpp"},
      {"svgf", "filter.*.history_length", false, 0.0, 0.0, true, "tests/gpu_svgf_test.cpp"},
      // Which variance each pixel took (1: the spatial estimate), a function of the exact n: exact.
      {"svgf", "filter.*.variance.spatial", false, 0.0, 0.0, true, "tests/gpu_svgf_test.cpp"},
      // A-SVGF: SVGF's colour bound, whose derivation holds with alpha_i fixed, and alpha_i itself: guards.
      {"asvgf", "color.[RGB]", true, kSvgfColour, kSvgfColourFp16, false, "tests/gpu_svgf_test.cpp"},
      {"asvgf", "filter.*.alpha", false, 1e-3, 1e-3, false, "tests/gpu_svgf_test.cpp"},
      // TRMV: the colour, a guard (alpha^V's differences pass through the clamp and the clean-up's w_C).
      {"trmv", "color.[RGB]", true, 5e-3, 5e-3, false, "tests/gpu_trmv_vulkan_test.cpp"},
  };
  return table;
}

const PortBound* find_port_bound(const std::string& method, const std::string& channel) {
  for (const PortBound& b : port_bounds())
    if (method == b.method && fnmatch(b.channels, channel.c_str(), 0) == 0) return &b;
  return nullptr;
}

}  // namespace rtdr
