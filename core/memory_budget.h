// The memory a run may still take, checked before allocating what a file declares or what --size asks for, so
// that an oversized input is refused with its size and the budget instead of ending in std::bad_alloc or the
// out-of-memory killer.
//
// The budget is the least of three headrooms, each where it exists:
// - MemAvailable (/proc/meminfo): what the kernel can hand out without swapping (proc(5));
// - the cgroup's: its limit less its usage, memory.max - memory.current (cgroup v2) or memory.limit_in_bytes -
//   memory.usage_in_bytes (v1), for the cgroup this process is in (/proc/self/cgroup) and each cgroup above it:
//   in a container, past its limit the OOM killer ends the process whatever the machine has free;
// - the address space's: RLIMIT_AS less the address space in use (VmSize, /proc/self/status): past it every
//   allocation fails.
// A source that is absent (no /proc, no cgroup limit, RLIMIT_AS unlimited) bounds nothing; with none at all the
// budget is unbounded (UINT64_MAX).
#pragma once

#include <cstdint>
#include <optional>
#include <string>

namespace rtdr {

// What the sources said; each is empty where it said nothing.
struct MemorySources {
  std::optional<uint64_t> mem_available;   // bytes
  std::optional<uint64_t> cgroup_headroom;  // bytes, the least over this cgroup and those above it
  std::optional<uint64_t> address_headroom;  // bytes, RLIMIT_AS - VmSize
};

struct MemoryBudget {
  uint64_t bytes = UINT64_MAX;
  std::string bound_by = "nothing";  // "MemAvailable", "the cgroup's memory limit", "RLIMIT_AS" or "nothing"
};

// The least of the sources, and which one it is.
MemoryBudget budget_from(const MemorySources& sources);
// The sources of this process now, and their budget.
MemorySources read_memory_sources();
MemoryBudget memory_budget();

// The parsers, for tests: MemAvailable of a /proc/meminfo text (its "kB" are KiB); a cgroup file's one number
// ("max" and an unreadable text say nothing); VmSize of a /proc/self/status text.
std::optional<uint64_t> meminfo_available(const std::string& meminfo);
std::optional<uint64_t> cgroup_number(const std::string& text);
std::optional<uint64_t> status_vm_size(const std::string& status);

// Bytes for people: "812 B", "8.3 KiB", "3.00 GiB" (three significant digits).
std::string format_bytes(uint64_t bytes);

// Throws a one-line rtdr::Error "<what> needs <bytes>, more than the <budget> of memory available (bound by
// <bound_by>)" when bytes > budget.bytes.
void require_within_budget(uint64_t bytes, const std::string& what, const MemoryBudget& budget);

// a * b, or UINT64_MAX when the product overflows: for byte counts that are compared with a budget, where
// "more than any budget" is the right answer for a product too large to hold.
uint64_t saturating_product(uint64_t a, uint64_t b);

}  // namespace rtdr
