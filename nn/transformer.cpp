#include "nn/transformer.h"

#include <string>

#include "core/ops.h"

namespace lc2wf {

TransformerEncoderLayer::TransformerEncoderLayer(const EncoderSizes& s, Rng& init_rng)
    : self_attn_(s.embed_dim, s.num_heads, s.attn_dropout, init_rng),
      linear1_(s.embed_dim, s.ffn_dim, init_rng, LinearInit::XavierWeight),
      linear2_(s.ffn_dim, s.embed_dim, init_rng, LinearInit::XavierWeight),
      norm1_(s.embed_dim),
      norm2_(s.embed_dim),
      dropout_(s.dropout),
      dropout1_(s.dropout),
      dropout2_(s.dropout) {
  register_module("self_attn", self_attn_);
  register_module("linear1", linear1_);
  register_module("linear2", linear2_);
  register_module("norm1", norm1_);
  register_module("norm2", norm2_);
  register_module("dropout", dropout_);
  register_module("dropout1", dropout1_);
  register_module("dropout2", dropout2_);
}

Tensor TransformerEncoderLayer::forward(const Tensor& x, const Tensor& key_padding_mask, Rng& rng,
                                        Tensor* attn_weights) {
  // Both LayerNorms are fused into the product that follows them, so their outputs are rebuilt in the
  // backward pass instead of being kept: two (rows x E) activations less per layer during training.
  const Tensor attn = self_attn_.forward(x, norm1_, key_padding_mask, rng, attn_weights);
  // Each dropout is fused with the add or ReLU after it: one pass over memory instead of two, and the
  // dropped tensor never exists (same values and draws as dropping first).
  const Tensor h = dropout1_.forward_added_to(x, attn, rng);
  // Drop(ReLU(z)) == ReLU(Drop(z)) exactly (the mask scales by 0 or 1/(1-p) >= 0, same draws), but in
  // this order the one tensor ReLU keeps for its backward is also linear2's saved input: one activation
  // of (rows x ffn) less per layer during training.
  const Tensor hidden = layer_norm_linear(h, norm2_.weight(), norm2_.bias(), norm2_.eps(), linear1_.weight(),
                                          linear1_.bias());
  const Tensor ffn = linear2_.forward(dropout_.forward_relu(hidden, rng));
  return dropout2_.forward_added_to(h, ffn, rng);
}

TransformerEncoder::TransformerEncoder(const EncoderSizes& sizes, int64_t num_layers, Rng& init_rng)
    : norm_(sizes.embed_dim) {
  for (int64_t i = 0; i < num_layers; ++i) {
    layers_.push_back(std::make_unique<TransformerEncoderLayer>(sizes, init_rng));
    register_module("layers." + std::to_string(i), *layers_.back());
  }
  register_module("norm", norm_);
}

Tensor TransformerEncoder::forward(const Tensor& x, const Tensor& key_padding_mask, Rng& rng, Tensor* attn_weights) {
  Tensor h = x;
  for (auto& layer : layers_) h = layer->forward(h, key_padding_mask, rng, attn_weights);
  return norm_.forward(h);
}

}  // namespace lc2wf
