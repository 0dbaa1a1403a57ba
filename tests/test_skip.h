// A test that cannot run on this machine says so, and ctest reports it as skipped, not passed.
//
// Catch2 2 has no SKIP. But catch_discover_tests runs every test case in a process of its own, so a test case can
// end its process with kSkipReturnCode, which tests/CMakeLists.txt declares to ctest as SKIP_RETURN_CODE: ctest
// then lists it as "Not Run (Skipped)" with the reason printed here. (Running a test executable by hand, the first
// skipped case ends the run with status 77: run the cases through ctest.)
#pragma once

#include "gpu/vulkan_context.h"

#include <cstdio>
#include <cstdlib>
#include <string>

namespace rtdr::test {

inline constexpr int kSkipReturnCode = 77;  // the automake convention for "skipped"

[[noreturn]] inline void skip_test(const std::string& why) {
  std::printf("SKIPPED: %s\n", why.c_str());
  std::fflush(stdout);
  std::exit(kSkipReturnCode);
}

// Skips the calling test case where no Vulkan device exists (none, or lavapipe missing), naming the reason.
inline void skip_without_vulkan() {
  std::string reason;
  if (!VulkanContext::available(&reason)) skip_test("no Vulkan device: " + reason);
}

}  // namespace rtdr::test
