#include "nn/layers.h"

#include <cmath>

#include "core/ops.h"
#include "nn/init.h"

namespace lc2wf {

Linear::Linear(int64_t in, int64_t out, Rng& init_rng, LinearInit init, bool bias) {
  weight_ = register_parameter("weight", Tensor::empty({out, in}));
  if (init == LinearInit::XavierWeight) xavier_uniform_(weight_, init_rng);
  else kaiming_uniform_default_(weight_, init_rng);
  if (bias) {
    bias_ = register_parameter("bias", Tensor::empty({out}));
    const double bound = 1.0 / std::sqrt(static_cast<double>(in));
    uniform_(bias_, -bound, bound, init_rng);
  }
}

Tensor Linear::forward(const Tensor& x) const { return linear(x, weight_, bias_); }

BatchNorm::BatchNorm(int64_t channels, double momentum, double eps) : momentum_(momentum), eps_(eps) {
  weight_ = register_parameter("weight", Tensor::ones({channels}));
  bias_ = register_parameter("bias", Tensor::zeros({channels}));
  running_mean_ = register_buffer("running_mean", Tensor::zeros({channels}));
  running_var_ = register_buffer("running_var", Tensor::ones({channels}));
}

Tensor BatchNorm::forward(const Tensor& x) {
  return batch_norm(x, weight_, bias_, running_mean_, running_var_, is_training(), momentum_, eps_);
}

LayerNorm::LayerNorm(int64_t channels, double eps) : eps_(eps) {
  weight_ = register_parameter("weight", Tensor::ones({channels}));
  bias_ = register_parameter("bias", Tensor::zeros({channels}));
}

Tensor LayerNorm::forward(const Tensor& x) const { return layer_norm(x, weight_, bias_, eps_); }

Tensor Dropout::forward(const Tensor& x, Rng& rng) const { return dropout(x, p_, is_training(), rng); }

Tensor Dropout::forward_added_to(const Tensor& x, const Tensor& a, Rng& rng) const {
  return add_dropout(x, a, p_, is_training(), rng);
}

Tensor Dropout::forward_relu(const Tensor& a, Rng& rng) const { return dropout_relu(a, p_, is_training(), rng); }

}  // namespace lc2wf
