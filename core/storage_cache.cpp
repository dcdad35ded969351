#include "core/storage_cache.h"

#include <sys/mman.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <bit>
#include <cstdlib>
#include <list>
#include <map>
#include <mutex>
#include <new>
#include <stdexcept>
#include <string>
#include <vector>

namespace lc2wf {

namespace {

constexpr size_t kAlignment = 64;

size_t default_budget() {
  if (const char* env = std::getenv("LC2WF_STORAGE_CACHE_MB")) {
    std::string text(env);
    size_t used = 0;
    unsigned long long mb = 0;
    try {
      mb = std::stoull(text, &used);
    } catch (const std::exception&) {
      used = 0;
    }
    if (text.empty() || used != text.size() || text[0] == '-')
      throw std::invalid_argument("LC2WF_STORAGE_CACHE_MB: '" + text + "' is not a non-negative whole number of MiB");
    return static_cast<size_t>(mb) << 20;
  }
  long pages = sysconf(_SC_PHYS_PAGES);
  long page_size = sysconf(_SC_PAGESIZE);
  size_t physical = pages > 0 && page_size > 0 ? static_cast<size_t>(pages) * static_cast<size_t>(page_size) : 0;
  return std::min(physical / 4, size_t{4} << 30);
}

void* heap_allocate(size_t size) {
  void* data = std::aligned_alloc(kAlignment, size);
  if (data == nullptr) throw std::bad_alloc();
  return data;
}

std::atomic<bool> huge_pages{true};

// Large blocks are mapped directly (page aligned), so a block given back is really gone from the process
// instead of leaving a hole in the malloc heap.
void* map_block(size_t size) {
  void* data = mmap(nullptr, size, PROT_READ | PROT_WRITE, MAP_PRIVATE | MAP_ANONYMOUS, -1, 0);
  if (data == MAP_FAILED) throw std::bad_alloc();
  // Huge pages where the kernel allows them on request: a fresh block then faults in 2 MiB at a time
  // instead of 4 KiB, so a cache miss costs little more than zeroing the memory.
  if (huge_pages.load(std::memory_order_relaxed)) madvise(data, size, MADV_HUGEPAGE);
  return data;
}

void unmap_block(void* data, size_t size) { munmap(data, size); }

// A mapped block made `size` bytes long: shrinking keeps its first pages, growing keeps them all and maps
// the rest (the mapping may move; page contents move with it, nothing is copied).
void* reshape_block(void* data, size_t old_size, size_t size) {
  if (size == old_size) return data;
  void* moved = mremap(data, old_size, size, MREMAP_MAYMOVE);
  if (moved == MAP_FAILED) {
    unmap_block(data, old_size);
    return map_block(size);
  }
  return moved;
}

class StorageCache {
 public:
  StorageCache() : budget_(default_budget()) {}

  StorageBlock acquire(size_t size) {
    {
      std::unique_lock<std::mutex> lock(mutex_);
      // Best fit among cached blocks up to twice the request: a resident block costs no page faults,
      // and its unused tail adds nothing to the footprint already counted.
      auto it = by_size_.lower_bound(size);
      if (it != by_size_.end() && it->first <= 2 * size) {
        const Block block = take(it);
        live_bytes_ += block.size;
        ++hits_;
        return {block.data, block.size};
      }
      ++misses_;
      live_bytes_ += size;
      high_water_ = std::max(high_water_, live_bytes_);
      // Cached + live never exceeds `slack` times the live high-water mark: the process holds a bounded
      // multiple of its largest working set, and a shifting mix of sizes can never pile up.
      const size_t room = static_cast<size_t>(slack_ * static_cast<double>(high_water_)) - live_bytes_;
      if (cached_bytes_ > room) {
        // Blocks must go back to the system anyway: one of them becomes this request instead, so its
        // resident pages are reused rather than unmapped while fresh ones are faulted in and zeroed.
        // The block needing the fewest fresh pages: the smallest one at least as large, else the largest.
        auto fit = by_size_.lower_bound(size);
        const Block block = take(fit != by_size_.end() ? fit : std::prev(by_size_.end()));
        evict_until(room);
        ++reshaped_;
        if (size > block.size) fresh_bytes_ += size - block.size;
        lock.unlock();
        return {reshape_block(block.data, block.size, size), size};
      }
      fresh_bytes_ += size;
    }
    return {map_block(size), size};
  }

