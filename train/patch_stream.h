// Batches of stacked building patches in lc2wf-train's order: dataset/batch_loader.h shuffles the buildings
// per (seed, epoch) and seeds each batch from (seed, epoch, batch index); building k of a batch gets
// mix_seed(batch seed, k). An epoch can start at any batch (exact resume mid-epoch), and the sequence is the
// same for any number of workers.
#pragma once

#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <vector>

#include "dataset/batch_loader.h"
#include "dataset/patches.h"
#include "train/train_config.h"

namespace lc2wf {

struct PatchStreamOptions {
  int64_t batch_size = 16;
  bool shuffle = true;
  bool drop_last = true;
  int64_t workers = 1;
  uint64_t seed = 1555;
  int64_t max_batches = 0;  // 0 = all

  // A stage's stream: its schedule's batch size, last-batch rule and step cap, the run's loader threads,
  // and the stage's seed.
  static PatchStreamOptions of_stage(const StageSchedule& s, int64_t workers, uint64_t seed) {
    PatchStreamOptions o;
    o.batch_size = s.batch_size;
    o.drop_last = s.drop_last;
    o.workers = workers;
    o.seed = seed;
    o.max_batches = s.max_steps_per_epoch;
    return o;
  }
};

template <class Patches>
class PatchStream {
 public:
  // build(building, seed) makes one building's patches; it runs on loader threads.
  using BuildFn = std::function<Patches(size_t building, uint64_t seed)>;

  PatchStream(size_t num_buildings, BuildFn build, const PatchStreamOptions& o)
      : loader_(num_buildings,
                [build = std::move(build)](const std::vector<size_t>& buildings, uint64_t batch_seed) {
                  std::vector<Patches> parts;
                  for (size_t k = 0; k < buildings.size(); ++k) parts.push_back(build(buildings[k], mix_seed(batch_seed, k)));
                  return stack(parts);
                },
                loader_options(o)) {}

  int64_t batches_per_epoch() const { return static_cast<int64_t>(loader_.batches_per_epoch()); }
  // Starts `epoch` at batch `first_batch` (earlier batches are skipped without being built).
  void start(int64_t epoch, int64_t first_batch = 0) {
    loader_.start_epoch(static_cast<int>(epoch), static_cast<size_t>(first_batch));
  }
  // The next stacked batch, or nullopt at the end of the epoch.
  std::optional<Patches> next() { return loader_.next(); }

 private:
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

  BatchLoader<Patches> loader_;
};

}  // namespace lc2wf
