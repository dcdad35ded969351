// Pre-norm Transformer encoder as in the release (DETR style): each layer is
//   h = x + Drop(MHA(LN1(x)));  y = h + Drop(W2 Drop(ReLU(W1 LN2(h))))
// and the encoder ends with a final LayerNorm.
#pragma once

#include <memory>
#include <vector>

#include "core/rng.h"
#include "core/tensor.h"
#include "nn/attention.h"
#include "nn/layers.h"
#include "nn/module.h"

namespace lc2wf {

struct EncoderSizes {
  int64_t embed_dim = 256;
  int64_t num_heads = 8;
  int64_t ffn_dim = 256;
  double dropout = 0.5;       // residual and FFN dropout
  double attn_dropout = 0.5;  // on the attention weights
};

class TransformerEncoderLayer : public Module {
 public:
  TransformerEncoderLayer(const EncoderSizes& sizes, Rng& init_rng);
  Tensor forward(const Tensor& x, const Tensor& key_padding_mask, Rng& rng, Tensor* attn_weights = nullptr);

 private:
  MultiheadAttention self_attn_;
  Linear linear1_, linear2_;
  LayerNorm norm1_, norm2_;
  Dropout dropout_, dropout1_, dropout2_;
};

class TransformerEncoder : public Module {
 public:
  TransformerEncoder(const EncoderSizes& sizes, int64_t num_layers, Rng& init_rng);
  // x (B, L, E), key_padding_mask Bool (B, L) or undefined. attn_weights gets the last layer's weights.
  Tensor forward(const Tensor& x, const Tensor& key_padding_mask, Rng& rng, Tensor* attn_weights = nullptr);

 private:
  std::vector<std::unique_ptr<TransformerEncoderLayer>> layers_;
  LayerNorm norm_;
};

}  // namespace lc2wf
