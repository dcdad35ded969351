// One training step of a data-parallel job, shared by both stages: this rank's forward/backward passes
// over its share of the global batch, each drawing the dropout masks those buildings get in the whole
// batch (core/rng.h batch slices), optionally with BatchNorm statistics summed over the ranks, then the
// gradient sum over the ranks (overlapped with the last backward pass), the BatchNorm running
// statistics averaged over the ranks (per-rank statistics) and one dropout stream position for all.
// The losses are scaled by the stage to the share of the global batch, so the summed gradient is the
// global batch's gradient: a run depends on the number of ranks only through BatchNorm statistics and
// the order of floating-point sums. With one rank every operation reduces to the single-process step.
#pragma once

#include <cstdint>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "core/rng.h"
#include "nn/module.h"
#include "train/batch_share.h"
#include "train/communicator.h"
#include "train/gradient_reducer.h"

namespace lc2wf {

// Gradient buckets: big enough to keep the per-call latency small next to the bandwidth term, small
// enough that the first buckets start well before the backward pass ends (the paper's networks have
// about 1.5 M parameters, 6 MB of gradients).
constexpr int64_t kGradientBucketBytes = int64_t{1} << 20;

class DataParallel {
 public:
  DataParallel(Communicator& comm, Module& model, Rng& dropout_rng, bool synchronised_batch_norm);
  ~DataParallel();

  Communicator& comm() { return comm_; }
  int rank() const { return comm_.rank(); }
  int ranks() const { return comm_.size(); }

  // Runs this rank's passes of a batch of `batch` buildings: pass(first, count) runs the forward and
  // backward pass of buildings [first, first + count) of the batch. Returns the seconds spent waiting
  // for the gradient sum after the last backward pass.
  double run_step(int64_t batch, int64_t micro_batch, const std::function<void(int64_t first, int64_t count)>& pass);

  // Element-wise sums over the ranks (loss terms, validation counts).
  void sum(std::vector<double>& values, const char* what) { comm_.sum(values.data(), static_cast<int64_t>(values.size()), what); }

 private:
  void average_running_statistics(bool ran);

  Communicator& comm_;
  Module& model_;
  Rng& dropout_rng_;
  bool synchronised_;
  std::unique_ptr<GradientReducer> reducer_;
};

// A hash of the bits of every parameter and buffer: equal on every rank while the replicas agree.
uint64_t state_fingerprint(const Module& model);

// Makes every rank's model, optimiser slots and dropout stream rank 0's (also the start of a resumed run).
class Optimizer;
void broadcast_training_state(Communicator& comm, Module& model, Optimizer* optimizer, Rng& dropout_rng);

}  // namespace lc2wf
