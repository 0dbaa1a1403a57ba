// The memory a run may still take. See memory_budget.h.
#include "core/memory_budget.h"

#include "core/error.h"

#include <sys/resource.h>

#include <algorithm>
#include <charconv>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>

namespace rtdr {
namespace {

std::string read_small_file(const std::filesystem::path& path) {
  std::ifstream in(path);
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

// The number after `key` on the line that starts with it ("MemAvailable:   22893180 kB"), in KiB.
std::optional<uint64_t> kib_field(const std::string& text, const std::string& key) {
  std::istringstream lines(text);
  for (std::string line; std::getline(lines, line);) {
    if (line.rfind(key, 0) != 0) continue;
    const size_t digits = line.find_first_of("0123456789", key.size());
    if (digits == std::string::npos) return std::nullopt;
    uint64_t kib = 0;
    const auto [end, ec] = std::from_chars(line.data() + digits, line.data() + line.size(), kib);
    if (ec != std::errc() || kib > UINT64_MAX / 1024) return std::nullopt;
    return kib * 1024;
  }
  return std::nullopt;
}

// limit - usage of one cgroup folder, from the file names of its version; empty without a limit there.
std::optional<uint64_t> cgroup_headroom_at(const std::filesystem::path& dir, const char* limit_file,
                                           const char* usage_file) {
  const std::optional<uint64_t> limit = cgroup_number(read_small_file(dir / limit_file));
  if (!limit) return std::nullopt;
  const uint64_t usage = cgroup_number(read_small_file(dir / usage_file)).value_or(0);
  return *limit > usage ? *limit - usage : 0;
}

// The least headroom of the cgroup at `relative` (as /proc/self/cgroup names it) below the mount `root`, and of
// every cgroup above it: a parent's limit binds its children too.
std::optional<uint64_t> cgroup_chain_headroom(const std::filesystem::path& root, std::filesystem::path relative,
                                              const char* limit_file, const char* usage_file) {
  std::optional<uint64_t> least;
  for (relative = relative.relative_path();; relative = relative.parent_path()) {
    const std::optional<uint64_t> here = cgroup_headroom_at(root / relative, limit_file, usage_file);
    if (here) least = std::min(least.value_or(UINT64_MAX), *here);
    if (relative.empty()) return least;
  }
}

// The cgroup headroom of this process: v2 ("0::/path", the unified hierarchy at /sys/fs/cgroup, or at
// /sys/fs/cgroup/unified on a hybrid system) and v1 ("4:memory:/path", at /sys/fs/cgroup/memory).
std::optional<uint64_t> read_cgroup_headroom() {
  std::optional<uint64_t> least;
  const auto take = [&](std::optional<uint64_t> h) {
    if (h) least = std::min(least.value_or(UINT64_MAX), *h);
  };
  std::istringstream lines(read_small_file("/proc/self/cgroup"));
  for (std::string line; std::getline(lines, line);) {
    const size_t first = line.find(':'), second = line.find(':', first + 1);
    if (first == std::string::npos || second == std::string::npos) continue;
    const std::string controllers = line.substr(first + 1, second - first - 1), path = line.substr(second + 1);
    if (line.compare(0, first, "0") == 0 && controllers.empty()) {
      take(cgroup_chain_headroom("/sys/fs/cgroup", path, "memory.max", "memory.current"));
      take(cgroup_chain_headroom("/sys/fs/cgroup/unified", path, "memory.max", "memory.current"));
    }
    std::istringstream names(controllers);
    for (std::string name; std::getline(names, name, ',');)
      if (name == "memory")
        take(cgroup_chain_headroom("/sys/fs/cgroup/memory", path, "memory.limit_in_bytes", "memory.usage_in_bytes"));
  }
  return least;
}

}  // namespace

std::optional<uint64_t> meminfo_available(const std::string& meminfo) { return kib_field(meminfo, "MemAvailable:"); }
std::optional<uint64_t> status_vm_size(const std::string& status) { return kib_field(status, "VmSize:"); }

std::optional<uint64_t> cgroup_number(const std::string& text) {
  const size_t end_of_number = text.find_last_not_of(" \n");
  if (end_of_number == std::string::npos) return std::nullopt;
  uint64_t value = 0;
  const auto [end, ec] = std::from_chars(text.data(), text.data() + end_of_number + 1, value);
  if (ec != std::errc() || end != text.data() + end_of_number + 1) return std::nullopt;  // "max", or damage
  return value;
}

MemoryBudget budget_from(const MemorySources& sources) {
  MemoryBudget budget;
  const auto bound = [&](const std::optional<uint64_t>& bytes, const char* name) {
    if (bytes && *bytes < budget.bytes) budget = {*bytes, name};
  };
  bound(sources.mem_available, "MemAvailable");
  bound(sources.cgroup_headroom, "the cgroup's memory limit");
  bound(sources.address_headroom, "RLIMIT_AS");
  return budget;
}

MemorySources read_memory_sources() {
  MemorySources s;
  s.mem_available = meminfo_available(read_small_file("/proc/meminfo"));
  s.cgroup_headroom = read_cgroup_headroom();
  rlimit as{};
  if (getrlimit(RLIMIT_AS, &as) == 0 && as.rlim_cur != RLIM_INFINITY) {
    const uint64_t used = status_vm_size(read_small_file("/proc/self/status")).value_or(0);
    s.address_headroom = uint64_t(as.rlim_cur) > used ? uint64_t(as.rlim_cur) - used : 0;
  }
  return s;
}

MemoryBudget memory_budget() { return budget_from(read_memory_sources()); }

std::string format_bytes(uint64_t bytes) {
  static const char* const units[] = {"B", "KiB", "MiB", "GiB", "TiB", "PiB", "EiB"};
  double value = double(bytes);
  int unit = 0;
  while (value >= 1024.0 && unit < 6) value /= 1024.0, ++unit;
  char text[32];
  if (unit == 0)
    std::snprintf(text, sizeof text, "%llu B", static_cast<unsigned long long>(bytes));
  else
    std::snprintf(text, sizeof text, value < 10.0 ? "%.2f %s" : value < 100.0 ? "%.1f %s" : "%.0f %s", value,
                  units[unit]);
  return text;
}

void require_within_budget(uint64_t bytes, const std::string& what, const MemoryBudget& budget) {
  if (bytes <= budget.bytes) return;
  throw Error(what + " needs " + format_bytes(bytes) + ", more than the " + format_bytes(budget.bytes) +
              " of memory available (bound by " + budget.bound_by + ")");
}

uint64_t saturating_product(uint64_t a, uint64_t b) {
  uint64_t product = 0;
  return __builtin_mul_overflow(a, b, &product) ? UINT64_MAX : product;
}

}  // namespace rtdr
