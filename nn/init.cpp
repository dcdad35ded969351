#include "nn/init.h"

#include <cmath>
#include <stdexcept>

namespace lc2wf {

namespace {
template <class T>
void fill_uniform(T* data, int64_t n, double lo, double hi, const Rng& rng, uint64_t first) {
  for (int64_t i = 0; i < n; ++i) data[i] = static_cast<T>(lo + (hi - lo) * rng.uniform(first + i));
}
}  // namespace

void uniform_(Tensor& t, double lo, double hi, Rng& rng) {
  const uint64_t first = rng.reserve(static_cast<uint64_t>(t.numel()));
  if (t.dtype() == DType::F32) fill_uniform(t.data<float>(), t.numel(), lo, hi, rng, first);
  else if (t.dtype() == DType::F64) fill_uniform(t.data<double>(), t.numel(), lo, hi, rng, first);
  else throw std::invalid_argument(std::string("uniform_: expected a float tensor, got ") + dtype_name(t.dtype()));
}

void xavier_uniform_(Tensor& weight, Rng& rng) {
  if (weight.dim() != 2) throw std::invalid_argument("xavier_uniform_: expected a 2-D weight, got " + shape_str(weight.shape()));
  const double bound = std::sqrt(6.0 / static_cast<double>(weight.size(0) + weight.size(1)));
  uniform_(weight, -bound, bound, rng);
}

void kaiming_uniform_default_(Tensor& weight, Rng& rng) {
  if (weight.dim() != 2) throw std::invalid_argument("kaiming_uniform_default_: expected a 2-D weight, got " + shape_str(weight.shape()));
  const double bound = 1.0 / std::sqrt(static_cast<double>(weight.size(1)));
  uniform_(weight, -bound, bound, rng);
}

}  // namespace lc2wf
