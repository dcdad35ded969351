// Basic layers on channels-last features (M, C): Linear, BatchNorm (the release's 1x1 Conv + BatchNorm
// pair becomes Linear + BatchNorm with statistics over all M rows), LayerNorm and Dropout.
#pragma once

#include "core/rng.h"
#include "core/tensor.h"
#include "nn/module.h"

namespace lc2wf {

enum class LinearInit { PyTorchDefault, XavierWeight };

class Linear : public Module {
 public:
  // PyTorchDefault: Kaiming-uniform(a=sqrt 5) weight, U(+-1/sqrt(in)) bias.
  // XavierWeight: Xavier-uniform weight (the release's transformer matrices), same default bias.
  Linear(int64_t in, int64_t out, Rng& init_rng, LinearInit init = LinearInit::PyTorchDefault, bool bias = true);
  Tensor forward(const Tensor& x) const;  // x (..., in) -> (..., out)
  const Tensor& weight() const { return weight_; }
  const Tensor& bias() const { return bias_; }

 private:
  Tensor weight_, bias_;
};

class BatchNorm : public Module {
 public:
  explicit BatchNorm(int64_t channels, double momentum = 0.1, double eps = 1e-5);
  Tensor forward(const Tensor& x);  // x (M, C); updates the running statistics in training mode
  const Tensor& weight() const { return weight_; }
  const Tensor& bias() const { return bias_; }
  const Tensor& running_mean() const { return running_mean_; }
  const Tensor& running_var() const { return running_var_; }
  double momentum() const { return momentum_; }
  double eps() const { return eps_; }

 private:
  Tensor weight_, bias_, running_mean_, running_var_;
  double momentum_, eps_;
};

class LayerNorm : public Module {
 public:
  explicit LayerNorm(int64_t channels, double eps = 1e-5);
  Tensor forward(const Tensor& x) const;  // normalises the last axis
  const Tensor& weight() const { return weight_; }
  const Tensor& bias() const { return bias_; }
  double eps() const { return eps_; }

 private:
  Tensor weight_, bias_;
  double eps_;
};

class Dropout : public Module {
 public:
  explicit Dropout(double p) : p_(p) {}
  Tensor forward(const Tensor& x, Rng& rng) const;  // identity in eval mode or when p == 0
  // x + forward(a) and relu(forward(a)), each in one pass (core/ops.h add_dropout, dropout_relu).
  Tensor forward_added_to(const Tensor& x, const Tensor& a, Rng& rng) const;
  Tensor forward_relu(const Tensor& a, Rng& rng) const;
  double p() const { return p_; }

 private:
  double p_;
};

}  // namespace lc2wf
