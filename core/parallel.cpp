#include "core/parallel.h"

#include <omp.h>

#include <exception>
#include <mutex>

namespace lc2wf {

namespace {
int g_threads = 0;  // 0 = not set yet: use OpenMP's default
}

void set_num_threads(int n) { g_threads = n <= 0 ? omp_get_num_procs() : n; }

int num_threads() { return g_threads > 0 ? g_threads : omp_get_max_threads(); }

void parallel_for(int64_t n, int64_t grain, const std::function<void(int64_t, int64_t)>& fn) {
  if (n <= 0) return;
  if (grain <= 0) grain = n;
  int64_t chunks = num_chunks(n, grain);
  int threads = num_threads();
  if (chunks == 1 || threads <= 1 || omp_in_parallel()) {
    for (int64_t c = 0; c < chunks; ++c) fn(c * grain, std::min(n, (c + 1) * grain));
    return;
  }
  std::exception_ptr error;
  std::mutex error_mutex;
  int team = static_cast<int>(std::min<int64_t>(threads, chunks));
#pragma omp parallel for schedule(dynamic, 1) num_threads(team)
  for (int64_t c = 0; c < chunks; ++c) {
    try {
      fn(c * grain, std::min(n, (c + 1) * grain));
    } catch (...) {
      std::lock_guard<std::mutex> lock(error_mutex);
      if (!error) error = std::current_exception();
    }
  }
  if (error) std::rethrow_exception(error);
}

}  // namespace lc2wf
