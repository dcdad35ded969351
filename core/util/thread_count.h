// How many threads "-j 0" or no -j means, for every command and library: OMP_NUM_THREADS, else every core.
#pragma once

#include <algorithm>
#include <cstdlib>
#include <thread>

namespace lc2wf {

inline int default_thread_count() {
  if (const char* env = std::getenv("OMP_NUM_THREADS")) {
    const int n = std::atoi(env);
    if (n > 0) return n;
  }
  return static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
}

// A -j value: 0 (or negative) = the default.
inline int resolve_thread_count(int requested) { return requested > 0 ? requested : default_thread_count(); }

}  // namespace lc2wf
