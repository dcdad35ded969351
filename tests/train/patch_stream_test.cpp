// The training batch order is part of a run's resumable state: a run resumed with --resume must continue
// the same sequence of (building, seed) it started with. These values were recorded with the trainer's
// order before its loader was shared with dataset/sampling/batch_loader.h and must never change.
#include <gtest/gtest.h>

#include <cstdint>
#include <vector>

#include "train/patch_stream.h"

namespace lc2wf {
namespace {

// One "patch" per building carrying the building index and the seed the stream gave it.
JunctionPatches tagged(size_t building, uint64_t seed) {
  JunctionPatches p;
  p.num_patches = 1;
  p.label = {static_cast<int32_t>(building)};
  p.endpoint = {static_cast<int32_t>(seed & 0x7fffffff)};
  return p;
}

// FNV-1a over every (building, seed bits) the stream delivers in one epoch from `first`.
uint64_t digest(PatchStream<JunctionPatches>& stream, int64_t epoch, int64_t first, std::vector<int>* buildings) {
  stream.start(epoch, first);
  uint64_t h = 1469598103934665603ull;
  auto add = [&h](int32_t v) {
    for (int byte = 0; byte < 4; ++byte) h = (h ^ ((static_cast<uint32_t>(v) >> (8 * byte)) & 0xff)) * 1099511628211ull;
  };
  while (auto p = stream.next()) {
    for (int b = 0; b < p->patches.batch; ++b) {
      add(p->patches.label[b]);
      add(p->patches.endpoint[b]);
      if (buildings) buildings->push_back(p->patches.label[b]);
    }
  }
  return h;
}

PatchStreamOptions options(bool drop_last, int64_t workers, int64_t max_batches) {
  PatchStreamOptions o;
  o.batch_size = 3;
  o.drop_last = drop_last;
  o.workers = workers;
  o.seed = 1556;  // lc2wf-train passes config.seed + 1
  o.max_batches = max_batches;
  return o;
}

TEST(PatchStream, OrderAndSeedsArePinnedForResume) {
  PatchStream<JunctionPatches> stream(11, tagged, options(true, 1, 0));
  ASSERT_EQ(stream.batches_per_epoch(), 3);
  std::vector<int> epoch0;
  EXPECT_EQ(digest(stream, 0, 0, &epoch0), 0xd91ff3dfaf469387ull);
  EXPECT_EQ(epoch0, (std::vector<int>{0, 6, 10, 9, 2, 1, 5, 7, 4}));
  EXPECT_EQ(digest(stream, 5, 0, nullptr), 0xe9c7d5887d9305bbull);
}

TEST(PatchStream, ResumingMidEpochContinuesTheSameSequence) {
  PatchStream<JunctionPatches> whole(11, tagged, options(false, 2, 0)), resumed(11, tagged, options(false, 1, 0));
  std::vector<int> all, tail;
  digest(whole, 3, 0, &all);
  digest(resumed, 3, 2, &tail);
  ASSERT_EQ(all.size(), 11u);
  EXPECT_EQ(tail, std::vector<int>(all.begin() + 6, all.end()));
  EXPECT_EQ(digest(whole, 3, 0, nullptr), digest(resumed, 3, 0, nullptr));
  EXPECT_EQ(digest(resumed, 3, 2, nullptr), 0xb9475b00f3f6bdc2ull);
}

TEST(PatchStream, MaxBatchesCutsTheEpoch) {
  PatchStream<JunctionPatches> stream(11, tagged, options(false, 1, 2));
  EXPECT_EQ(stream.batches_per_epoch(), 2);
  std::vector<int> seen;
  digest(stream, 1, 0, &seen);
  EXPECT_EQ(seen.size(), 6u);
}

// A data-parallel job: the ranks' shares of each batch, taken in rank order, are the one-process batch
// with the same seeds, so the pinned order above holds for any number of ranks.
TEST(PatchStream, RankSharesPartitionEachBatch) {
  std::vector<int> single;
  PatchStream<JunctionPatches> whole(11, tagged, options(false, 1, 0));
  const uint64_t expected = digest(whole, 2, 0, &single);
  for (int ranks : {2, 3, 4}) {
    std::vector<std::vector<std::pair<int, int>>> per_rank(ranks);  // (building, seed) per rank, batch by batch
    std::vector<int64_t> batch_sizes;
    for (int r = 0; r < ranks; ++r) {
      PatchStreamOptions o = options(false, 2, 0);
      o.rank = r;
      o.ranks = ranks;
      PatchStream<JunctionPatches> stream(11, tagged, o);
      stream.start(2);
      int64_t batch = 0;
      while (auto p = stream.next()) {
        EXPECT_EQ(p->share, batch_share(p->batch, r, ranks));
        if (r == 0) batch_sizes.push_back(p->batch);
        ASSERT_EQ(p->share.count, p->share.count > 0 ? p->patches.batch : 0);
        for (int b = 0; b < p->share.count; ++b) per_rank[r].push_back({p->patches.label[b], p->patches.endpoint[b]});
        ++batch;
      }
      EXPECT_EQ(batch, whole.batches_per_epoch());
    }
    // Interleave the shares back into batch order and compare with the one-process epoch.
    std::vector<int> merged;
    std::vector<size_t> taken(ranks, 0);
    for (int64_t n : batch_sizes)
      for (int r = 0; r < ranks; ++r)
        for (int64_t k = 0; k < batch_share(n, r, ranks).count; ++k) merged.push_back(per_rank[r][taken[r]++].first);
    EXPECT_EQ(merged, single) << ranks << " ranks";
  }
  EXPECT_EQ(digest(whole, 2, 0, nullptr), expected);
  PatchStreamOptions bad = options(false, 1, 0);
  bad.rank = 2;
  bad.ranks = 2;
  EXPECT_THROW(PatchStream<JunctionPatches>(11, tagged, bad), std::invalid_argument);
}

}  // namespace
}  // namespace lc2wf
