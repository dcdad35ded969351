// Training losses of the two stages.
//
// Junction, "release" (the loss the released code trains with): 2-class softmax cross-entropy over all B*G patches plus
//   reg_weight * mean_b[ sum_g sum_xyz |offset - target| * cls / (sum_g cls + 1e-8) ].
// Junction, "paper": binary cross-entropy on the positive logit z1 - z0 (so sigmoid of it equals the
//   softmax confidence used at inference) plus reg_weight * the same per-building mean with squared
//   error instead of absolute error.
// Edge (as the release): 5-class cross-entropy with class weights, PyTorch's weighted mean.
#pragma once

#include "core/tensor.h"
#include "nn/config.h"
#include "nn/junction_net.h"

namespace lc2wf {

struct JunctionTargets {
  Tensor labels;   // I64 (B, G): 1 = patch holds a junction, 0 otherwise
  Tensor offsets;  // float (B, G, 3): regression target, only read where labels == 1
};

struct LossTerms {
  Tensor total;           // scalar, differentiable
  Tensor classification;  // scalar, differentiable
  Tensor regression;      // scalar, differentiable (already multiplied by reg_weight)
};

LossTerms junction_loss(const JunctionOutput& out, const JunctionTargets& targets, const JunctionLossConfig& config);

// logits (B, P, C), labels I64 (B, P). With `weight_total` > 0 the class-weighted sum is divided by it
// instead of by this batch's own weight sum, so the losses of micro-batches cut from one batch, each
// divided by the whole batch's edge_loss_weight(), add up to the batch's loss (and so do their gradients).
Tensor edge_loss(const Tensor& logits, const Tensor& labels, const EdgeLossConfig& config, double weight_total = 0.0);
// Sum of the class weights of `labels` (the denominator of edge_loss's weighted mean).
double edge_loss_weight(const Tensor& labels, const EdgeLossConfig& config);

}  // namespace lc2wf
