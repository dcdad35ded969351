// Parameter initialisers matching PyTorch's formulas, drawn from our counter-based Rng so a seed fixes
// every weight at any thread count.
#pragma once

#include "core/rng.h"
#include "core/tensor.h"

namespace lc2wf {

// Fills t (F32 or F64) in place with U(lo, hi), element i from draw first+i of one reserved block.
void uniform_(Tensor& t, double lo, double hi, Rng& rng);
// Xavier/Glorot uniform for a 2-D weight (fan_out, fan_in): bound sqrt(6 / (fan_in + fan_out)).
void xavier_uniform_(Tensor& weight, Rng& rng);
// PyTorch's default Linear/Conv weight init, Kaiming-uniform with a = sqrt(5): bound 1/sqrt(fan_in).
void kaiming_uniform_default_(Tensor& weight, Rng& rng);

}  // namespace lc2wf
