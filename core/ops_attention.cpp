// The attention ops and their reference kernel. One (batch item, head) pair is one cache-resident task:
// scores, key mask, softmax, dropout and P.V in a single pass. The reference kernel (double, and float
// shapes the fused kernel of attention_fused.cpp does not take) saves nothing but the inputs: its
// backward pass recomputes the probabilities and the counter-based dropout mask pair by pair.
#include <cmath>
#include <cstring>
#include <vector>
#include <limits>
#include <type_traits>

#include "core/attention_fused.h"
#include "core/attention_layout.h"
#include "core/autograd.h"
#include "core/kernels.h"
#include "core/ops.h"
#include "core/simd512.h"
#include "core/small_gemm.h"

namespace lc2wf {

namespace {

using attention::DropoutPlan;
using attention::kPairsPerTask;
using attention::Layout;
using attention::prefetch_next_pair;
using AttnShape = attention::Shape4;

// Softmax of one score row in place (scaled, masked keys excluded; all masked -> zeros), then the
// dropped-out copy into pd. Element j of row `row` has dropout index row * Lk + j.
template <class T, int LKC = 0>
inline void softmax_dropout_row(T* pr, T* pd, int64_t Lk_runtime, T scale, const uint8_t* mrow,
                                const DropoutPlan& drop, uint64_t row) {
  const int64_t Lk = LKC > 0 ? LKC : Lk_runtime;
  T m = -std::numeric_limits<T>::infinity();
  if (mrow) {
    for (int64_t j = 0; j < Lk; ++j) m = mrow[j] ? m : std::max(m, pr[j] * scale);
  } else {
#pragma omp simd reduction(max : m)
    for (int64_t j = 0; j < Lk; ++j) m = std::max(m, pr[j] * scale);
  }
  if (m == -std::numeric_limits<T>::infinity()) {
    std::fill_n(pr, Lk, T(0));
    std::fill_n(pd, Lk, T(0));
    return;
  }
  T sum = 0;
#pragma omp simd reduction(+ : sum)
  for (int64_t j = 0; j < Lk; ++j) {
    T e = fast_exp(pr[j] * scale - m);
    e = (mrow && mrow[j]) ? T(0) : e;
    pr[j] = e;
    sum += e;
  }
  T inv = T(1) / sum;
  if (drop.active) {
    T sc = static_cast<T>(drop.scale);
    uint64_t base = row * static_cast<uint64_t>(Lk);
#pragma omp simd
    for (int64_t j = 0; j < Lk; ++j) {
      pr[j] *= inv;
      pd[j] = drop.mask.keep(base + j) ? pr[j] * sc : T(0);
    }
  } else {
#pragma omp simd
    for (int64_t j = 0; j < Lk; ++j) {
      pr[j] *= inv;
      pd[j] = pr[j];
    }
  }
}

#if defined(__AVX512F__) && defined(__AVX512BW__) && defined(__AVX512VL__)
#define LC2WF_ATTENTION_ROW16 1
// The same row for float scores of 32 or 64 keys, held in registers: masked max, exp, sum, normalise,
// and the dropout keep mask of 16 keys per instruction.
template <int LK>
inline void softmax_dropout_row16(float* pr, float* pd, float scale, const uint8_t* mrow, const DropoutPlan& drop,
                                  uint64_t row) {
  constexpr int V = LK / 16;
  const float neg_inf = -std::numeric_limits<float>::infinity();
  __m512 x[V];
  __mmask16 valid[V];
  __m512 mx = _mm512_set1_ps(neg_inf);
  for (int v = 0; v < V; ++v) {
    x[v] = _mm512_mul_ps(_mm512_loadu_ps(pr + 16 * v), _mm512_set1_ps(scale));
    valid[v] = mrow ? _mm_cmpeq_epi8_mask(_mm_loadu_si128(reinterpret_cast<const __m128i*>(mrow + 16 * v)),
                                          _mm_setzero_si128())
                    : static_cast<__mmask16>(0xFFFF);
    mx = _mm512_mask_max_ps(mx, valid[v], mx, x[v]);
  }
  const float m = _mm512_reduce_max_ps(mx);
  if (m == neg_inf) {
    std::fill_n(pr, LK, 0.0f);
    std::fill_n(pd, LK, 0.0f);
    return;
  }
  __m512 sum = _mm512_setzero_ps();
  for (int v = 0; v < V; ++v) {
    x[v] = _mm512_maskz_mov_ps(valid[v], exp16(_mm512_sub_ps(x[v], _mm512_set1_ps(m))));
    sum = _mm512_add_ps(sum, x[v]);
  }
  const __m512 inv = _mm512_set1_ps(1.0f / _mm512_reduce_add_ps(sum));
  const __m512 keep_scale = _mm512_set1_ps(static_cast<float>(drop.scale));
  const uint64_t base = row * LK;
  for (int v = 0; v < V; ++v) {
    __m512 p = _mm512_mul_ps(x[v], inv);
    _mm512_storeu_ps(pr + 16 * v, p);
    _mm512_storeu_ps(pd + 16 * v, drop.active ? _mm512_maskz_mul_ps(drop.mask.keep16(base + 16 * v), p, keep_scale) : p);
  }
}
#endif

// Scores, softmax and dropout of one (batch item, head): P gets the probabilities, pd the dropped-out
// copy. Shared by the forward pass and the backward recomputation, so both see the same bits.
template <class T>
inline void attention_probs(const AttnShape& s, int64_t p, const T* Q, int64_t ldq, const T* K, int64_t ldk,
                            const uint8_t* mrow, T scale, const DropoutPlan& drop, T* kt, T* P, T* pd) {
  const int64_t Lq = s.Lq, Lk = s.Lk, D = s.D;
  transpose_into(Lk, D, K, ldk, kt);
  small_gemm(Lq, Lk, D, Q, ldq, kt, Lk, P, Lk);  // raw scores
  for (int64_t i = 0; i < Lq; ++i) {
    T* pr = P + i * Lk;
    T* pdr = pd + i * Lk;
    uint64_t row = static_cast<uint64_t>(p * Lq + i);
#ifdef LC2WF_ATTENTION_ROW16
    if constexpr (std::is_same_v<T, float>) {
      if (Lk == 32) {
        softmax_dropout_row16<32>(pr, pdr, scale, mrow, drop, row);
        continue;
      }
      if (Lk == 64) {
        softmax_dropout_row16<64>(pr, pdr, scale, mrow, drop, row);
        continue;
      }
    }
#endif
    if (Lk == 32)
      softmax_dropout_row<T, 32>(pr, pdr, Lk, scale, mrow, drop, row);
    else if (Lk == 64)
      softmax_dropout_row<T, 64>(pr, pdr, Lk, scale, mrow, drop, row);
    else
      softmax_dropout_row<T>(pr, pdr, Lk, scale, mrow, drop, row);
  }
}

template <class T>
void attention_forward(const AttnShape& s, const T* q, Layout lq, const T* k, Layout lk, const T* v, Layout lv, T* o,
                       Layout lo, const uint8_t* mask, T scale, const DropoutPlan& drop, T* probs) {
  const int64_t Lq = s.Lq, Lk = s.Lk, D = s.D;
  parallel_for_work(s.B * s.H, kPairsPerTask, 4 * Lq * Lk * (D + 4), [&](int64_t p0, int64_t p1) {
    // Unless the caller asked for the weights, they live in a per-task scratch block.
    std::vector<T> kt(static_cast<size_t>(D * Lk)), pd(static_cast<size_t>(Lq * Lk));
    std::vector<T> scratch(probs ? 0 : static_cast<size_t>(Lq * Lk));
    for (int64_t p = p0; p < p1; ++p) {
      int64_t b = p / s.H, h = p % s.H;
      prefetch_next_pair(s, p, q, lq, k, lk, v, lv);
      const uint8_t* mrow = mask ? mask + b * Lk : nullptr;
      T* P = probs ? probs + p * Lq * Lk : scratch.data();
      attention_probs(s, p, q + lq.at(b, h), lq.row, k + lk.at(b, h), lk.row, mrow, scale, drop, kt.data(), P,
                      pd.data());
      small_gemm(Lq, D, Lk, pd.data(), Lk, v + lv.at(b, h), lv.row, o + lo.at(b, h), lo.row);
    }
  });
}

// Writes every row of dq, dk and dv for each (batch item, head). The probabilities are recomputed
// from q and k (B*H*Lq*Lk floats that are never saved: as large as q itself at 32 keys, twice at 64).
template <class T>
void attention_backward(const AttnShape& s, const T* q, Layout lq, const T* k, Layout lk, const T* v, Layout lv,
                        const T* go, Layout lo, const uint8_t* mask, T scale, const DropoutPlan& drop, T* dq,
                        Layout ldq, T* dk, Layout ldk, T* dv, Layout ldv) {
  const int64_t Lq = s.Lq, Lk = s.Lk, D = s.D;
  parallel_for_work(s.B * s.H, kPairsPerTask, 12 * Lq * Lk * (D + 4), [&](int64_t p0, int64_t p1) {
    size_t n = static_cast<size_t>(Lq * Lk);
    std::vector<T> t(static_cast<size_t>(D * Lk)), P(n), ds(n), pd(n);
    T sc = static_cast<T>(drop.scale);
    for (int64_t p = p0; p < p1; ++p) {
      int64_t b = p / s.H, h = p % s.H;
      prefetch_next_pair(s, p, q, lq, k, lk, v, lv, go, lo);
      const T* Q = q + lq.at(b, h);
      const T* GO = go + lo.at(b, h);
      const uint8_t* mrow = mask ? mask + b * Lk : nullptr;
      attention_probs(s, p, Q, lq.row, k + lk.at(b, h), lk.row, mrow, scale, drop, t.data(), P.data(), pd.data());
      transpose_into(Lk, D, v + lv.at(b, h), lv.row, t.data());
      small_gemm(Lq, Lk, D, GO, lo.row, t.data(), Lk, ds.data(), Lk);  // dP (after dropout)
      for (int64_t i = 0; i < Lq; ++i) {
        const T* pr = P.data() + i * Lk;
        const T* pdr = pd.data() + i * Lk;
        T* dr = ds.data() + i * Lk;
        if (drop.active) {
          // The dropout scale is >= 1, so a kept positive probability stays positive in pd: pd != 0
          // marks the kept keys wherever P > 0, and where P == 0 the gradient below is 0 either way.
#pragma omp simd
          for (int64_t j = 0; j < Lk; ++j) dr[j] = pdr[j] != T(0) ? dr[j] * sc : T(0);
        }
        // Softmax backward folded with the score scale: dS = P * (dP - sum(P * dP)) * scale.
        T dot = 0;
#pragma omp simd reduction(+ : dot)
        for (int64_t j = 0; j < Lk; ++j) dot += pr[j] * dr[j];
#pragma omp simd
        for (int64_t j = 0; j < Lk; ++j) dr[j] = pr[j] * (dr[j] - dot) * scale;
      }
      small_gemm(Lq, D, Lk, ds.data(), Lk, k + lk.at(b, h), lk.row, dq + ldq.at(b, h), ldq.row);
      small_gemm_tn(Lk, D, Lq, ds.data(), Lk, Q, lq.row, dk + ldk.at(b, h), ldk.row);
      small_gemm_tn(Lk, D, Lq, pd.data(), Lk, GO, lo.row, dv + ldv.at(b, h), ldv.row);
    }
  });
}

template <class T>
void head_average(const AttnShape& s, const T* probs, T* avg) {
  int64_t LL = s.Lq * s.Lk;
  parallel_for_work(s.B, 1, s.H * s.Lq * s.Lk, [&](int64_t b0, int64_t b1) {
    for (int64_t b = b0; b < b1; ++b) {
      T* dst = avg + b * LL;
      std::fill_n(dst, LL, T(0));
      for (int64_t h = 0; h < s.H; ++h) {
        const T* src = probs + (b * s.H + h) * LL;
        for (int64_t i = 0; i < LL; ++i) dst[i] += src[i];
      }
      T inv = T(1) / static_cast<T>(s.H);
      for (int64_t i = 0; i < LL; ++i) dst[i] *= inv;
    }
  });
}

DropoutPlan make_dropout(double p, bool training, Rng& rng, uint64_t count, const char* op) {
  if (!(p >= 0.0 && p < 1.0)) throw_arg(std::string(op) + ": dropout_p must be in [0, 1), got " + std::to_string(p));
  DropoutPlan plan;
  if (!training || p == 0.0) return plan;
  plan.active = true;
  plan.mask = DropoutMask(rng, rng.reserve_tensor(count), p);
  plan.scale = 1.0 / (1.0 - p);
  return plan;
}

void check_mask(const Tensor& mask, int64_t B, int64_t L, const char* op) {
  if (!mask.defined()) return;
  check_dtype(mask, DType::Bool, op, "key_padding_mask");
  if (mask.shape() != Shape{B, L})
    throw_arg(std::string(op) + ": key_padding_mask " + shape_str(mask.shape()) + " must be " + shape_str({B, L}));
}

bool g_fused_attention = true;

// Where the three operands and the output of one call live: q, k, v as offsets into their source
// tensors (one packed qkv tensor, or three separate ones) with their head layouts.
struct Operands {
  Tensor qs, ks, vs;
  int64_t q_off, k_off, v_off;
  Layout lq, lk, lv, lo;
  bool packed;  // qs, ks and vs are one tensor, which gets one gradient
};

// What the backward pass of the fused kernel reads besides the inputs (empty for the reference kernel).
struct FusedSaved {
  Tensor stats, keep_bits;
};

bool takes_fused(DType dtype, const AttnShape& s) {
  return g_fused_attention && dtype == DType::F32 && attention::fused_supported(s.Lk, s.D);
}

// Inference with a key count the fused kernel does not take (the patch encoder over a building's
// thousands of pairs): k and v are copied with zero rows up to padded_key_count that the key mask hides,
// which gives the fused kernel's result for the real keys. Returns false when the case does not apply.
bool fused_forward_padded(const AttnShape& s, const Operands& x, Tensor& out, const uint8_t* mask, double scale,
                          const DropoutPlan& drop, const Tensor& probs, bool keep_for_backward) {
  if (!g_fused_attention || keep_for_backward || drop.active || probs.defined() || x.qs.dtype() != DType::F32) return false;
  const int64_t Lk_padded = attention::padded_key_count(s.Lk);
  if (s.Lk % 8 == 0 || !attention::fused_supported(Lk_padded, s.D)) return false;
  const int64_t HD = s.H * s.D;
  Tensor kp = Tensor::zeros({s.B, Lk_padded, HD}, DType::F32), vp = Tensor::zeros({s.B, Lk_padded, HD}, DType::F32);
  std::vector<uint8_t> padded_mask(static_cast<size_t>(s.B * Lk_padded), 1);
  const float* k = ptr<float>(x.ks) + x.k_off;
  const float* v = ptr<float>(x.vs) + x.v_off;
  float *kd = ptr<float>(kp), *vd = ptr<float>(vp);
  for (int64_t b = 0; b < s.B; ++b)
    for (int64_t i = 0; i < s.Lk; ++i) {
      padded_mask[static_cast<size_t>(b * Lk_padded + i)] = mask ? mask[b * s.Lk + i] : 0;
      for (int64_t h = 0; h < s.H; ++h) {
        std::memcpy(kd + (b * Lk_padded + i) * HD + h * s.D, k + x.lk.at(b, h) + i * x.lk.row, sizeof(float) * s.D);
        std::memcpy(vd + (b * Lk_padded + i) * HD + h * s.D, v + x.lv.at(b, h) + i * x.lv.row, sizeof(float) * s.D);
      }
    }
  const AttnShape s_padded{s.B, s.H, s.Lq, Lk_padded, s.D};
  const Layout lk_padded{Lk_padded * HD, s.D, HD};
  attention::fused_forward(s_padded, ptr<float>(x.qs) + x.q_off, x.lq, kd, lk_padded, vd, lk_padded, ptr<float>(out), x.lo,
                           padded_mask.data(), static_cast<float>(scale), drop, nullptr, nullptr, nullptr);
  return true;
}

// Runs the forward kernel into out; probs (B, H, Lq, Lk) is filled when defined.
FusedSaved run_forward(const AttnShape& s, const Operands& x, Tensor& out, const uint8_t* mask, double scale,
                       const DropoutPlan& drop, Tensor& probs, bool keep_for_backward, const char* op) {
  FusedSaved saved;
  if (takes_fused(x.qs.dtype(), s)) {
    if (keep_for_backward) {
      saved.stats = Tensor::empty({attention::fused_stats_floats(s)}, DType::F32);
      // Raw keep bits, 8 keys per byte, in a byte tensor so the storage cache accounts for them.
      if (drop.active) saved.keep_bits = Tensor::empty({attention::fused_keep_bytes(s)}, DType::Bool);
    }
    attention::fused_forward(s, ptr<float>(x.qs) + x.q_off, x.lq, ptr<float>(x.ks) + x.k_off, x.lk,
                             ptr<float>(x.vs) + x.v_off, x.lv, ptr<float>(out), x.lo, mask, static_cast<float>(scale),
                             drop, probs.defined() ? ptr<float>(probs) : nullptr,
                             saved.stats.defined() ? ptr<float>(saved.stats) : nullptr,
                             saved.keep_bits.defined() ? saved.keep_bits.data<uint8_t>() : nullptr);
    return saved;
  }
  if (fused_forward_padded(s, x, out, mask, scale, drop, probs, keep_for_backward)) return saved;
  dispatch_float(x.qs.dtype(), op, [&](auto tag) {
    using T = decltype(tag);
    attention_forward<T>(s, ptr<T>(x.qs) + x.q_off, x.lq, ptr<T>(x.ks) + x.k_off, x.lk, ptr<T>(x.vs) + x.v_off, x.lv,
                         ptr<T>(out), x.lo, mask, static_cast<T>(scale), drop,
                         probs.defined() ? ptr<T>(probs) : nullptr);
    return 0;
  });
  return saved;
}

// Writes the gradients of q, k and v into dq, dk, dv (at the operands' offsets and layouts).
void run_backward(const AttnShape& s, const Operands& x, const Tensor& g, const uint8_t* mask, double scale,
                  const DropoutPlan& drop, const FusedSaved& saved, Tensor& dq, Tensor& dk, Tensor& dv,
                  const char* op) {
  if (saved.stats.defined()) {
    attention::fused_backward(s, ptr<float>(x.qs) + x.q_off, x.lq, ptr<float>(x.ks) + x.k_off, x.lk,
                              ptr<float>(x.vs) + x.v_off, x.lv, ptr<float>(g), x.lo, mask, static_cast<float>(scale),
                              drop, ptr<float>(saved.stats),
                              saved.keep_bits.defined() ? saved.keep_bits.data<uint8_t>() : nullptr,
                              ptr<float>(dq) + x.q_off, x.lq, ptr<float>(dk) + x.k_off, x.lk,
                              ptr<float>(dv) + x.v_off, x.lv);
    return;
  }
  dispatch_float(g.dtype(), op, [&](auto tag) {
    using T = decltype(tag);
    attention_backward<T>(s, ptr<T>(x.qs) + x.q_off, x.lq, ptr<T>(x.ks) + x.k_off, x.lk, ptr<T>(x.vs) + x.v_off,
                          x.lv, ptr<T>(g), x.lo, mask, static_cast<T>(scale), drop, ptr<T>(dq) + x.q_off, x.lq,
                          ptr<T>(dk) + x.k_off, x.lk, ptr<T>(dv) + x.v_off, x.lv);
    return 0;
  });
}

// The forward pass, the head-averaged weights when asked for, and the backward closure of both ops.
Tensor attention_op(const AttnShape& s, const Operands& x, const Shape& out_shape, const Tensor& key_padding_mask,
                    const DropoutPlan& drop, bool grad, const std::vector<Tensor>& inputs, Tensor* attn_weights,
                    const char* op) {
  Tensor out = Tensor::empty(out_shape, x.qs.dtype());
  Tensor probs = attn_weights ? Tensor::empty({s.B, s.H, s.Lq, s.Lk}, x.qs.dtype()) : Tensor();
  const uint8_t* mask = key_padding_mask.defined() ? key_padding_mask.data<uint8_t>() : nullptr;
  const double scale = s.D > 0 ? 1.0 / std::sqrt(static_cast<double>(s.D)) : 1.0;
  FusedSaved saved = run_forward(s, x, out, mask, scale, drop, probs, grad, op);
  if (attn_weights) {
    *attn_weights = Tensor::empty({s.B, s.Lq, s.Lk}, x.qs.dtype());
    dispatch_float(x.qs.dtype(), op, [&](auto tag) {
      using T = decltype(tag);
      head_average<T>(s, ptr<T>(probs), ptr<T>(*attn_weights));
      return 0;
    });
  }
  if (!grad) return out;
  Operands kept{x.qs.detach(), x.ks.detach(), x.vs.detach(), x.q_off, x.k_off, x.v_off, x.lq, x.lk, x.lv, x.lo,
                x.packed};
  record(out, op, inputs,
         [kept, mask_t = key_padding_mask, drop, s, scale, saved, op](const Tensor& g) -> std::vector<Tensor> {
           const uint8_t* m = mask_t.defined() ? mask_t.data<uint8_t>() : nullptr;
           if (kept.packed) {
             Tensor dx = Tensor::empty(kept.qs.shape(), g.dtype());
             run_backward(s, kept, g, m, scale, drop, saved, dx, dx, dx, op);
             return {dx};
           }
           Tensor dq = Tensor::empty(kept.qs.shape(), g.dtype());
           Tensor dk = Tensor::empty(kept.ks.shape(), g.dtype());
           Tensor dv = Tensor::empty(kept.vs.shape(), g.dtype());
           run_backward(s, kept, g, m, scale, drop, saved, dq, dk, dv, op);
           return {dq, dk, dv};
         });
  return out;
}

}  // namespace

void set_fused_attention(bool enabled) { g_fused_attention = enabled; }
bool fused_attention_enabled() { return g_fused_attention; }

Tensor scaled_dot_product_attention(const Tensor& q, const Tensor& k, const Tensor& v, const Tensor& key_padding_mask,
                                    double dropout_p, bool training, Rng& rng, Tensor* attn_weights) {
  const char* op = "scaled_dot_product_attention";
  check_float(q, op, "q");
  check_float(k, op, "k");
  check_float(v, op, "v");
  check_same_dtype(q, k, op);
  check_same_dtype(q, v, op);
  if (q.dim() != 4 || k.dim() != 4 || k.shape() != v.shape() || q.size(0) != k.size(0) || q.size(1) != k.size(1) ||
      q.size(3) != k.size(3))
    throw_arg(std::string(op) + ": expected q (B, H, Lq, D) and k, v (B, H, Lk, D), got " + shape_str(q.shape()) +
              ", " + shape_str(k.shape()) + ", " + shape_str(v.shape()));
  AttnShape s{q.size(0), q.size(1), q.size(2), k.size(2), q.size(3)};
  check_mask(key_padding_mask, s.B, s.Lk, op);
  DropoutPlan drop = make_dropout(dropout_p, training, rng, static_cast<uint64_t>(s.B * s.H * s.Lq * s.Lk), op);
  Layout lq{s.H * s.Lq * s.D, s.Lq * s.D, s.D}, lk{s.H * s.Lk * s.D, s.Lk * s.D, s.D};
  Operands x{q, k, v, 0, 0, 0, lq, lk, lk, lq, false};
  return attention_op(s, x, q.shape(), key_padding_mask, drop, needs_grad({&q, &k, &v}), {q, k, v}, attn_weights, op);
}

Tensor packed_attention(const Tensor& qkv, int64_t num_heads, const Tensor& key_padding_mask, double dropout_p,
                        bool training, Rng& rng, Tensor* attn_weights) {
  const char* op = "packed_attention";
  check_float(qkv, op, "qkv");
  if (qkv.dim() != 3 || qkv.size(2) % 3 != 0)
    throw_arg(std::string(op) + ": qkv must be (B, L, 3E), got " + shape_str(qkv.shape()));
  int64_t B = qkv.size(0), L = qkv.size(1), E = qkv.size(2) / 3;
  if (num_heads <= 0 || E % num_heads != 0)
    throw_arg(std::string(op) + ": embedding " + std::to_string(E) + " is not divisible by num_heads " +
              std::to_string(num_heads));
  int64_t Dh = E / num_heads;
  AttnShape s{B, num_heads, L, L, Dh};
  check_mask(key_padding_mask, B, L, op);
  DropoutPlan drop = make_dropout(dropout_p, training, rng, static_cast<uint64_t>(B * num_heads * L * L), op);
  Layout lin{L * 3 * E, Dh, 3 * E}, lout{L * E, Dh, E};
  Operands x{qkv, qkv, qkv, 0, E, 2 * E, lin, lin, lin, lout, true};
  return attention_op(s, x, {B, L, E}, key_padding_mask, drop, needs_grad({&qkv}), {qkv}, attn_weights, op);
}

}  // namespace lc2wf
