// A small MLP with plain SGD used by the determinism and memory tests.
#pragma once

#include <cmath>
#include <vector>

#include "core/ops.h"
#include "core/rng.h"
#include "core/tensor.h"

namespace lc2wf::test {

class TinyMlp {
 public:
  TinyMlp(int64_t in, int64_t hidden, uint64_t seed) : rng_(seed) {
    w1_ = init({hidden, in});
    b1_ = Tensor::zeros({hidden}).set_requires_grad();
    gamma_ = Tensor::ones({hidden}).set_requires_grad();
    beta_ = Tensor::zeros({hidden}).set_requires_grad();
    w2_ = init({hidden, hidden});
    b2_ = Tensor::zeros({hidden}).set_requires_grad();
    w3_ = init({1, hidden});
    b3_ = Tensor::zeros({1}).set_requires_grad();
    running_mean_ = Tensor::zeros({hidden});
    running_var_ = Tensor::ones({hidden});
  }

  Tensor forward(const Tensor& x, bool training) {
    Tensor h = linear(x, w1_, b1_);
    h = relu(batch_norm(h, gamma_, beta_, running_mean_, running_var_, training));
    h = dropout(h, 0.1, training, rng_);
    h = relu(layer_norm(linear(h, w2_, b2_), Tensor(), Tensor()));
    return linear(h, w3_, b3_);
  }

  // One SGD step on the mean squared error; returns the loss.
  double step(const Tensor& x, const Tensor& y, double lr) {
    Tensor loss = mse_loss(forward(x, true), y);
    loss.backward();
    for (Tensor* p : params()) {
      float* w = p->data<float>();
      const float* g = p->grad().data<float>();
      for (int64_t i = 0; i < p->numel(); ++i) w[i] -= static_cast<float>(lr) * g[i];
      p->zero_grad();
    }
    return loss.item();
  }

  std::vector<Tensor*> params() { return {&w1_, &b1_, &gamma_, &beta_, &w2_, &b2_, &w3_, &b3_}; }

 private:
  Tensor init(const Shape& s) {
    std::vector<float> v(static_cast<size_t>(shape_numel(s)));
    double bound = 1.0 / std::sqrt(static_cast<double>(s[1]));
    for (float& x : v) x = static_cast<float>(rng_.next_uniform(-bound, bound));
    return Tensor::from_vector(v, s).set_requires_grad();
  }

  Rng rng_;
  Tensor w1_, b1_, gamma_, beta_, w2_, b2_, w3_, b3_, running_mean_, running_var_;
};

// Regression data y = sin(sum x) on uniform inputs.
inline std::pair<Tensor, Tensor> make_regression(int64_t n, int64_t in, uint64_t seed) {
  Rng rng(seed);
  std::vector<float> x(static_cast<size_t>(n * in)), y(static_cast<size_t>(n));
  for (int64_t i = 0; i < n; ++i) {
    double s = 0;
    for (int64_t j = 0; j < in; ++j) {
      x[i * in + j] = static_cast<float>(rng.next_uniform(-1, 1));
      s += x[i * in + j];
    }
    y[i] = static_cast<float>(std::sin(s));
  }
  return {Tensor::from_vector(x, {n, in}), Tensor::from_vector(y, {n, 1})};
}

}  // namespace lc2wf::test
