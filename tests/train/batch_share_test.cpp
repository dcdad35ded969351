// How a data-parallel job cuts a global batch: disjoint contiguous shares covering the batch, and the
// passes of each share (micro-batches, or the same number of passes on every rank for synchronised
// BatchNorm).
#include <gtest/gtest.h>

#include "train/batch_share.h"

namespace lc2wf {
namespace {

using Ranges = std::vector<std::pair<int64_t, int64_t>>;

TEST(BatchShare, SharesAreDisjointContiguousAndCoverTheBatch) {
  for (int64_t batch : {0, 1, 3, 16, 17, 32}) {
    for (int ranks : {1, 2, 3, 4, 16, 64}) {
      int64_t next = 0, smallest = batch, largest = 0;
      for (int r = 0; r < ranks; ++r) {
        const BatchShare s = batch_share(batch, r, ranks);
        EXPECT_EQ(s.first, next) << batch << " " << ranks << " " << r;
        next += s.count;
        smallest = std::min(smallest, s.count);
        largest = std::max(largest, s.count);
      }
      EXPECT_EQ(next, batch);
      EXPECT_LE(largest - smallest, 1) << "shares differ by at most one building";
    }
  }
  EXPECT_EQ(batch_share(16, 0, 1), (BatchShare{0, 16}));
  EXPECT_EQ(batch_share(3, 0, 4), (BatchShare{0, 0}));  // fewer buildings than ranks: some have none
  EXPECT_EQ(batch_share(3, 1, 4), (BatchShare{0, 1}));
  EXPECT_THROW(batch_share(16, 2, 2), std::invalid_argument);
}

TEST(BatchShare, PerRankPassesAreMicroBatchesOfTheShare) {
  // One process: the micro-batches of the whole batch, as before.
  EXPECT_EQ(share_passes(32, 0, 1, 4, false), (Ranges{{0, 4}, {4, 4}, {8, 4}, {12, 4}, {16, 4}, {20, 4}, {24, 4}, {28, 4}}));
  EXPECT_EQ(share_passes(16, 0, 1, 0, true), (Ranges{{0, 16}}));
  // Two ranks, micro-batches of 4: the same passes as one process's, split between them.
  EXPECT_EQ(share_passes(32, 1, 2, 4, false), (Ranges{{16, 4}, {20, 4}, {24, 4}, {28, 4}}));
  EXPECT_EQ(share_passes(5, 1, 2, 0, false), (Ranges{{2, 3}}));
  EXPECT_TRUE(share_passes(1, 0, 2, 0, false).empty());
}

TEST(BatchShare, SynchronisedPassesAreAlignedOverTheRanks) {
  // 10, 11 and 11 buildings in passes of at most 4: three passes everywhere.
  for (int r = 0; r < 3; ++r) {
    const Ranges p = share_passes(32, r, 3, 4, true);
    ASSERT_EQ(p.size(), 3u) << r;
    int64_t covered = 0;
    for (const auto& [first, count] : p) {
      EXPECT_GE(count, 1);
      EXPECT_LE(count, 4);
      covered += count;
    }
    EXPECT_EQ(covered, batch_share(32, r, 3).count);
  }
  EXPECT_EQ(synchronised_batch_problem(32, 3, 4), "");
  EXPECT_NE(synchronised_batch_problem(3, 4, 0), "");  // a rank without buildings cannot join the sums
  EXPECT_THROW(share_passes(3, 0, 4, 0, true), std::invalid_argument);
}

}  // namespace
}  // namespace lc2wf
