// Every differentiable op of the engine. Each op is one function whose forward and backward live side
// by side in core/ops_*.cpp; core/README.md lists the gradient formula of every input.
// Float ops accept F32 or F64 (all float inputs of one op must share the dtype); masks are Bool,
// indices and class targets I64. Misuse throws std::invalid_argument naming the op and the shapes.
#pragma once

#include <functional>
#include <optional>
#include <vector>

#include "core/rng.h"
#include "core/tensor.h"

namespace lc2wf {

// ---------------------------------------------------------------- elementwise (NumPy broadcasting)
Tensor add(const Tensor& a, const Tensor& b);
Tensor sub(const Tensor& a, const Tensor& b);
Tensor mul(const Tensor& a, const Tensor& b);
Tensor div(const Tensor& a, const Tensor& b);
Tensor add(const Tensor& a, double s);
Tensor sub(const Tensor& a, double s);  // a - s
Tensor rsub(double s, const Tensor& a);  // s - a
Tensor mul(const Tensor& a, double s);
Tensor div(const Tensor& a, double s);
Tensor rdiv(double s, const Tensor& a);  // s / a
Tensor neg(const Tensor& a);
Tensor exp(const Tensor& a);
Tensor log(const Tensor& a);
Tensor sqrt(const Tensor& a);
Tensor pow(const Tensor& a, double exponent);
Tensor relu(const Tensor& a);
Tensor sigmoid(const Tensor& a);
Tensor tanh(const Tensor& a);
Tensor abs(const Tensor& a);

inline Tensor operator+(const Tensor& a, const Tensor& b) { return add(a, b); }
inline Tensor operator-(const Tensor& a, const Tensor& b) { return sub(a, b); }
inline Tensor operator*(const Tensor& a, const Tensor& b) { return mul(a, b); }
inline Tensor operator/(const Tensor& a, const Tensor& b) { return div(a, b); }
inline Tensor operator+(const Tensor& a, double s) { return add(a, s); }
inline Tensor operator-(const Tensor& a, double s) { return sub(a, s); }
inline Tensor operator*(const Tensor& a, double s) { return mul(a, s); }
inline Tensor operator/(const Tensor& a, double s) { return div(a, s); }
inline Tensor operator+(double s, const Tensor& a) { return add(a, s); }
inline Tensor operator-(double s, const Tensor& a) { return rsub(s, a); }
inline Tensor operator*(double s, const Tensor& a) { return mul(a, s); }
inline Tensor operator/(double s, const Tensor& a) { return rdiv(s, a); }
inline Tensor operator-(const Tensor& a) { return neg(a); }

// Reduces a broadcast gradient back to `shape` (sums over the broadcast axes). The backward of every
// broadcasting op goes through this one helper.
Tensor sum_to(const Tensor& grad, const Shape& shape);
Shape broadcast_shapes(const Shape& a, const Shape& b);  // throws naming both shapes

// ---------------------------------------------------------------- reductions
Tensor sum(const Tensor& a);  // all elements -> shape []
Tensor sum(const Tensor& a, const std::vector<int64_t>& axes, bool keepdim = false);
Tensor mean(const Tensor& a);
Tensor mean(const Tensor& a, const std::vector<int64_t>& axes, bool keepdim = false);
// max/min pass the gradient to the first extremal element along the reduced axes.
Tensor max(const Tensor& a, const std::vector<int64_t>& axes, bool keepdim = false);
Tensor min(const Tensor& a, const std::vector<int64_t>& axes, bool keepdim = false);

// ---------------------------------------------------------------- linear algebra
// 2-D (M,K)x(K,N), batched (...,M,K)x(...,K,N) with broadcast batch dims, and (...,M,K)x(K,N).
Tensor matmul(const Tensor& a, const Tensor& b);
// y = x W^T + b over the last axis of x: x (..., in), weight (out, in), bias (out) or undefined.
Tensor linear(const Tensor& x, const Tensor& weight, const Tensor& bias = Tensor());

// ---------------------------------------------------------------- shape and indexing
Tensor concat(const std::vector<Tensor>& parts, int64_t axis);
Tensor stack(const std::vector<Tensor>& parts, int64_t axis);
Tensor slice(const Tensor& a, int64_t axis, int64_t start, int64_t end, int64_t step = 1);
Tensor index_select(const Tensor& a, int64_t axis, const Tensor& index);  // index: I64 1-D
// out[i][j][k] = a[i][index[i][j][k]][k] for axis 1 (PyTorch gather); index I64, same ndim as a.
Tensor gather(const Tensor& a, int64_t axis, const Tensor& index);
Tensor expand(const Tensor& a, const Shape& shape);  // broadcast to shape (copies)
Tensor repeat(const Tensor& a, const std::vector<int64_t>& repeats);  // tile like torch.repeat

// ---------------------------------------------------------------- masking
// Where mask (Bool, broadcastable to a) is true, the output is `value`; gradient flows elsewhere.
Tensor masked_fill(const Tensor& a, const Tensor& mask, double value);
Tensor where(const Tensor& mask, const Tensor& a, const Tensor& b);

// ---------------------------------------------------------------- neural-network ops
// Stable (row max subtracted) along `axis`.
Tensor softmax(const Tensor& a, int64_t axis);
Tensor log_softmax(const Tensor& a, int64_t axis);
// Inverted dropout with a counter-based mask: deterministic for a given rng state at any thread count.
// Identity when !training or p == 0.
Tensor dropout(const Tensor& a, double p, bool training, Rng& rng);
// x + dropout(a) (same shapes), the residual after a dropped sub-layer, in one pass: the same values and
// the same draws as the two ops, without the dropped tensor in memory.
Tensor add_dropout(const Tensor& x, const Tensor& a, double p, bool training, Rng& rng);
// relu(dropout(a)) in one pass, the same values and draws as the two ops; its backward reads the output
// only (y > 0 exactly where the mask kept a positive value), so the mask is not recomputed.
Tensor dropout_relu(const Tensor& a, double p, bool training, Rng& rng);
// Normalises over the last axis; weight/bias (C) may be undefined.
Tensor layer_norm(const Tensor& x, const Tensor& weight, const Tensor& bias, double eps = 1e-5);
// Channels-last batch norm: x (M, C), statistics over the M rows. In training the batch statistics
// are used and running_mean/running_var (C, no grad) are updated in place with the unbiased variance,
// like PyTorch; in eval the running buffers are used. weight/bias (C) may be undefined.
Tensor batch_norm(const Tensor& x, const Tensor& weight, const Tensor& bias, Tensor& running_mean,
                  Tensor& running_var, bool training, double momentum = 0.1, double eps = 1e-5);

// While alive, batch_norm in training mode on this thread takes its statistics over the rows of every
// process of a data-parallel job (synchronised BatchNorm). `sum(values, n)` adds n doubles element-wise
// across the processes, in place; it is called once in the forward and once in the backward pass of each
// batch_norm, in the same order on every process. The weight and bias gradients stay per process (the
// trainer sums all gradients afterwards). Guards nest; the innermost one is used.
class BatchNormSyncGuard {
 public:
  using Sum = std::function<void(double* values, int64_t n)>;
  explicit BatchNormSyncGuard(Sum sum);
  ~BatchNormSyncGuard();
  BatchNormSyncGuard(const BatchNormSyncGuard&) = delete;
  BatchNormSyncGuard& operator=(const BatchNormSyncGuard&) = delete;

