// Multi-head self-attention with a packed in-projection (3E x E weight + bias, layout [q | k | v]),
// like torch.nn.MultiheadAttention, evaluated by core's packed_attention without permute copies.
#pragma once

#include "core/rng.h"
#include "core/tensor.h"
#include "nn/layers.h"
#include "nn/module.h"

namespace lc2wf {

class MultiheadAttention : public Module {
 public:
  // Xavier-uniform in-projection and out-projection weights, zero biases (the release's init).
  MultiheadAttention(int64_t embed_dim, int64_t num_heads, double attn_dropout, Rng& init_rng);
  // x (B, L, E); key_padding_mask Bool (B, L), true = ignore that key, or undefined.
  // attn_weights, when given, receives the head-averaged weights (B, L, L) without gradient.
  Tensor forward(const Tensor& x, const Tensor& key_padding_mask, Rng& rng, Tensor* attn_weights = nullptr) const;
  // The same on norm(x), with the LayerNorm fused into the in-projection (its output is not kept).
  Tensor forward(const Tensor& x, const LayerNorm& norm, const Tensor& key_padding_mask, Rng& rng,
                 Tensor* attn_weights = nullptr) const;

 private:
  int64_t num_heads_;
  double attn_dropout_;
  Tensor in_proj_weight_, in_proj_bias_;
  Linear out_proj_;
};

}  // namespace lc2wf
