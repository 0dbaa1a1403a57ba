#include "core/parallel.h"

#include <tbb/global_control.h>
#include <tbb/info.h>
#include <tbb/parallel_for.h>

#include <memory>

namespace rtdr {
namespace {
std::unique_ptr<tbb::global_control> g_limit;
}

void set_thread_count(int threads) {
  g_limit.reset();
  if (threads > 0)
    g_limit = std::make_unique<tbb::global_control>(tbb::global_control::max_allowed_parallelism, size_t(threads));
}

int thread_count() {
  return int(tbb::global_control::active_value(tbb::global_control::max_allowed_parallelism));
}

void parallel_rows(int rows, const std::function<void(int)>& row_fn) {
  tbb::parallel_for(tbb::blocked_range<int>(0, rows), [&](const tbb::blocked_range<int>& r) {
    for (int y = r.begin(); y != r.end(); ++y) row_fn(y);
  });
}

}  // namespace rtdr
