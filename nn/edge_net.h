// Edge (connectivity) model of the LC2WF paper and release: LPT over the 64-line patches of junction pairs, the patch
// encoder running over all pairs of a building, and one head with 5 class logits per pair.
#pragma once

#include <cstdint>

#include "core/rng.h"
#include "core/tensor.h"
#include "nn/config.h"
#include "nn/head.h"
#include "nn/lpt.h"
#include "nn/module.h"

namespace lc2wf {

class EdgeNet : public Module {
 public:
  explicit EdgeNet(const EdgeNetConfig& config, uint64_t seed = 1555);
  // x (B, P, N, F), mask Bool (B, P, N). Returns logits (B, P, num_classes).
  Tensor forward(const Tensor& x, const Tensor& mask);
  const EdgeNetConfig& config() const { return config_; }
  Rng& dropout_rng() { return dropout_rng_; }
  void set_recompute_mlp(bool on) { lpt_.set_recompute_mlp(on); }  // LinePatchTransformer::set_recompute_mlp

 private:
  EdgeNetConfig config_;
  Rng init_rng_;
  LinePatchTransformer lpt_;
  Head cls_head_;
  Rng dropout_rng_;
};

}  // namespace lc2wf
