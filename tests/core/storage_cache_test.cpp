// Large tensor buffers are recycled by size class, within the byte budget and the live high-water mark.
#include "core/storage_cache.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <cstdint>
#include <fstream>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include "core/tensor.h"

namespace lc2wf {
namespace {

constexpr size_t kMiB = size_t{1} << 20;

int64_t rss_bytes() {
  std::ifstream statm("/proc/self/statm");
  int64_t size = 0, resident = 0;
  statm >> size >> resident;
  return resident * sysconf(_SC_PAGESIZE);
}

Tensor floats(size_t bytes) { return Tensor::empty({static_cast<int64_t>(bytes / 4)}); }

// Every test starts from an empty cache with the given budget and cached + live held to the high water
// itself (slack 1), and restores the defaults after.
class StorageCacheTest : public ::testing::Test {
 protected:
  void SetUp() override {
    default_budget_ = storage_cache_stats().budget_bytes;
    storage_cache_clear();
    set_storage_cache_slack(1.0);
  }
  void TearDown() override {
    storage_cache_clear();
    set_storage_cache_budget(default_budget_);
    set_storage_cache_slack(kStorageCacheDefaultSlack);
  }
  size_t default_budget_ = 0;
};

TEST(StorageSizeClass, RoundsUpByAtMostAnEighthAndKeeps64ByteMultiples) {
  EXPECT_EQ(storage_size_class(0), 64u);
  EXPECT_EQ(storage_size_class(100), 128u);
  EXPECT_EQ(storage_size_class(kMiB), kMiB);
  EXPECT_EQ(storage_size_class(kMiB + 1), kMiB + kMiB / 8);
  EXPECT_EQ(storage_size_class(128 * kMiB + 1), 144 * kMiB);
  std::mt19937_64 rng(7);
  for (int i = 0; i < 10000; ++i) {
    size_t bytes = kMiB + rng() % (size_t{1} << 32);
    size_t size = storage_size_class(bytes);
    ASSERT_GE(size, bytes);
    ASSERT_LE(size - bytes, bytes / 8) << bytes;
    ASSERT_EQ(size % 64, 0u) << bytes;
  }
}

TEST_F(StorageCacheTest, FreedBlockIsReusedBySameClassAndStaysAligned) {
  set_storage_cache_budget(64 * kMiB);
  const float* first = nullptr;
  {
    Tensor t = floats(4 * kMiB + 4096);
    first = t.data<float>();
    EXPECT_EQ(reinterpret_cast<uintptr_t>(first) % 64, 0u);
  }
  EXPECT_EQ(storage_cache_stats().cached_blocks, 1u);
  int64_t hits = storage_cache_stats().hits;
  Tensor again = floats(4 * kMiB + 256 * 1024);  // same class (4 MiB .. 4.5 MiB)
  EXPECT_EQ(again.data<float>(), first);
  EXPECT_EQ(storage_cache_stats().hits, hits + 1);
  EXPECT_EQ(storage_cache_stats().cached_blocks, 0u);
}

TEST_F(StorageCacheTest, LargerBlockServesARequestUpToHalfItsSize) {
  set_storage_cache_budget(64 * kMiB);
  const float* big = nullptr;
  {
    Tensor t = floats(16 * kMiB);
    big = t.data<float>();
  }
  {
    Tensor fits = floats(9 * kMiB);
    EXPECT_EQ(fits.data<float>(), big);
    EXPECT_EQ(storage_cache_stats().live_bytes, 16 * kMiB);  // the whole block is accounted while in use
  }
  int64_t misses = storage_cache_stats().misses;
  Tensor too_small = floats(6 * kMiB);  // 16 MiB is more than twice 6 MiB: not used
  EXPECT_EQ(storage_cache_stats().misses, misses + 1);
}

TEST_F(StorageCacheTest, ZerosAndOnesFillAReusedBlock) {
  set_storage_cache_budget(64 * kMiB);
  const int64_t n = 2 * kMiB / 4;
  const float* block = nullptr;
  {
    Tensor dirty = Tensor::full({n}, 7.0);
    block = dirty.data<float>();
  }
  Tensor zeros = Tensor::zeros({n});
  ASSERT_EQ(zeros.data<float>(), block);  // really the recycled block
  for (int64_t i = 0; i < n; ++i) ASSERT_EQ(zeros.data<float>()[i], 0.0f) << i;
  zeros = Tensor();
  Tensor ones = Tensor::ones({n});
  ASSERT_EQ(ones.data<float>(), block);
  for (int64_t i = 0; i < n; ++i) ASSERT_EQ(ones.data<float>()[i], 1.0f) << i;
}

TEST_F(StorageCacheTest, SmallBuffersBypassTheCache) {
  set_storage_cache_budget(64 * kMiB);
  int64_t misses = storage_cache_stats().misses;
  { Tensor t = floats(kMiB / 2); }
  EXPECT_EQ(storage_cache_stats().cached_blocks, 0u);
  EXPECT_EQ(storage_cache_stats().misses, misses);
}

TEST_F(StorageCacheTest, BudgetEvictsLeastRecentlyFreedBlocks) {
  set_storage_cache_budget(8 * kMiB);
  const float* kept = nullptr;
  {
    Tensor a = floats(4 * kMiB), b = floats(4 * kMiB), c = floats(4 * kMiB);
    kept = c.data<float>();
    a = Tensor();
    b = Tensor();
    c = Tensor();  // freed last: survives while a, the oldest, is evicted
  }
  StorageCacheStats stats = storage_cache_stats();
  EXPECT_EQ(stats.cached_bytes, 8 * kMiB);
  EXPECT_EQ(stats.cached_blocks, 2u);
  Tensor reused = floats(4 * kMiB);
  EXPECT_EQ(reused.data<float>(), kept);  // most recently freed block of the class comes first

  set_storage_cache_budget(0);  // shrinking frees the excess at once, and 0 disables caching
  EXPECT_EQ(storage_cache_stats().cached_bytes, 0u);
  reused = Tensor();
  EXPECT_EQ(storage_cache_stats().cached_bytes, 0u);
}

TEST_F(StorageCacheTest, MissGivesBackBlocksBeyondTheLiveHighWater) {
  set_storage_cache_budget(256 * kMiB);
  const float* two = nullptr;
  {
    Tensor a = floats(4 * kMiB), b = floats(6 * kMiB), c = floats(2 * kMiB);  // high water 12 MiB
    two = c.data<float>();
    a = Tensor();
    b = Tensor();
    c = Tensor();
  }
  ASSERT_EQ(storage_cache_stats().cached_bytes, 12 * kMiB);
  // No block can serve 7 MiB, and 12 cached + 7 live would exceed the 12 MiB high water: the 6 MiB block
  // (the largest, none being >= 7) is grown into the request, then the least recently freed (4 MiB)
  // goes back to the system until 7 + cached <= 12.
  const StorageCacheStats before = storage_cache_stats();
  Tensor seven = floats(7 * kMiB);
  StorageCacheStats stats = storage_cache_stats();
  EXPECT_EQ(stats.reshaped, before.reshaped + 1);
  EXPECT_EQ(stats.fresh_bytes - before.fresh_bytes, 1 * kMiB);  // only the growth is new memory
  EXPECT_EQ(stats.cached_bytes, 2 * kMiB);
  EXPECT_EQ(stats.cached_blocks, 1u);
  EXPECT_LE(stats.cached_bytes + stats.live_bytes, stats.high_water);
  seven = Tensor();
  EXPECT_EQ(floats(2 * kMiB).data<float>(), two);
}

// A block that must leave the cache becomes the request: shrunk (no fresh page) or grown (fresh pages for
// the growth only), and the whole request is usable memory.
TEST_F(StorageCacheTest, MissReshapesABlockThatWouldBeEvicted) {
  set_storage_cache_budget(256 * kMiB);
  floats(40 * kMiB) = Tensor();  // high water 40 MiB, one 40 MiB block cached
  StorageCacheStats before = storage_cache_stats();
  {
    // A 40 MiB block may not serve 4 MiB (more than twice), and 40 cached + 4 live exceed 40: the block
    // is shrunk into the request.
    Tensor small = floats(4 * kMiB);
    StorageCacheStats after = storage_cache_stats();
    EXPECT_EQ(after.reshaped, before.reshaped + 1);
    EXPECT_EQ(after.fresh_bytes, before.fresh_bytes);
    EXPECT_EQ(after.cached_bytes, 0u);
    float* p = small.data<float>();
    for (int64_t i = 0; i < small.numel(); ++i) p[i] = static_cast<float>(i);
    EXPECT_EQ(p[small.numel() - 1], static_cast<float>(small.numel() - 1));
  }
  storage_cache_clear();  // the high water restarts from the live bytes (0)
  {
    Tensor a = floats(8 * kMiB), b = floats(8 * kMiB);  // high water 16 MiB
  }
  before = storage_cache_stats();
  ASSERT_EQ(before.cached_bytes, 16 * kMiB);
  // No block reaches 24 MiB: the largest (8 MiB) grows by 16 MiB, and the other goes, since the live
  // 24 MiB are the new high water.
  Tensor big = floats(24 * kMiB);
  StorageCacheStats after = storage_cache_stats();
  EXPECT_EQ(after.reshaped, before.reshaped + 1);
  EXPECT_EQ(after.fresh_bytes - before.fresh_bytes, 16 * kMiB);
  EXPECT_EQ(after.cached_bytes, 0u);
  float* p = big.data<float>();
  for (int64_t i = 0; i < big.numel(); ++i) p[i] = 1.0f;
  EXPECT_EQ(p[big.numel() - 1], 1.0f);
}

// With room under the high water nothing has to go: a miss maps fresh memory and the cache is kept.
TEST_F(StorageCacheTest, MissWithRoomUnderTheHighWaterKeepsTheCache) {
  set_storage_cache_budget(256 * kMiB);
  Tensor a = floats(32 * kMiB), b = floats(8 * kMiB);  // high water 40 MiB
  a = Tensor();                                        // cached 32, live 8
  Tensor c = floats(2 * kMiB);  // 32 cached + 10 live exceed 40: the 32 MiB block becomes c
  ASSERT_EQ(storage_cache_stats().cached_bytes, 0u);
  b = Tensor();
  c = Tensor();  // cached 8 + 2, live 0
  const StorageCacheStats before = storage_cache_stats();
  Tensor d = floats(20 * kMiB);  // 10 cached + 20 live fit under 40
  const StorageCacheStats after = storage_cache_stats();
  EXPECT_EQ(after.reshaped, before.reshaped);
  EXPECT_EQ(after.fresh_bytes - before.fresh_bytes, 20 * kMiB);
  EXPECT_EQ(after.cached_bytes, 10 * kMiB);
}

// With slack, blocks that are not live at the peak stay cached: a step that frees its activations and
// then asks for other sizes is served from the cache from its second repetition on.
TEST_F(StorageCacheTest, SlackKeepsBlocksThatAreNotLiveAtThePeak) {
  auto step = [] {
    { Tensor a = floats(8 * kMiB), b = floats(8 * kMiB); }  // the peak: 16 MiB
    Tensor c = floats(3 * kMiB), d = floats(5 * kMiB);       // other sizes, after the peak
  };
  step();
  step();
  StorageCacheStats before = storage_cache_stats();
  step();
  StorageCacheStats tight = storage_cache_stats();
  EXPECT_GT(tight.fresh_bytes, before.fresh_bytes);  // slack 1: 16 cached + 3 live exceed 16, every step
  set_storage_cache_slack(1.5);
  step();
  before = storage_cache_stats();
  step();
  StorageCacheStats loose = storage_cache_stats();
  EXPECT_EQ(loose.misses, before.misses);
  EXPECT_EQ(loose.fresh_bytes, before.fresh_bytes);
  EXPECT_LE(static_cast<double>(loose.cached_bytes + loose.live_bytes), 1.5 * static_cast<double>(loose.high_water));
  EXPECT_THROW(set_storage_cache_slack(0.5), std::invalid_argument);
  EXPECT_THROW(set_storage_cache_slack(std::nan("")), std::invalid_argument);
  EXPECT_EQ(storage_cache_slack(), 1.5);  // a refused factor changes nothing
}

TEST_F(StorageCacheTest, SlackGuardRestoresThePreviousFactor) {
  set_storage_cache_slack(1.5);
  {
    const StorageCacheSlackGuard batch(kBatchInferenceSlack);
    EXPECT_EQ(storage_cache_slack(), kBatchInferenceSlack);
  }
  EXPECT_EQ(storage_cache_slack(), 1.5);
}

// The VmFlags of the mapping holding `address` (/proc/self/smaps; "hg" = MADV_HUGEPAGE was asked for).
std::string mapping_flags(const void* address) {
  std::ifstream smaps("/proc/self/smaps");
  const auto at = reinterpret_cast<uintptr_t>(address);
  bool inside = false;
  for (std::string line; std::getline(smaps, line);) {
    uintptr_t lo = 0, hi = 0;
    char dash = 0;
    std::istringstream range(line);
    if (range >> std::hex >> lo >> dash >> hi && dash == '-' && line.find(':') > line.find(' ')) inside = lo <= at && at < hi;
    if (inside && line.rfind("VmFlags:", 0) == 0) return line;
  }
  return "";
}

TEST_F(StorageCacheTest, HugePagesAreAskedForUnlessAGuardSaysNo) {
  EXPECT_TRUE(storage_cache_huge_pages()) << "training's default";
  auto flags_of_fresh_block = [](size_t bytes) {
    storage_cache_clear();  // no cached block may serve it
    const StorageBlock block = storage_allocate(bytes);
    const std::string flags = mapping_flags(block.data);
    storage_release(block);
    return flags;
  };
  const std::string with = flags_of_fresh_block(40 * kMiB);
  ASSERT_NE(with, "") << "the block's mapping in /proc/self/smaps";
  if (!std::ifstream("/sys/kernel/mm/transparent_hugepage/enabled")) GTEST_SKIP() << "a kernel without huge pages";
  EXPECT_NE(with.find(" hg"), std::string::npos) << with;
  {
    const StorageCacheHugePagesGuard inference(false);
    EXPECT_FALSE(storage_cache_huge_pages());
    const std::string without = flags_of_fresh_block(40 * kMiB);
    ASSERT_NE(without, "");
    EXPECT_EQ(without.find(" hg"), std::string::npos) << without;
  }
  EXPECT_TRUE(storage_cache_huge_pages()) << "restored";
}

TEST_F(StorageCacheTest, ThousandStepsOfShiftingSizesStayBounded) {
  const size_t budget = 48 * kMiB;
  set_storage_cache_budget(budget);
  int64_t rss_warm = 0;
  for (int step = 0; step < 1000; ++step) {
    // A "step": six activations whose sizes drift every 100 steps, all released at the end.
    std::vector<Tensor> live;
    int shift = (step / 100) % 3;
    for (int k = 0; k < 6; ++k) {
      size_t mib = 1 + static_cast<size_t>((step + k) % 6 + shift * 2);
      live.push_back(Tensor::zeros({static_cast<int64_t>(mib * kMiB / 4)}));
    }
    live.clear();
    StorageCacheStats stats = storage_cache_stats();
    ASSERT_LE(stats.cached_bytes, budget) << "step " << step;
    ASSERT_LE(stats.cached_bytes + stats.live_bytes, stats.high_water) << "step " << step;
    if (step == 299) rss_warm = rss_bytes();
  }
  EXPECT_GT(storage_cache_stats().hits, 0);
  // Once every size mix has been seen, the process does not grow.
  int64_t growth = rss_bytes() - rss_warm;
  EXPECT_LT(growth, 8 << 20) << "RSS grew by " << growth << " bytes over 700 steps";
}

}  // namespace
}  // namespace lc2wf
