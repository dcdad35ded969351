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
  int64_t misses = 0;        // large requests that went to the system allocator
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
// A miss also returns cached blocks when needed so that cached + live bytes never exceed the
// high-water mark of live bytes. Default: LC2WF_STORAGE_CACHE_MB if set (a bad value throws
// std::invalid_argument on the first large allocation), else a quarter of physical memory, at most 4 GiB.
// 0 disables caching.
void set_storage_cache_budget(size_t bytes);
// Returns every cached block to the system and restarts the high-water mark from the live bytes.
void storage_cache_clear();
StorageCacheStats storage_cache_stats();

}  // namespace lc2wf