  void release(void* data, size_t size) {
    std::lock_guard<std::mutex> lock(mutex_);
    live_bytes_ -= size;
    if (size > budget_) {
      unmap_block(data, size);
      return;
    }
    lru_.push_front(Block{data, size});
    by_size_[size].push_back(lru_.begin());
    cached_bytes_ += size;
    evict_until(budget_);
  }

  void set_slack(double factor) {
    if (!(factor >= 1.0 && factor <= 16.0))
      throw std::invalid_argument("storage cache slack must be in [1, 16], got " + std::to_string(factor));
    std::lock_guard<std::mutex> lock(mutex_);
    slack_ = factor;
  }

  double slack() {
    std::lock_guard<std::mutex> lock(mutex_);
    return slack_;
  }

  void set_budget(size_t bytes) {
    std::lock_guard<std::mutex> lock(mutex_);
    budget_ = bytes;
    evict_until(budget_);
  }

  void clear() {
    std::lock_guard<std::mutex> lock(mutex_);
    evict_until(0);
    high_water_ = live_bytes_;
  }

  StorageCacheStats stats() {
    std::lock_guard<std::mutex> lock(mutex_);
    return StorageCacheStats{budget_, cached_bytes_, lru_.size(), live_bytes_, high_water_, hits_, misses_, reshaped_, fresh_bytes_};
  }

 private:
  struct Block {
    void* data;
    size_t size;
  };
  using BlockList = std::list<Block>;

  // Removes from the cache the most recently freed block of a size class (the likeliest to still be in
  // the CPU's caches). Caller holds mutex_.
  Block take(std::map<size_t, std::vector<BlockList::iterator>>::iterator size_class) {
    const auto block = size_class->second.back();
    size_class->second.pop_back();
    if (size_class->second.empty()) by_size_.erase(size_class);
    const Block taken = *block;
    cached_bytes_ -= taken.size;
    lru_.erase(block);
    return taken;
  }

  // Frees least recently released blocks until at most `limit` bytes stay cached. Caller holds mutex_.
  void evict_until(size_t limit) {
    while (cached_bytes_ > limit) {
      auto oldest = std::prev(lru_.end());
      auto same_size = by_size_.find(oldest->size);
      same_size->second.erase(std::find(same_size->second.begin(), same_size->second.end(), oldest));
      if (same_size->second.empty()) by_size_.erase(same_size);
      cached_bytes_ -= oldest->size;
      unmap_block(oldest->data, oldest->size);
      lru_.erase(oldest);
    }
  }

  std::mutex mutex_;
  size_t budget_;
  double slack_ = kStorageCacheDefaultSlack;
  size_t cached_bytes_ = 0;
  size_t live_bytes_ = 0;
  size_t high_water_ = 0;
  int64_t hits_ = 0;
  int64_t misses_ = 0;
  int64_t reshaped_ = 0;
  size_t fresh_bytes_ = 0;
  BlockList lru_;  // front = most recently released
  std::map<size_t, std::vector<BlockList::iterator>> by_size_;  // capacity -> blocks, oldest first
};

// Never destroyed: tensors held by other static objects are released during static destruction.
StorageCache& cache() {
  static StorageCache* instance = new StorageCache();
  return *instance;
}

}  // namespace

size_t storage_size_class(size_t bytes) {
  if (bytes < kStorageCacheMinBytes) {
    return bytes == 0 ? kAlignment : (bytes + kAlignment - 1) / kAlignment * kAlignment;
  }
  size_t step = std::bit_floor(bytes) / 8;
  return (bytes + step - 1) / step * step;
}

StorageBlock storage_allocate(size_t bytes) {
  size_t size = storage_size_class(bytes);
  if (size < kStorageCacheMinBytes) return {heap_allocate(size), size};
  return cache().acquire(size);
}

void storage_release(const StorageBlock& block) {
  if (block.data == nullptr) return;
  if (block.capacity < kStorageCacheMinBytes) {
    std::free(block.data);
    return;
  }
  cache().release(block.data, block.capacity);
}

void set_storage_cache_budget(size_t bytes) { cache().set_budget(bytes); }

void set_storage_cache_slack(double factor) { cache().set_slack(factor); }

double storage_cache_slack() { return cache().slack(); }

void set_storage_cache_huge_pages(bool on) { huge_pages.store(on, std::memory_order_relaxed); }

bool storage_cache_huge_pages() { return huge_pages.load(std::memory_order_relaxed); }

void storage_cache_clear() { cache().clear(); }

StorageCacheStats storage_cache_stats() { return cache().stats(); }

}  // namespace lc2wf
