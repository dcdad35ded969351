// Finite-difference gradient check in F64 on a random-weighted scalar loss L = sum(f(x) * R).
// A fixed random R (not sum(f(x))) matters: normalisation layers have zero gradient under sum().
#pragma once

#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <sstream>
#include <vector>

#include "core/ops.h"
#include "core/rng.h"
#include "core/tensor.h"

namespace lc2wf::test {

// Uniform values in [lo, hi), F64 unless told otherwise.
inline Tensor random_tensor(const Shape& shape, Rng& rng, double lo = -1.0, double hi = 1.0, DType dtype = DType::F64) {
  std::vector<double> v(static_cast<size_t>(shape_numel(shape)));
  for (double& x : v) x = rng.next_uniform(lo, hi);
  Tensor t = Tensor::from_vector(v, shape);
  return dtype == DType::F64 ? t : t.to(dtype);
}

// Values in [lo, hi) with |x| >= margin, for ops with a kink at 0 (relu, abs).
inline Tensor random_away_from_zero(const Shape& shape, Rng& rng, double margin = 0.05) {
  std::vector<double> v(static_cast<size_t>(shape_numel(shape)));
  for (double& x : v) {
    double u = rng.next_uniform(margin, 1.0);
    x = rng.next_uniform() < 0.5 ? -u : u;
  }
  return Tensor::from_vector(v, shape);
}

struct GradCheckOptions {
  double eps = 1e-6;
  double rtol = 1e-5;
  double atol = 1e-7;
  uint64_t weight_seed = 1234;
};

using TestFn = std::function<Tensor(const std::vector<Tensor>&)>;

inline double weighted_sum(const Tensor& out, const std::vector<double>& r) {
  std::vector<double> o = out.to_vector();
  double s = 0;
  for (size_t i = 0; i < o.size(); ++i) s += o[i] * r[i];
  return s;
}

// Compares the backward gradient of every input with central differences.
inline ::testing::AssertionResult gradcheck(const TestFn& f, std::vector<Tensor> inputs, GradCheckOptions opt = {}) {
  for (Tensor& t : inputs) {
    if (t.dtype() != DType::F64) return ::testing::AssertionFailure() << "gradcheck needs F64 inputs";
    t.zero_grad();
    t.set_requires_grad(true);
  }
  Tensor out = f(inputs);
  Rng rng(opt.weight_seed);
  std::vector<double> r(static_cast<size_t>(out.numel()));
  for (double& x : r) x = rng.next_uniform(-1.0, 1.0);
  Tensor R = Tensor::from_vector(r, out.shape());
  Tensor loss = sum(mul(out, R));
  loss.backward();
  std::ostringstream errors;
  int bad = 0;
  for (size_t k = 0; k < inputs.size(); ++k) {
    Tensor g = inputs[k].grad();
    std::vector<double> analytic = g.defined() ? g.to_vector() : std::vector<double>(inputs[k].numel(), 0.0);
    double* x = inputs[k].data<double>();
    for (int64_t i = 0; i < inputs[k].numel(); ++i) {
      double saved = x[i];
      double lp, lm;
      {
        NoGradGuard no_grad;
        x[i] = saved + opt.eps;
        lp = weighted_sum(f(inputs), r);
        x[i] = saved - opt.eps;
        lm = weighted_sum(f(inputs), r);
      }
      x[i] = saved;
      double numeric = (lp - lm) / (2 * opt.eps);
      double diff = std::abs(numeric - analytic[i]);
      if (!(diff <= opt.atol + opt.rtol * std::abs(numeric)) || std::isnan(analytic[i])) {
        if (++bad <= 8)
          errors << "\n  input " << k << " element " << i << ": analytic " << analytic[i] << " numeric " << numeric;
      }
    }
  }
  if (bad) return ::testing::AssertionFailure() << bad << " gradient mismatches" << errors.str();
  return ::testing::AssertionSuccess();
}

}  // namespace lc2wf::test
