// Junction model of the LC2WF paper and release: LPT over the line patches around G sample points, then a 2-logit
// classification head and a 3-offset regression head per patch.
#pragma once

#include <cstdint>

#include "core/rng.h"
#include "core/tensor.h"
#include "nn/config.h"
#include "nn/head.h"
#include "nn/lpt.h"
#include "nn/module.h"

namespace lc2wf {

struct JunctionOutput {
  Tensor logits;   // (B, G, 2): [not a junction, junction]
  Tensor offsets;  // (B, G, 3): junction position minus sample point (normalised units)
};

class JunctionNet : public Module {
 public:
  // Weights are drawn from Rng(seed); dropout uses its own stream that is part of the training state.
  explicit JunctionNet(const JunctionNetConfig& config, uint64_t seed = 1555);
  // x (B, G, N, F), mask Bool (B, G, N), true = padded slot.
  JunctionOutput forward(const Tensor& x, const Tensor& mask);
  const JunctionNetConfig& config() const { return config_; }
  Rng& dropout_rng() { return dropout_rng_; }
  void set_recompute_mlp(bool on) { lpt_.set_recompute_mlp(on); }  // LinePatchTransformer::set_recompute_mlp

 private:
  JunctionNetConfig config_;
  Rng init_rng_;
  LinePatchTransformer lpt_;
  Head cls_head_, reg_head_;
  Rng dropout_rng_;
};

}  // namespace lc2wf
