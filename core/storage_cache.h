// Recycling of large tensor buffers: a training step frees and re-requests the same activation sizes every
// step, and handing freed blocks back saves the kernel from faulting in and zero-filling fresh pages each time.
#pragma once

#include <cstddef>
#include <cstdint>

namespace lc2wf {

// Requests of at least this many bytes go through the cache; smaller ones go straight to malloc.
constexpr size_t kStorageCacheMinBytes = size_t{1} << 20;

struct StorageCacheStats {
  size_t budget_bytes = 0;
  size_t cached_bytes = 0;   // free blocks held for reuse
  size_t cached_blocks = 0;
  size_t live_bytes = 0;     // large blocks currently owned by tensors
  size_t high_water = 0;     // most live_bytes ever reached
  int64_t hits = 0;          // large requests served by a cached block
  int64_t misses = 0;        // large requests that no cached block could serve as it is
  int64_t reshaped = 0;      // misses served by resizing a cached block that had to go anyway
  size_t fresh_bytes = 0;    // bytes ever mapped new (the pages the kernel must zero on first touch)
};

// Bytes reserved for a request: a multiple of 64 below the threshold, otherwise the request rounded up to
// the next eighth of its power of two (at most 12.5% more), so near sizes share a class.
size_t storage_size_class(size_t bytes);

struct StorageBlock {
  void* data = nullptr;
  size_t capacity = 0;  // usable bytes, at least the request
};

// 64-byte aligned, contents uninitialised (a reused block holds whatever its last owner wrote). A cached
// block of up to twice the size class may serve the request.
StorageBlock storage_allocate(size_t bytes);
void storage_release(const StorageBlock& block);

// Most bytes of free blocks kept; beyond it the least recently freed blocks are returned to the system.
// A miss also returns cached blocks when needed so that cached + live bytes never exceed the slack
// factor times the high-water mark of live bytes; the first of them is resized into the request instead
// (its pages stay resident, so only growth beyond them faults). Default budget: LC2WF_STORAGE_CACHE_MB
// if set (a bad value throws std::invalid_argument on the first large allocation), else a quarter of
// physical memory, at most 4 GiB. 0 disables caching.
void set_storage_cache_budget(size_t bytes);

// A training step's blocks are not all live at its peak: with cached + live held to 1.0x the peak, the
// paper-size junction step re-mapped 1.5 GB (45 blocks) every step, 11% of its CPU time in the kernel
// zeroing pages. In lpt_bench 1.5x left 0.26 GB per junction step, 2x none (peak RSS 2.15 / 2.32 GB
// against 1.48); the real run at 1.5x still faulted ~220 huge pages per step (8% of its CPU time).
constexpr double kStorageCacheDefaultSlack = 2.0;
// The factor above, in [1, 16] (std::invalid_argument otherwise).
void set_storage_cache_slack(double factor);
double storage_cache_slack();

// Inference over a batch of buildings asks for blocks whose sizes follow each building's pair count: at 2x
// the cache returned blocks of one size to map others, and 7 % of lc2wf-eval's time went to the kernel
// zeroing fresh pages (392 page faults per building); at 4x, 2 per building, 0.071-0.075 instead of
// 0.077-0.081 s per building, peak RSS 427 instead of 281 MB (bench/README.md).
constexpr double kBatchInferenceSlack = 4.0;

// Whether blocks mapped from now on ask for huge pages (MADV_HUGEPAGE; default on). Training wants them
// (fewer TLB misses over its 128-384 MiB operands: a junction step 30.9 -> 18.8 user-s, bench/README.md);
// inference does not: a process faults its blocks in once, and where the kernel compacts memory on such a
// fault (defrag "madvise") the fault may stall, e.g. a 157 m line map's junction model 0.17 s or 0.32 s
// by the run, 0.21 s every run without (infer/README.md, "Time per line map").
void set_storage_cache_huge_pages(bool on);
bool storage_cache_huge_pages();

// Sets one of the cache's process-wide choices while alive and restores the previous one.
template <class T, T (*Get)(), void (*Set)(T)>
class StorageCacheSettingGuard {
 public:
  explicit StorageCacheSettingGuard(T value) : previous_(Get()) { Set(value); }
  ~StorageCacheSettingGuard() { Set(previous_); }
  StorageCacheSettingGuard(const StorageCacheSettingGuard&) = delete;
  StorageCacheSettingGuard& operator=(const StorageCacheSettingGuard&) = delete;

 private:
  T previous_;
};
using StorageCacheSlackGuard = StorageCacheSettingGuard<double, storage_cache_slack, set_storage_cache_slack>;
using StorageCacheHugePagesGuard = StorageCacheSettingGuard<bool, storage_cache_huge_pages, set_storage_cache_huge_pages>;

// Returns every cached block to the system and restarts the high-water mark from the live bytes.
void storage_cache_clear();
StorageCacheStats storage_cache_stats();

}  // namespace lc2wf
