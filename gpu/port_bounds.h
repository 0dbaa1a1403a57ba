// How far the Vulkan ports may be from the golden passes, over a sequence filtered on both back ends as `rtdr
// compare` runs it (each back end keeping its own history): one table, which the pipeline tests assert
// (tests/gpu_svgf_test.cpp, tests/gpu_trmv_vulkan_test.cpp) and rtdr compare reports each channel against. A row
// names a method, the channels it bounds (an fnmatch(3) pattern of the names rtdr compare prints), the measure and
// the bound for each kind of illumination records; its derivation, or why it is a guard and not derived, is in the
// banner of the test it names. A channel no row names has no stated bound: rtdr compare reports it and judges
// nothing (the variances, whose relative difference has no bound independent of the frame; the display, which the
// tests bound against the golden TAA of the port's own colour, not against the golden display).
#pragma once

#include <string>
#include <vector>

namespace rtdr {

// Relative bounds are on |port - golden| / max(|golden|, kPortRelFloor), rtdr compare's default --rel-floor.
inline constexpr double kPortRelFloor = 1e-2;

struct PortBound {
  const char* method;    // svgf, asvgf or trmv
  const char* channels;  // an fnmatch(3) pattern: "color.[RGB]", "filter.*.history_length"
  bool relative;         // relative (floor kPortRelFloor), else absolute
  double fp32, fp16;     // with fp32 or fp16 illumination records (gpu/vulkan_context.h)
  bool derived;          // derived in the test's banner; else a regression guard from what lavapipe measures
  const char* test;      // the test whose banner says why
  double bound(bool half_records) const { return half_records ? fp16 : fp32; }
};

const std::vector<PortBound>& port_bounds();
// The first row of `method` whose pattern matches `channel`, or nullptr when none does.
const PortBound* find_port_bound(const std::string& method, const std::string& channel);

}  // namespace rtdr
