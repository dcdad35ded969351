#include "core/parallel.h"

#include "core/util/thread_count.h"

#include <immintrin.h>

#include <algorithm>
#include <atomic>
#include <condition_variable>
#include <cstdlib>
#include <exception>
#include <memory>
#include <mutex>
#include <thread>
#include <vector>

namespace lc2wf {

namespace {

// A small pool with brief spinning and then blocking waits. Busy-waiting runtimes collapse when the
// machine is oversubscribed (a descheduled spinner stalls every barrier), so waits here always block
// after a few microseconds. Chunks are claimed through one atomic word that carries the job
// generation, so a worker that wakes late can never run chunks of a finished job.
class ThreadPool {
 public:
  ~ThreadPool() { resize(1); }

  int size() const { return static_cast<int>(workers_.size()) + 1; }

  void resize(int threads) {
    {
      std::lock_guard<std::mutex> lock(mutex_);
      stop_ = true;
    }
    wake_.notify_all();
    for (std::thread& t : workers_) t.join();
    workers_.clear();
    stop_ = false;
    for (int i = 1; i < threads; ++i) workers_.emplace_back([this] { worker_loop(); });
  }

  void run(int64_t chunks, const std::function<void(int64_t)>& chunk_fn) {
    {
      std::lock_guard<std::mutex> lock(mutex_);
      // The last job's claim word is closed before this job's count is written: a worker that read the
      // word earlier and then this job's count can no longer claim with it (its compare-exchange fails),
      // so it never runs an index of the old job with this job's function. The claim and count accesses
      // are sequentially consistent, which makes that argument hold.
      claim_.store((generation_ << 32) | kClaimClosed);
      job_ = &chunk_fn;
      chunks_.store(chunks);
      done_.store(0, std::memory_order_relaxed);
      error_ = nullptr;
      ++generation_;
      claim_.store(generation_ << 32);
    }
    wake_.notify_all();
    work(generation_);
    for (int spin = 0; done_.load(std::memory_order_acquire) < chunks && spin < kSpins; ++spin) _mm_pause();
    if (done_.load(std::memory_order_acquire) < chunks) {
      std::unique_lock<std::mutex> lock(mutex_);
      finished_.wait(lock, [&] { return done_.load(std::memory_order_acquire) >= chunks; });
    }
    std::exception_ptr error;
    {
      std::lock_guard<std::mutex> lock(mutex_);
      job_ = nullptr;
      error = error_;
    }
    if (error) std::rethrow_exception(error);
  }

 private:
  static constexpr int kSpins = 4000;
  static constexpr uint64_t kClaimClosed = 0xffffffffu;  // an index no job reaches (chunks < 2^32)

  // Claims and runs chunks of job `gen` until none are left.
  void work(uint64_t gen) {
    for (;;) {
      uint64_t v = claim_.load();
      if ((v >> 32) != gen || static_cast<int64_t>(v & 0xffffffffu) >= chunks_.load()) return;
      if (!claim_.compare_exchange_weak(v, v + 1)) continue;
      int64_t chunk = static_cast<int64_t>(v & 0xffffffffu);
      try {
        (*job_)(chunk);
      } catch (...) {
        std::lock_guard<std::mutex> lock(mutex_);
        if (!error_) error_ = std::current_exception();
      }
      if (done_.fetch_add(1, std::memory_order_acq_rel) + 1 == chunks_.load(std::memory_order_relaxed)) {
        std::lock_guard<std::mutex> lock(mutex_);
        finished_.notify_all();
      }
    }
  }

  void worker_loop() {
    in_pool_ = true;
    uint64_t seen = 0;
    {
      std::lock_guard<std::mutex> lock(mutex_);
      seen = generation_;
    }
    for (;;) {
      uint64_t gen = 0;
      for (int spin = 0; spin < kSpins; ++spin) {
        gen = claim_.load(std::memory_order_acquire) >> 32;
        if (gen != seen) break;
        _mm_pause();
      }
      if (gen == seen) {
        std::unique_lock<std::mutex> lock(mutex_);
        wake_.wait(lock, [&] { return stop_ || generation_ != seen; });
        if (stop_) return;
        gen = generation_;
      }
      seen = gen;
      work(gen);
    }
  }

  std::vector<std::thread> workers_;
  std::mutex mutex_;
  std::condition_variable wake_, finished_;
  uint64_t generation_ = 0;           // guarded by mutex_
  std::atomic<uint64_t> claim_{0};    // (generation << 32) | next chunk
  std::atomic<int64_t> done_{0};
  std::atomic<int64_t> chunks_{0};
  const std::function<void(int64_t)>* job_ = nullptr;
  std::exception_ptr error_;
  bool stop_ = false;

 public:
  static thread_local bool in_pool_;
};

thread_local bool ThreadPool::in_pool_ = false;

int default_threads() { return default_thread_count(); }

int g_threads = 0;  // 0 = default, resolved on first use
std::mutex g_pool_mutex;

ThreadPool& pool() {
  static ThreadPool instance;
  return instance;
}

}  // namespace

void set_num_threads(int n) {
  g_threads = n <= 0 ? default_threads() : n;
}

int num_threads() { return g_threads > 0 ? g_threads : (g_threads = default_threads()); }

void parallel_for(int64_t n, int64_t grain, const std::function<void(int64_t, int64_t)>& fn) {
  if (n <= 0) return;
  if (grain <= 0) grain = n;
  int64_t chunks = num_chunks(n, grain);
  auto run_chunk = [&](int64_t c) { fn(c * grain, std::min(n, (c + 1) * grain)); };
  int threads = num_threads();
  // Nested calls and calls from a second user thread run inline: same chunks, same results.
  std::unique_lock<std::mutex> lock(g_pool_mutex, std::defer_lock);
  if (chunks == 1 || threads <= 1 || ThreadPool::in_pool_ || chunks >= (int64_t{1} << 32) || !lock.try_lock()) {
    for (int64_t c = 0; c < chunks; ++c) run_chunk(c);
    return;
  }
  ThreadPool& p = pool();
  if (p.size() != threads) p.resize(threads);
  p.run(chunks, run_chunk);
}

void parallel_for_work(int64_t n, int64_t grain, int64_t work_per_item,
                       const std::function<void(int64_t, int64_t)>& fn) {
  // About 100 microseconds of arithmetic: below that a parallel region costs more than it saves.
  constexpr int64_t kMinParallelWork = 1 << 18;
  if (n > 0 && n * std::max<int64_t>(1, work_per_item) < kMinParallelWork) {
    if (grain <= 0) grain = n;
    for (int64_t c = 0, chunks = num_chunks(n, grain); c < chunks; ++c) fn(c * grain, std::min(n, (c + 1) * grain));
    return;
  }
  parallel_for(n, grain, fn);
}

}  // namespace lc2wf
