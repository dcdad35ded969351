#include "train/batch_share.h"

#include <algorithm>
#include <stdexcept>
#include <string>

#include "train/stage_loop.h"

namespace lc2wf {

namespace {

int64_t passes_needed(int64_t buildings, int64_t micro) {
  return micro <= 0 || micro >= buildings ? 1 : (buildings + micro - 1) / micro;
}

}  // namespace

BatchShare batch_share(int64_t batch, int rank, int ranks) {
  if (ranks < 1 || rank < 0 || rank >= ranks || batch < 0)
    throw std::invalid_argument("batch_share: rank " + std::to_string(rank) + " of " + std::to_string(ranks) +
                                ", batch " + std::to_string(batch));
  const int64_t first = batch * rank / ranks, end = batch * (rank + 1) / ranks;
  return {first, end - first};
}

std::string synchronised_batch_problem(int64_t batch, int ranks, int64_t micro) {
  const int64_t smallest = batch / ranks, largest = (batch + ranks - 1) / ranks;
  const int64_t passes = passes_needed(largest, micro);
  if (smallest >= passes) return "";
  return "a batch of " + std::to_string(batch) + " buildings gives " + std::to_string(smallest) +
         " building(s) to some of the " + std::to_string(ranks) + " ranks for " + std::to_string(passes) +
         " synchronised pass(es)";
}

std::vector<std::pair<int64_t, int64_t>> share_passes(int64_t batch, int rank, int ranks, int64_t micro, bool synchronised) {
  const BatchShare share = batch_share(batch, rank, ranks);
  std::vector<std::pair<int64_t, int64_t>> out;
  if (!synchronised || ranks == 1) {
    if (share.count == 0) return out;
    for (const auto& [first, count] : micro_batch_ranges(static_cast<int>(share.count), micro))
      out.emplace_back(share.first + first, count);
    return out;
  }
  if (const std::string problem = synchronised_batch_problem(batch, ranks, micro); !problem.empty())
    throw std::invalid_argument(problem);
  const int64_t passes = passes_needed((batch + ranks - 1) / ranks, micro);
  for (int64_t k = 0; k < passes; ++k) {
    const int64_t begin = share.count * k / passes, end = share.count * (k + 1) / passes;
    out.emplace_back(share.first + begin, end - begin);
  }
  return out;
}

}  // namespace lc2wf
