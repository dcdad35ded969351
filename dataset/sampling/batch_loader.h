// Builds batches on worker threads ahead of the consumer through a bounded window, delivering them in a
// fixed order. The epoch's item order and every batch's seed depend only on (seed, epoch, batch index),
// so the sequence of batches is identical for any number of workers, and an epoch can start at any batch
// (a resumed training run continues the sequence). The project's one batch order: lc2wf-train uses it.
#pragma once

#include <algorithm>
#include <condition_variable>
#include <cstdint>
#include <exception>
#include <functional>
#include <mutex>
#include <optional>
#include <stdexcept>
#include <thread>
#include <vector>

#include "dataset/sampling/rng.h"

namespace lc2wf {

struct LoaderOptions {
  int batch_size = 16;
  int workers = 2;
  int prefetch_batches = 4;  // at most this many batches built but not yet consumed
  bool shuffle = true;
  bool drop_last = true;
  uint64_t seed = 1555;
  int64_t max_batches = 0;   // batches per epoch at most (0 = all)
  void Check() const {
    if (batch_size < 1) throw std::invalid_argument("LoaderOptions.batch_size must be >= 1");
    if (workers < 1) throw std::invalid_argument("LoaderOptions.workers must be >= 1");
    if (prefetch_batches < 1) throw std::invalid_argument("LoaderOptions.prefetch_batches must be >= 1");
    if (max_batches < 0) throw std::invalid_argument("LoaderOptions.max_batches must be >= 0");
  }
};

template <typename Batch>
class BatchLoader {
 public:
  // build(items, batch_seed) makes one batch from item indices; it runs on worker threads and must not
  // share mutable state between calls. Exceptions are re-thrown by next().
  using BuildFn = std::function<Batch(const std::vector<size_t>& items, uint64_t batch_seed)>;

  BatchLoader(size_t num_items, BuildFn build, LoaderOptions options)
      : num_items_(num_items), build_(std::move(build)), options_(options) {
    options_.Check();
  }
  ~BatchLoader() { stop(); }
  BatchLoader(const BatchLoader&) = delete;
  BatchLoader& operator=(const BatchLoader&) = delete;

  size_t batches_per_epoch() const {
    const size_t b = options_.batch_size;
    const size_t all = options_.drop_last ? num_items_ / b : (num_items_ + b - 1) / b;
    return options_.max_batches > 0 ? std::min(all, static_cast<size_t>(options_.max_batches)) : all;
  }

  // The item order of an epoch (a pure function of seed and epoch).
  std::vector<size_t> epoch_order(int epoch) const {
    std::vector<size_t> order(num_items_);
    for (size_t i = 0; i < num_items_; ++i) order[i] = i;
    if (options_.shuffle) {
      DataRng rng(mix_seed(options_.seed, static_cast<uint64_t>(epoch)));
      rng.shuffle(order);
    }
    return order;
  }

  // Stops any running epoch and starts building `epoch` at batch `first_batch` (earlier batches are skipped
  // without being built; the later ones are the same as in a whole epoch).
  void start_epoch(int epoch, size_t first_batch = 0) {
    stop();
    epoch_ = epoch;
    order_ = epoch_order(epoch);
    slots_.assign(batches_per_epoch(), Slot{});
    next_build_ = std::min(first_batch, slots_.size());
    next_take_ = next_build_;
    stopping_ = false;
    for (int w = 0; w < options_.workers; ++w) threads_.emplace_back([this] { work(); });
  }

  // The next batch in order, or nullopt at the end of the epoch.
  std::optional<Batch> next() {
    std::unique_lock<std::mutex> lock(mutex_);
    if (next_take_ >= slots_.size()) return std::nullopt;
    Slot& slot = slots_[next_take_];
    ready_.wait(lock, [&] { return slot.done; });
    ++next_take_;
    space_.notify_all();
    if (slot.error) std::rethrow_exception(slot.error);
    std::optional<Batch> out(std::move(*slot.batch));
    slot.batch.reset();
    return out;
  }

 private:
  struct Slot {
    std::optional<Batch> batch;
    std::exception_ptr error;
    bool done = false;
  };

  void work() {
    for (;;) {
      size_t b;
      {
        std::unique_lock<std::mutex> lock(mutex_);
        space_.wait(lock, [&] {
          return stopping_ || next_build_ >= slots_.size() || next_build_ < next_take_ + options_.prefetch_batches;
        });
        if (stopping_ || next_build_ >= slots_.size()) return;
        b = next_build_++;
      }
      const size_t first = b * options_.batch_size;
      const size_t last = std::min(first + options_.batch_size, num_items_);
      std::vector<size_t> items(order_.begin() + first, order_.begin() + last);
      std::optional<Batch> batch;
      std::exception_ptr error;
      try {
        batch.emplace(build_(items, mix_seed(mix_seed(options_.seed, static_cast<uint64_t>(epoch_)), b)));
      } catch (...) {
        error = std::current_exception();
      }
      {
        std::lock_guard<std::mutex> lock(mutex_);
        slots_[b].batch = std::move(batch);
        slots_[b].error = error;
        slots_[b].done = true;
      }
      ready_.notify_all();
    }
  }

  void stop() {
    {
      std::lock_guard<std::mutex> lock(mutex_);
      stopping_ = true;
    }
    space_.notify_all();
    for (auto& t : threads_) t.join();
    threads_.clear();
  }

  size_t num_items_;
  BuildFn build_;
  LoaderOptions options_;
  int epoch_ = 0;
  std::vector<size_t> order_;
  std::vector<Slot> slots_;
  size_t next_build_ = 0;
  size_t next_take_ = 0;
  bool stopping_ = false;
  std::mutex mutex_;
  std::condition_variable space_, ready_;
  std::vector<std::thread> threads_;
};

}  // namespace lc2wf
