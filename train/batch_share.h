// How a data-parallel job cuts a global batch: each rank takes a contiguous share of the buildings and
// runs it in one or more forward/backward passes. Pure functions of (batch, rank, ranks, micro_batch),
// so every rank knows every other rank's share without asking.
#pragma once

#include <cstdint>
#include <string>
#include <utility>
#include <vector>

namespace lc2wf {

struct BatchShare {
  int64_t first = 0;  // index of the share's first building in the batch
  int64_t count = 0;  // may be 0 when the batch has fewer buildings than there are ranks
  bool operator==(const BatchShare&) const = default;
};

// Rank `rank`'s buildings of a batch of `batch`: [batch*rank/ranks, batch*(rank+1)/ranks).
BatchShare batch_share(int64_t batch, int rank, int ranks);

// The passes of a share as (first, count) ranges in batch indices. Per-rank BatchNorm: micro-batches of
// at most `micro` buildings (micro <= 0: one pass). Synchronised BatchNorm: every rank runs the same
// number of passes, since each pass's statistics are summed over the ranks; that is the number the
// largest share needs, and every share is cut into that many near-equal parts.
std::vector<std::pair<int64_t, int64_t>> share_passes(int64_t batch, int rank, int ranks, int64_t micro, bool synchronised);

// The problem that stops synchronised BatchNorm on a batch of `batch` (a rank would have a pass without
// buildings), or "" when there is none.
std::string synchronised_batch_problem(int64_t batch, int ranks, int64_t micro);

}  // namespace lc2wf
