// Items spread over plain threads, for the code below the tensor library and its pool (core/parallel.h):
// every item is done exactly once, by whichever thread takes it next, so a result that goes to the item's
// own slot does not depend on the thread count.
#pragma once

#include <algorithm>
#include <atomic>
#include <cstdint>
#include <exception>
#include <mutex>
#include <thread>
#include <vector>

namespace lc2wf {

// fn(i) for i in [0, n) on up to `threads` threads (the caller's among them), `chunk` items at a time.
// The first exception thrown by fn is rethrown here after every thread stopped.
template <class Fn>
void for_each_item(int64_t n, int threads, Fn&& fn, int64_t chunk = 64) {
  const int64_t chunks = (n + chunk - 1) / std::max<int64_t>(1, chunk);
  const int workers = static_cast<int>(std::clamp<int64_t>(threads, 1, std::max<int64_t>(1, chunks)));
  std::atomic<int64_t> next{0};
  std::exception_ptr failure;
  std::mutex failure_mutex;
  auto work = [&] {
    try {
      for (int64_t c; (c = next.fetch_add(1)) < chunks;)
        for (int64_t i = c * chunk, end = std::min(n, i + chunk); i < end; ++i) fn(i);
    } catch (...) {
      const std::lock_guard<std::mutex> lock(failure_mutex);
      if (!failure) failure = std::current_exception();
      next.store(chunks);  // the others stop at their next chunk
    }
  };
  std::vector<std::thread> pool;
  for (int t = 1; t < workers; ++t) pool.emplace_back(work);
  work();
  for (std::thread& t : pool) t.join();
  if (failure) std::rethrow_exception(failure);
}

}  // namespace lc2wf