 private:
  Sum sum_;
  const Sum* previous_;
};

// ---------------------------------------------------------------- recompute in backward (activation memory)
// y = linear(layer_norm(x, norm_weight, norm_bias, eps), weight, bias) saving only x and the weights: the
// normalised rows are rebuilt in the backward pass, one (rows x in) activation less than the two ops.
Tensor layer_norm_linear(const Tensor& x, const Tensor& norm_weight, const Tensor& norm_bias, double eps,
                         const Tensor& weight, const Tensor& bias = Tensor());
// Activation checkpointing: y = fn(inputs, false) is computed without recording and only the inputs are
// saved; the backward pass calls fn(leaves, true) with recording on and back-propagates through that
// local graph. fn must give the same values both times and read nothing else that needs a gradient;
// `recompute` lets it skip side effects such as running-statistics updates.
using CheckpointFn = std::function<Tensor(const std::vector<Tensor>& inputs, bool recompute)>;
Tensor checkpoint(const std::vector<Tensor>& inputs, const CheckpointFn& fn);

// ---------------------------------------------------------------- losses (fused, stable)
enum class Reduction { None, Mean, Sum };
// logits (M, C), target I64 (M). Mean reduction is PyTorch's weighted mean: sum(w_t * nll) / sum(w_t)
// over non-ignored rows. class_weight (C) may be undefined.
Tensor cross_entropy(const Tensor& logits, const Tensor& target, const Tensor& class_weight = Tensor(),
                     int64_t ignore_index = -100, Reduction reduction = Reduction::Mean);
// max(x,0) - x*y + log1p(exp(-|x|)); finite for any logit.
Tensor bce_with_logits(const Tensor& logits, const Tensor& target, Reduction reduction = Reduction::Mean);
Tensor l1_loss(const Tensor& a, const Tensor& b, Reduction reduction = Reduction::Mean);
Tensor mse_loss(const Tensor& a, const Tensor& b, Reduction reduction = Reduction::Mean);

// ---------------------------------------------------------------- attention
// q, k, v: (B, H, L, D). key_padding_mask: Bool (B, L), true = ignore that key, or undefined.
// softmax(q k^T / sqrt(D)) with masked keys at -inf; a row whose keys are all masked yields zeros
// (no NaN). Dropout on the attention weights. Returns (B, H, L, D). If attn_weights is given it
// receives the head-averaged attention weights (B, L, L) without gradient.
Tensor scaled_dot_product_attention(const Tensor& q, const Tensor& k, const Tensor& v,
                                    const Tensor& key_padding_mask, double dropout_p, bool training,
                                    Rng& rng, Tensor* attn_weights = nullptr);
// The same attention on the packed output of a multi-head in-projection, so no permute copies are
// needed: qkv (B, L, 3E) laid out as [q | k | v], each split into num_heads heads of E/num_heads.
// Returns (B, L, E) with the heads concatenated, ready for the out-projection.
Tensor packed_attention(const Tensor& qkv, int64_t num_heads, const Tensor& key_padding_mask,
                        double dropout_p, bool training, Rng& rng, Tensor* attn_weights = nullptr);
// Float attention runs the fused AVX2 kernel where the build and shape allow (key count and head
// width multiples of 8), else the reference kernel that double uses. Tests and benchmarks switch the
// fused kernel off to compare both in one process; the setting is process-wide.
void set_fused_attention(bool enabled);
bool fused_attention_enabled();

}  // namespace lc2wf
