// Fused scaled-dot-product attention. One (batch item, head) pair is one cache-resident task: scores,
// key mask, softmax, dropout and P.V in a single pass; only the probabilities are saved and the
// dropout mask is recomputed from the counter-based stream in the backward pass.
#include <cmath>
#include <cstring>
#include <limits>

#include "core/autograd.h"
#include "core/kernels.h"
#include "core/ops.h"

namespace lc2wf {

namespace {

// Where the rows of one head live: element (b, h, i, d) is at b*batch + h*head + i*row + d.
struct Layout {
  int64_t batch, head, row;
  int64_t at(int64_t b, int64_t h) const { return b * batch + h * head; }
};

struct AttnShape {
  int64_t B, H, Lq, Lk, D;
};

struct DropoutPlan {
  Rng stream;
  uint64_t first = 0;
  uint64_t threshold = 0;
  double scale = 1.0;
  bool active = false;
};

constexpr int64_t kPairsPerTask = 4;

template <class T>
void attention_forward(const AttnShape& s, const T* q, Layout lq, const T* k, Layout lk, const T* v, Layout lv, T* o,
                       Layout lo, const uint8_t* mask, T scale, const DropoutPlan& drop, T* probs) {
  const int64_t Lq = s.Lq, Lk = s.Lk, D = s.D;
  parallel_for_work(s.B * s.H, kPairsPerTask, 4 * s.Lq * s.Lk * (s.D + 4), [&](int64_t p0, int64_t p1) {
    std::vector<T> kt(static_cast<size_t>(D * Lk)), pd(static_cast<size_t>(Lk));
    for (int64_t p = p0; p < p1; ++p) {
      int64_t b = p / s.H, h = p % s.H;
      const T* Q = q + lq.at(b, h);
      const T* K = k + lk.at(b, h);
      const T* V = v + lv.at(b, h);
      T* O = o + lo.at(b, h);
      T* P = probs + p * Lq * Lk;
      const uint8_t* mrow = mask ? mask + b * Lk : nullptr;
      // K transposed so each score row is a run of vector FMAs over the keys.
      for (int64_t j = 0; j < Lk; ++j)
        for (int64_t d = 0; d < D; ++d) kt[d * Lk + j] = K[j * lk.row + d];
      bool any_key = true;
      if (mrow) {
        any_key = false;
        for (int64_t j = 0; j < Lk; ++j) any_key |= !mrow[j];
      }
      for (int64_t i = 0; i < Lq; ++i) {
        T* pr = P + i * Lk;
        T* orow = O + i * lo.row;
        if (!any_key) {
          std::fill_n(pr, Lk, T(0));
          std::fill_n(orow, D, T(0));
          continue;
        }
        const T* qi = Q + i * lq.row;
        std::fill_n(pr, Lk, T(0));
        for (int64_t d = 0; d < D; ++d) {
          T qd = qi[d] * scale;
          const T* kr = kt.data() + d * Lk;
          for (int64_t j = 0; j < Lk; ++j) pr[j] += qd * kr[j];
        }
        T m = -std::numeric_limits<T>::infinity();
        for (int64_t j = 0; j < Lk; ++j)
          if (!mrow || !mrow[j]) m = std::max(m, pr[j]);
        T sum = 0;
        for (int64_t j = 0; j < Lk; ++j) {
          T e = (mrow && mrow[j]) ? T(0) : std::exp(pr[j] - m);
          pr[j] = e;
          sum += e;
        }
        T inv = T(1) / sum;
        for (int64_t j = 0; j < Lk; ++j) pr[j] *= inv;
        const T* pw = pr;
        if (drop.active) {
          uint64_t base = drop.first + static_cast<uint64_t>((p * Lq + i) * Lk);
          T sc = static_cast<T>(drop.scale);
          for (int64_t j = 0; j < Lk; ++j) pd[j] = dropout_keep(drop.stream, base + j, drop.threshold) ? pr[j] * sc : T(0);
          pw = pd.data();
        }
        std::fill_n(orow, D, T(0));
        for (int64_t j = 0; j < Lk; ++j) {
          T w = pw[j];
          if (w == T(0)) continue;
          const T* vr = V + j * lv.row;
          for (int64_t d = 0; d < D; ++d) orow[d] += w * vr[d];
        }
      }
    }
  });
}

// dq/dk/dv must not alias each other's rows; every row of the three is written (dk/dv zeroed first).
template <class T>
void attention_backward(const AttnShape& s, const T* q, Layout lq, const T* k, Layout lk, const T* v, Layout lv,
                        const T* go, Layout lo, const T* probs, T scale, const DropoutPlan& drop, T* dq, Layout ldq,
                        T* dk, Layout ldk, T* dv, Layout ldv) {
  const int64_t Lq = s.Lq, Lk = s.Lk, D = s.D;
  parallel_for_work(s.B * s.H, kPairsPerTask, 4 * s.Lq * s.Lk * (s.D + 4), [&](int64_t p0, int64_t p1) {
    std::vector<T> vt(static_cast<size_t>(D * Lk)), dp(static_cast<size_t>(Lk)), pw(static_cast<size_t>(Lk));
    std::vector<uint8_t> keep(static_cast<size_t>(Lk), 1);
    for (int64_t p = p0; p < p1; ++p) {
      int64_t b = p / s.H, h = p % s.H;
      const T* Q = q + lq.at(b, h);
      const T* K = k + lk.at(b, h);
      const T* V = v + lv.at(b, h);
      const T* GO = go + lo.at(b, h);
      const T* P = probs + p * Lq * Lk;
      T* DQ = dq + ldq.at(b, h);
      T* DK = dk + ldk.at(b, h);
      T* DV = dv + ldv.at(b, h);
      for (int64_t j = 0; j < Lk; ++j) {
        std::fill_n(DK + j * ldk.row, D, T(0));
        std::fill_n(DV + j * ldv.row, D, T(0));
        for (int64_t d = 0; d < D; ++d) vt[d * Lk + j] = V[j * lv.row + d];
      }
      T sc = static_cast<T>(drop.scale);
      for (int64_t i = 0; i < Lq; ++i) {
        const T* pr = P + i * Lk;
        const T* gi = GO + i * lo.row;
        const T* qi = Q + i * lq.row;
        T* dqi = DQ + i * ldq.row;
        if (drop.active) {
          uint64_t base = drop.first + static_cast<uint64_t>((p * Lq + i) * Lk);
          for (int64_t j = 0; j < Lk; ++j) keep[j] = dropout_keep(drop.stream, base + j, drop.threshold);
        }
        // dP_dropped = dO V^T, then through the dropout mask.
        std::fill_n(dp.data(), Lk, T(0));
        for (int64_t d = 0; d < D; ++d) {
          T g = gi[d];
          const T* vr = vt.data() + d * Lk;
          for (int64_t j = 0; j < Lk; ++j) dp[j] += g * vr[j];
        }
        for (int64_t j = 0; j < Lk; ++j) {
          pw[j] = drop.active ? (keep[j] ? pr[j] * sc : T(0)) : pr[j];
          if (drop.active) dp[j] = keep[j] ? dp[j] * sc : T(0);
        }
        // dV += P_dropped^T dO
        for (int64_t j = 0; j < Lk; ++j) {
          T w = pw[j];
          if (w == T(0)) continue;
          T* dvr = DV + j * ldv.row;
          for (int64_t d = 0; d < D; ++d) dvr[d] += w * gi[d];
        }
        // Softmax backward: dS = P * (dP - sum(P * dP)), folded with the score scale.
        T dot = 0;
        for (int64_t j = 0; j < Lk; ++j) dot += pr[j] * dp[j];
        std::fill_n(dqi, D, T(0));
        for (int64_t j = 0; j < Lk; ++j) {
          T ds = pr[j] * (dp[j] - dot) * scale;
          if (ds == T(0)) continue;
          const T* kr = K + j * lk.row;
          T* dkr = DK + j * ldk.row;
          for (int64_t d = 0; d < D; ++d) {
            dqi[d] += ds * kr[d];
            dkr[d] += ds * qi[d];
          }
        }
      }
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
  plan.first = rng.reserve(count);
  plan.stream = rng;
  plan.threshold = dropout_threshold(p);
  plan.scale = 1.0 / (1.0 - p);
  return plan;
}

void check_mask(const Tensor& mask, int64_t B, int64_t L, const char* op) {
  if (!mask.defined()) return;
  check_dtype(mask, DType::Bool, op, "key_padding_mask");
  if (mask.shape() != Shape{B, L})
    throw_arg(std::string(op) + ": key_padding_mask " + shape_str(mask.shape()) + " must be " + shape_str({B, L}));
}

}  // namespace

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
  Tensor out = Tensor::empty(q.shape(), q.dtype());
  Tensor probs = Tensor::empty({s.B, s.H, s.Lq, s.Lk}, q.dtype());
  const uint8_t* mask = key_padding_mask.defined() ? key_padding_mask.data<uint8_t>() : nullptr;
  double scale = s.D > 0 ? 1.0 / std::sqrt(static_cast<double>(s.D)) : 1.0;
  dispatch_float(q.dtype(), op, [&](auto tag) {
    using T = decltype(tag);
    attention_forward<T>(s, ptr<T>(q), lq, ptr<T>(k), lk, ptr<T>(v), lk, ptr<T>(out), lq, mask,
                         static_cast<T>(scale), drop, ptr<T>(probs));
    if (attn_weights) {
      *attn_weights = Tensor::empty({s.B, s.Lq, s.Lk}, q.dtype());
      head_average<T>(s, ptr<T>(probs), ptr<T>(*attn_weights));
    }
    return 0;
  });
  if (needs_grad({&q, &k, &v})) {
    record(out, op, {q, k, v},
           [qd = q.detach(), kd = k.detach(), vd = v.detach(), probs, drop, s, lq, lk, scale](const Tensor& g) -> std::vector<Tensor> {
             Tensor dq = Tensor::empty(qd.shape(), g.dtype());
             Tensor dk = Tensor::empty(kd.shape(), g.dtype());
             Tensor dv = Tensor::empty(vd.shape(), g.dtype());
             dispatch_float(g.dtype(), "attention backward", [&](auto tag) {
               using T = decltype(tag);
               attention_backward<T>(s, ptr<T>(qd), lq, ptr<T>(kd), lk, ptr<T>(vd), lk, ptr<T>(g), lq, ptr<T>(probs),
                                     static_cast<T>(scale), drop, ptr<T>(dq), lq, ptr<T>(dk), lk, ptr<T>(dv), lk);
               return 0;
             });
             return {dq, dk, dv};
           });
  }
  return out;
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
  Tensor out = Tensor::empty({B, L, E}, qkv.dtype());
  Tensor probs = Tensor::empty({B, num_heads, L, L}, qkv.dtype());
  const uint8_t* mask = key_padding_mask.defined() ? key_padding_mask.data<uint8_t>() : nullptr;
  double scale = Dh > 0 ? 1.0 / std::sqrt(static_cast<double>(Dh)) : 1.0;
  dispatch_float(qkv.dtype(), op, [&](auto tag) {
    using T = decltype(tag);
    const T* base = ptr<T>(qkv);
    attention_forward<T>(s, base, lin, base + E, lin, base + 2 * E, lin, ptr<T>(out), lout, mask,
                         static_cast<T>(scale), drop, ptr<T>(probs));
    if (attn_weights) {
      *attn_weights = Tensor::empty({B, L, L}, qkv.dtype());
      head_average<T>(s, ptr<T>(probs), ptr<T>(*attn_weights));
    }
    return 0;
  });
  if (needs_grad({&qkv})) {
    record(out, op, {qkv}, [xd = qkv.detach(), probs, drop, s, lin, lout, scale, E](const Tensor& g) -> std::vector<Tensor> {
      Tensor dx = Tensor::empty(xd.shape(), g.dtype());
      dispatch_float(g.dtype(), "packed_attention backward", [&](auto tag) {
        using T = decltype(tag);
        const T* base = ptr<T>(xd);
        T* dbase = ptr<T>(dx);
        attention_backward<T>(s, base, lin, base + E, lin, base + 2 * E, lin, ptr<T>(g), lout, ptr<T>(probs),
                              static_cast<T>(scale), drop, dbase, lin, dbase + E, lin, dbase + 2 * E, lin);
        return 0;
      });
      return {dx};
    });
  }
  return out;
}

}  // namespace lc2wf
