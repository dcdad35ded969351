// The thread pool behind parallel_for: every chunk of every job runs exactly once, while its job runs.
#include <gtest/gtest.h>

#include <atomic>
#include <vector>

#include "core/parallel.h"

namespace lc2wf {
namespace {

// Back-to-back jobs of different chunk counts on more threads than the machine has cores, so workers are
// preempted anywhere. A worker preempted between reading a finished job's claim word and claiming from it
// once took an index of the next job: that chunk ran twice and the job returned with a chunk still running
// (lc2wf-train died in the attention backward pass, 2026-12-05).
TEST(ThreadPool, EveryChunkOfBackToBackJobsRunsOnce) {
  const int before = num_threads();
  set_num_threads(8);
  constexpr int kJobs = 500000;
  int wrong = 0;
  for (int job = 0; job < kJobs && wrong == 0; ++job) {
    const int64_t chunks = 1 + job % 9;
    std::vector<std::atomic<int>> runs(static_cast<size_t>(chunks));
    parallel_for(chunks, 1, [&](int64_t c0, int64_t c1) {
      for (int64_t c = c0; c < c1; ++c) runs[static_cast<size_t>(c)].fetch_add(1, std::memory_order_relaxed);
    });
    for (int64_t c = 0; c < chunks; ++c)
      if (runs[static_cast<size_t>(c)].load() != 1) {
        ADD_FAILURE() << "job " << job << " chunk " << c << " of " << chunks << " ran " << runs[static_cast<size_t>(c)].load()
                      << " times";
        ++wrong;
      }
  }
  set_num_threads(before);
}

}  // namespace
}  // namespace lc2wf
