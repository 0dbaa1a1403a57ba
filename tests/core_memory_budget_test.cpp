// Tests of core/memory_budget.cpp: the parsers on texts as the kernel writes them, the budget as the least of its
// sources (and which one bounds it), the real budget against /proc/meminfo, a lowered RLIMIT_AS seen by the
// budget (in a child process, so the test's own limit is untouched), and the refusal's message.
#include "core/memory_budget.h"

#include "core/error.h"

#include <catch2/catch.hpp>

#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <fstream>
#include <sstream>

using namespace rtdr;

TEST_CASE("memory budget: MemAvailable, VmSize and cgroup numbers parsed as the kernel writes them") {
  const std::string meminfo = "MemTotal:       24346020 kB\nMemFree:        22410000 kB\n"
                              "MemAvailable:   22893180 kB\nBuffers:           12 kB\n";
  CHECK(meminfo_available(meminfo) == uint64_t(22893180) * 1024);
  CHECK_FALSE(meminfo_available("MemTotal: 5 kB\n"));  // a kernel before 3.14 has no MemAvailable
  CHECK(status_vm_size("Name:\trtdr\nVmPeak:\t  9000 kB\nVmSize:\t    3892 kB\n") == uint64_t(3892) * 1024);
  CHECK_FALSE(meminfo_available("MemAvailable: 99999999999999999999 kB\n"));  // would overflow: says nothing
  CHECK(cgroup_number("1659408384\n") == uint64_t(1659408384));
  CHECK_FALSE(cgroup_number("max\n"));  // cgroup v2 without a limit
  CHECK_FALSE(cgroup_number(""));
  CHECK_FALSE(cgroup_number("12abc\n"));
}

TEST_CASE("memory budget: the least of its sources, named, and none at all bounds nothing") {
  CHECK(budget_from({}).bytes == UINT64_MAX);
  CHECK(budget_from({}).bound_by == "nothing");
  const MemoryBudget by_cgroup = budget_from({8000, 3000, 5000});
  CHECK(by_cgroup.bytes == 3000);
  CHECK(by_cgroup.bound_by == "the cgroup's memory limit");
  CHECK(budget_from({8000, std::nullopt, 5000}).bound_by == "RLIMIT_AS");
  CHECK(budget_from({2000, 3000, 5000}).bound_by == "MemAvailable");
  CHECK(budget_from({std::nullopt, std::nullopt, 0}).bytes == 0);  // an address space already full
}

TEST_CASE("memory budget: this process's budget is at most its MemAvailable") {
  std::ifstream in("/proc/meminfo");
  std::stringstream text;
  text << in.rdbuf();
  const std::optional<uint64_t> available = meminfo_available(text.str());
  if (!available) return;  // no /proc here: nothing to compare with
  const MemoryBudget budget = memory_budget();
  CHECK(budget.bytes > 0);
  // MemAvailable moves between the two reads; a tenth of it is far more than it moves in between.
  CHECK(budget.bytes <= *available + *available / 10);
}

TEST_CASE("memory budget: a lowered RLIMIT_AS bounds the budget (in a child process)") {
  const pid_t child = fork();
  REQUIRE(child >= 0);
  if (child == 0) {
    // 256 MiB more than the address space in use: the budget is at most that.
    constexpr uint64_t kMargin = uint64_t(256) << 20;
    const MemorySources before = read_memory_sources();
    std::ifstream in("/proc/self/status");
    std::stringstream text;
    text << in.rdbuf();
    const uint64_t used = status_vm_size(text.str()).value_or(0);
    rlimit limit{};
    getrlimit(RLIMIT_AS, &limit);
    const uint64_t wanted = used + kMargin;
    if (limit.rlim_max != RLIM_INFINITY && limit.rlim_max < wanted) _exit(3);
    limit.rlim_cur = wanted;
    if (setrlimit(RLIMIT_AS, &limit) != 0) _exit(4);
    const MemoryBudget budget = memory_budget();
    const bool ok = budget.bytes <= kMargin && budget.bound_by == "RLIMIT_AS" &&
                    (!before.address_headroom || *before.address_headroom > kMargin);
    _exit(ok ? 0 : 1);
  }
  int status = 0;
  waitpid(child, &status, 0);
  REQUIRE(WIFEXITED(status));
  CHECK(WEXITSTATUS(status) == 0);
}

TEST_CASE("memory budget: a request over the budget is one line with both sizes and the bound") {
  const MemoryBudget budget{uint64_t(3) << 30, "MemAvailable"};
  CHECK_NOTHROW(require_within_budget(uint64_t(3) << 30, "x", budget));
  CHECK_THROWS_WITH(require_within_budget((uint64_t(3) << 30) + 1, "'a.exr' (16384x16384, 3 channels)", budget),
                    "'a.exr' (16384x16384, 3 channels) needs 3.00 GiB, more than the 3.00 GiB of memory available "
                    "(bound by MemAvailable)");
  CHECK(format_bytes(812) == "812 B");
  CHECK(format_bytes(8542) == "8.34 KiB");
  CHECK(format_bytes(uint64_t(16384) * 16384 * 12) == "3.00 GiB");
  CHECK(format_bytes(UINT64_MAX) == "16.0 EiB");
  CHECK(saturating_product(uint64_t(1) << 62, 4) == UINT64_MAX);
  CHECK(saturating_product(uint64_t(1) << 31, uint64_t(1) << 31) == uint64_t(1) << 62);
}
