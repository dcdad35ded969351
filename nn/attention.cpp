#include "nn/attention.h"

#include <stdexcept>
#include <string>

#include "core/ops.h"
#include "nn/init.h"

namespace lc2wf {

MultiheadAttention::MultiheadAttention(int64_t embed_dim, int64_t num_heads, double attn_dropout, Rng& init_rng)
    : num_heads_(num_heads),
      attn_dropout_(attn_dropout),
      out_proj_(embed_dim, embed_dim, init_rng, LinearInit::XavierWeight) {
  if (num_heads <= 0 || embed_dim % num_heads != 0)
    throw std::invalid_argument("MultiheadAttention: embed_dim " + std::to_string(embed_dim) +
                                " is not divisible by num_heads " + std::to_string(num_heads));
  in_proj_weight_ = register_parameter("in_proj_weight", Tensor::empty({3 * embed_dim, embed_dim}));
  xavier_uniform_(in_proj_weight_, init_rng);
  in_proj_bias_ = register_parameter("in_proj_bias", Tensor::zeros({3 * embed_dim}));
  register_module("out_proj", out_proj_);
  Tensor out_bias = out_proj_.bias();
  out_bias.fill_(0.0);
}

Tensor MultiheadAttention::forward(const Tensor& x, const Tensor& key_padding_mask, Rng& rng,
                                   Tensor* attn_weights) const {
  const Tensor qkv = linear(x, in_proj_weight_, in_proj_bias_);
  const Tensor heads = packed_attention(qkv, num_heads_, key_padding_mask, attn_dropout_, is_training(), rng,
                                        attn_weights);
  return out_proj_.forward(heads);
}

Tensor MultiheadAttention::forward(const Tensor& x, const LayerNorm& norm, const Tensor& key_padding_mask, Rng& rng,
                                   Tensor* attn_weights) const {
  const Tensor qkv = layer_norm_linear(x, norm.weight(), norm.bias(), norm.eps(), in_proj_weight_, in_proj_bias_);
  const Tensor heads = packed_attention(qkv, num_heads_, key_padding_mask, attn_dropout_, is_training(), rng,
                                        attn_weights);
  return out_proj_.forward(heads);
}

}  // namespace lc2wf
