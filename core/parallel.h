// Thread pool with *fixed* chunking: work is split into chunks whose bounds
// depend only on the problem size and grain, never on the thread count, so every reduction combines
// partial results in the same order and results are bit-identical at 1 or N threads.
#pragma once

#include <cstdint>
#include <functional>

namespace lc2wf {

// Default: OMP_NUM_THREADS when set, else all hardware threads.
void set_num_threads(int n);  // <= 0: OMP_NUM_THREADS when set, else all hardware threads
int num_threads();

// Calls fn(begin, end) for chunks [k*grain, min((k+1)*grain, n)); chunks run in parallel.
void parallel_for(int64_t n, int64_t grain, const std::function<void(int64_t, int64_t)>& fn);

// parallel_for that runs its chunks inline when the whole job (n * work_per_item, in rough
// multiply-add units) is too small to pay for waking the thread team. Chunk bounds are unchanged,
// so results are the same either way.
void parallel_for_work(int64_t n, int64_t grain, int64_t work_per_item,
                       const std::function<void(int64_t, int64_t)>& fn);

// Number of chunks parallel_for uses for (n, grain); chunk k covers [k*grain, ...).
inline int64_t num_chunks(int64_t n, int64_t grain) { return grain <= 0 ? 1 : (n + grain - 1) / grain; }

}  // namespace lc2wf
