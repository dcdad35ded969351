// Batches of stacked building patches in lc2wf-train's order: dataset/sampling/batch_loader.h shuffles the buildings
// per (seed, epoch) and seeds each batch from (seed, epoch, batch index); building k of a batch gets
// mix_seed(batch seed, k). An epoch can start at any batch (exact resume mid-epoch), and the sequence is the
// same for any number of workers. In a data-parallel job each rank builds only its share of every batch
// (train/batch_share.h); a building's patches do not depend on the share.
#pragma once

#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <vector>

#include "dataset/sampling/batch_loader.h"
#include "dataset/sampling/patches.h"
#include "train/batch_share.h"
#include "train/train_config.h"

namespace lc2wf {

struct PatchStreamOptions {
  int64_t batch_size = 16;
  bool shuffle = true;
  bool drop_last = true;
  int64_t workers = 1;
  uint64_t seed = 1555;
  int64_t max_batches = 0;  // 0 = all
  int rank = 0, ranks = 1;  // data-parallel job: this rank builds its share of every batch

  // A stage's stream: its schedule's batch size, last-batch rule and step cap, the run's loader threads,
  // the stage's seed, and this rank's place in the job.
  static PatchStreamOptions of_stage(const StageSchedule& s, int64_t workers, uint64_t seed, int rank = 0, int ranks = 1) {
    PatchStreamOptions o;
    o.batch_size = s.batch_size;
    o.drop_last = s.drop_last;
    o.workers = workers;
    o.seed = seed;
    o.max_batches = s.max_steps_per_epoch;
    o.rank = rank;
    o.ranks = ranks;
    return o;
  }
  void Check() const {
    if (ranks < 1 || rank < 0 || rank >= ranks) throw std::invalid_argument("PatchStreamOptions.rank must be in [0, ranks)");
  }
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
  // build(building, seed) makes one building's patches; it runs on loader threads.
  using BuildFn = std::function<Patches(size_t building, uint64_t seed)>;

  PatchStream(size_t num_buildings, BuildFn build, const PatchStreamOptions& o)
      : loader_(num_buildings, share_builder(std::move(build), checked(o)), loader_options(o)) {}

  int64_t batches_per_epoch() const { return static_cast<int64_t>(loader_.batches_per_epoch()); }
  // Starts `epoch` at batch `first_batch` (earlier batches are skipped without being built).
  void start(int64_t epoch, int64_t first_batch = 0) {
    loader_.start_epoch(static_cast<int>(epoch), static_cast<size_t>(first_batch));
  }
  // The next batch (this rank's share of it), or nullopt at the end of the epoch.
  std::optional<StreamBatch<Patches>> next() { return loader_.next(); }

 private:
  static const PatchStreamOptions& checked(const PatchStreamOptions& o) {
    o.Check();
    return o;
  }
  static typename BatchLoader<StreamBatch<Patches>>::BuildFn share_builder(BuildFn build, const PatchStreamOptions& o) {
    return [build = std::move(build), rank = o.rank, ranks = o.ranks](const std::vector<size_t>& buildings, uint64_t batch_seed) {
      StreamBatch<Patches> out;
      out.batch = static_cast<int64_t>(buildings.size());
      out.share = batch_share(out.batch, rank, ranks);
      std::vector<Patches> parts;
      for (int64_t k = out.share.first; k < out.share.first + out.share.count; ++k)
        parts.push_back(build(buildings[static_cast<size_t>(k)], mix_seed(batch_seed, static_cast<uint64_t>(k))));
      if (!parts.empty()) out.patches = stack(parts);
      return out;
    };
  }
  static LoaderOptions loader_options(const PatchStreamOptions& o) {
    LoaderOptions lo;
    lo.batch_size = static_cast<int>(o.batch_size);
    lo.workers = static_cast<int>(o.workers);
    lo.prefetch_batches = 2;
    lo.shuffle = o.shuffle;
    lo.drop_last = o.drop_last;
    lo.seed = o.seed;
    lo.max_batches = o.max_batches;
    return lo;
  }

  BatchLoader<StreamBatch<Patches>> loader_;
};

}  // namespace lc2wf
