// Batches of stacked building patches built ahead of the compute on loader threads (dataset/
// batch_loader.h), in a fixed order. The epoch's building order and each batch's seed depend only on
// (seed, epoch, batch index), so an epoch can start at any batch (exact resume mid-epoch) and the
// sequence is the same for any number of workers. In a data-parallel job each rank builds only its
// share of every batch (train/batch_share.h); a building's patches do not depend on the share.
#pragma once

#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <vector>

#include "dataset/patches.h"
#include "train/batch_share.h"

namespace lc2wf {

struct PatchStreamOptions {
  int64_t batch_size = 16;
  bool shuffle = true;
  bool drop_last = true;
  int64_t workers = 1;
  uint64_t seed = 1555;
  int64_t max_batches = 0;  // 0 = all
  int rank = 0, ranks = 1;  // data-parallel job: this rank builds its share of every batch
};

template <class Patches>
struct StreamBatch {
  Patches patches;   // the share's buildings, stacked (nothing when share.count == 0)
  int64_t batch = 0; // buildings in the whole batch
  BatchShare share;  // which of them this rank holds
};

template <class Patches>
class PatchStream {
 public:
  // build(buildings, seed) makes one building's patches; it runs on loader threads.
  using BuildFn = std::function<Patches(size_t building, uint64_t seed)>;

  PatchStream(size_t num_buildings, BuildFn build, PatchStreamOptions options);
  ~PatchStream();
  PatchStream(const PatchStream&) = delete;
  PatchStream& operator=(const PatchStream&) = delete;

  int64_t batches_per_epoch() const;
  // Starts `epoch` at batch `first_batch` (earlier batches are skipped without being built).
  void start(int64_t epoch, int64_t first_batch = 0);
  // The next batch (this rank's share of it), or nullopt at the end of the epoch.
  std::optional<StreamBatch<Patches>> next();

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

extern template class PatchStream<JunctionPatches>;
extern template class PatchStream<PairPatches>;

}  // namespace lc2wf
