// Sums the gradients of a model over the ranks of a data-parallel job after each step's backward passes.
// The parameters are cut into buckets of about `bucket_bytes` in reverse registration order (roughly
// the order the backward pass finishes them); during the step's last backward pass a bucket starts its
// sum as soon as all its gradients are final, in bucket order on every rank, so the communication
// overlaps the rest of the pass. Each bucket also sums a has-gradient flag per parameter, so a
// parameter with a gradient on any rank has one on every rank afterwards.
#pragma once

#include <cstdint>
#include <memory>
#include <unordered_map>
#include <vector>

#include "core/autograd.h"
#include "core/tensor.h"
#include "train/communicator.h"

namespace lc2wf {

class GradientReducer {
 public:
  // params: F32 leaves, the same list in the same order on every rank.
  GradientReducer(Communicator& comm, std::vector<Tensor> params, int64_t bucket_bytes);
  ~GradientReducer();
  GradientReducer(const GradientReducer&) = delete;
  GradientReducer& operator=(const GradientReducer&) = delete;

  // Installs the backward hook that starts buckets early; hold it around the step's last backward pass.
  std::unique_ptr<LeafGradReadyHook> overlap_next_backward();
  // Starts the buckets not started yet, waits for all and writes the sums into the gradients. Returns
  // the seconds spent here (the communication the backward pass did not hide).
  double finish();

  int64_t num_buckets() const { return static_cast<int64_t>(buckets_.size()); }

 private:
  struct Bucket {
    std::vector<size_t> params;  // indices into params_
    int64_t floats = 0;          // gradient floats (+ one flag per parameter after them)
    std::vector<float> buffer;
    size_t ready = 0;
    std::unique_ptr<Communicator::PendingSum> pending;
  };
  void on_ready(const TensorImpl* leaf);
  void start(Bucket& bucket);
  void start_in_order();

  Communicator& comm_;
  std::vector<Tensor> params_;
  std::vector<Bucket> buckets_;
  std::unordered_map<const TensorImpl*, size_t> bucket_of_;  // leaf -> bucket index
  size_t next_ = 0;                                          // next bucket to start
};

}  // namespace lc2wf
