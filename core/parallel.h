// Deterministic parallel loops. Work is split into rows; each row writes only its own outputs, so the
// result is bit-identical for any thread count. `set_thread_count` caps the threads for the whole
// process (rtdr --threads N); 0 means all cores.
#pragma once

#include <functional>

namespace rtdr {

void set_thread_count(int threads);
int thread_count();

// Calls row_fn(y) for every y in [0, rows), in parallel over rows.
void parallel_rows(int rows, const std::function<void(int)>& row_fn);

}  // namespace rtdr
