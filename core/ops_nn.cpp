// softmax / log_softmax, layer_norm and batch_norm with fused backward passes (dropout: ops_dropout.cpp).
#include <algorithm>
#include <cmath>
#include <cstring>
#include <type_traits>

#include "core/autograd.h"
#include "core/kernels.h"
#include "core/ops.h"
#include "core/simd512.h"

namespace lc2wf {

namespace {

constexpr int64_t kNormRows = 64;  // rows per block for column statistics (fixed => deterministic)

#ifdef __AVX512F__
// Rows of exactly 32 floats (attention-sized): two registers per row, no loop overhead.
inline void softmax_row32(const float* xr, float* yr, bool log_space) {
  __m512 a = _mm512_loadu_ps(xr), b = _mm512_loadu_ps(xr + 16);
  __m512 m = _mm512_set1_ps(_mm512_reduce_max_ps(_mm512_max_ps(a, b)));
  __m512 ea = exp16(_mm512_sub_ps(a, m)), eb = exp16(_mm512_sub_ps(b, m));
  float s = _mm512_reduce_add_ps(_mm512_add_ps(ea, eb));
  if (log_space) {
    __m512 lse = _mm512_add_ps(m, _mm512_set1_ps(std::log(s)));
    _mm512_storeu_ps(yr, _mm512_sub_ps(a, lse));
    _mm512_storeu_ps(yr + 16, _mm512_sub_ps(b, lse));
  } else {
    __m512 inv = _mm512_set1_ps(1.0f / s);
    _mm512_storeu_ps(yr, _mm512_mul_ps(ea, inv));
    _mm512_storeu_ps(yr + 16, _mm512_mul_ps(eb, inv));
  }
}
#endif

// One softmax (or log-softmax) row. RC > 0 fixes the row length at compile time so short rows (attention's 32/64 keys) unroll fully.
template <class T, int RC = 0>
void softmax_row(const T* __restrict xr, T* __restrict yr, int64_t R_runtime, bool log_space) {
  const int64_t R = RC > 0 ? RC : R_runtime;
  T m = xr[0];
#pragma omp simd reduction(max : m)
  for (int64_t i = 0; i < R; ++i) m = std::max(m, xr[i]);
  T s = 0;
  if (log_space) {
#pragma omp simd reduction(+ : s)
    for (int64_t i = 0; i < R; ++i) s += fast_exp(xr[i] - m);
    T lse = m + std::log(s);
#pragma omp simd
    for (int64_t i = 0; i < R; ++i) yr[i] = xr[i] - lse;
  } else {
#pragma omp simd reduction(+ : s)
    for (int64_t i = 0; i < R; ++i) {
      yr[i] = fast_exp(xr[i] - m);
      s += yr[i];
    }
    T inv = T(1) / s;
#pragma omp simd
    for (int64_t i = 0; i < R; ++i) yr[i] *= inv;
  }
}


// Softmax (or log-softmax) over contiguous rows of length R.
template <class T>
void softmax_rows(const T* x, T* y, int64_t rows, int64_t R, bool log_space) {
  parallel_for_work(rows, std::max<int64_t>(1, kElemGrain / std::max<int64_t>(1, R)), 8 * R, [&](int64_t r0, int64_t r1) {
#ifdef __AVX512F__
    if constexpr (std::is_same_v<T, float>) {
      if (R == 32) {
        for (int64_t r = r0; r < r1; ++r) softmax_row32(x + r * R, y + r * R, log_space);
        return;
      }
    }
#endif
    if (R == 32)
      for (int64_t r = r0; r < r1; ++r) softmax_row<T, 32>(x + r * R, y + r * R, R, log_space);
    else if (R == 64)
      for (int64_t r = r0; r < r1; ++r) softmax_row<T, 64>(x + r * R, y + r * R, R, log_space);
    else
      for (int64_t r = r0; r < r1; ++r) softmax_row<T>(x + r * R, y + r * R, R, log_space);
  });
}

Tensor softmax_last(const Tensor& a, bool log_space) {
  const char* name = log_space ? "log_softmax" : "softmax";
  int64_t R = a.size(-1);
  int64_t rows = R == 0 ? 0 : a.numel() / R;
  Tensor out = Tensor::empty(a.shape(), a.dtype());
  dispatch_float(a.dtype(), name, [&](auto tag) {
    using T = decltype(tag);
    if (rows > 0) softmax_rows(ptr<T>(a), ptr<T>(out), rows, R, log_space);
    return 0;
  });
  if (needs_grad({&a})) {
    record(out, name, {a}, [y = out.detach(), rows, R, log_space](const Tensor& g) -> std::vector<Tensor> {
      Tensor dx = Tensor::empty(g.shape(), g.dtype());
      dispatch_float(g.dtype(), "softmax backward", [&](auto tag) {
        using T = decltype(tag);
        const T* pg = ptr<T>(g);
        const T* py = ptr<T>(y);
        T* pd = ptr<T>(dx);
        parallel_for_work(rows, std::max<int64_t>(1, kElemGrain / R), 4 * R, [&](int64_t r0, int64_t r1) {
          for (int64_t r = r0; r < r1; ++r) {
            const T* gr = pg + r * R;
            const T* yr = py + r * R;
            T* dr = pd + r * R;
            T s = 0;
            if (log_space) {
              for (int64_t i = 0; i < R; ++i) s += gr[i];
              for (int64_t i = 0; i < R; ++i) dr[i] = gr[i] - fast_exp(yr[i]) * s;
            } else {
              for (int64_t i = 0; i < R; ++i) s += gr[i] * yr[i];
              for (int64_t i = 0; i < R; ++i) dr[i] = yr[i] * (gr[i] - s);
            }
          }
        });
        return 0;
      });
      return {dx};
    });
  }
  return out;
}

Tensor softmax_any(const Tensor& a, int64_t axis, bool log_space) {
  const char* name = log_space ? "log_softmax" : "softmax";
  check_float(a, name, "a");
  if (a.dim() == 0) throw_arg(std::string(name) + ": needs at least one dimension");
  axis = normalize_axis(axis, a.dim(), name);
  if (axis == a.dim() - 1) return softmax_last(a, log_space);
  // Other axes: move the axis last (copy), normalise rows, move it back.
  return softmax_last(a.transpose(axis, -1), log_space).transpose(axis, -1);
}

}  // namespace

Tensor softmax(const Tensor& a, int64_t axis) { return softmax_any(a, axis, false); }
Tensor log_softmax(const Tensor& a, int64_t axis) { return softmax_any(a, axis, true); }

Tensor layer_norm(const Tensor& x, const Tensor& weight, const Tensor& bias, double eps) {
  check_float(x, "layer_norm", "x");
  if (x.dim() == 0) throw_arg("layer_norm: needs at least one dimension");
  int64_t C = x.size(-1);
  int64_t M = C == 0 ? 0 : x.numel() / C;
  for (const Tensor* p : {&weight, &bias}) {
    if (!p->defined()) continue;
    check_float(*p, "layer_norm", p == &weight ? "weight" : "bias");
    check_same_dtype(x, *p, "layer_norm");
    if (p->shape() != Shape{C})
      throw_arg("layer_norm: " + std::string(p == &weight ? "weight " : "bias ") + shape_str(p->shape()) +
                " does not match the last axis of " + shape_str(x.shape()));
  }
  Tensor out = Tensor::empty(x.shape(), x.dtype());
  Tensor mean_t = Tensor::empty({M}, x.dtype()), rstd_t = Tensor::empty({M}, x.dtype());
  dispatch_float(x.dtype(), "layer_norm", [&](auto tag) {
    using T = decltype(tag);
    const T* px = ptr<T>(x);
    const T* pw = weight.defined() ? ptr<T>(weight) : nullptr;
    const T* pb = bias.defined() ? ptr<T>(bias) : nullptr;
    T* py = ptr<T>(out);
    T* pm = ptr<T>(mean_t);
    T* pr = ptr<T>(rstd_t);
    parallel_for_work(M, kNormRows, 4 * C, [&](int64_t r0, int64_t r1) {
      for (int64_t r = r0; r < r1; ++r) {
        const T* xr = px + r * C;
        T* yr = py + r * C;
        T s = 0;
#pragma omp simd reduction(+ : s)
        for (int64_t i = 0; i < C; ++i) s += xr[i];
        T mean = s / static_cast<T>(C);
        T v = 0;
#pragma omp simd reduction(+ : v)
        for (int64_t i = 0; i < C; ++i) v += (xr[i] - mean) * (xr[i] - mean);
        T rstd = T(1) / std::sqrt(v / static_cast<T>(C) + static_cast<T>(eps));
        pm[r] = mean;
        pr[r] = rstd;
#pragma omp simd
        for (int64_t i = 0; i < C; ++i) {
          T h = (xr[i] - mean) * rstd;
          yr[i] = (pw ? h * pw[i] : h) + (pb ? pb[i] : T(0));
        }
      }
    });
    return 0;
  });
  if (needs_grad({&x, &weight, &bias})) {
    bool gx = x.requires_grad(), gw = weight.defined() && weight.requires_grad(),
         gb = bias.defined() && bias.requires_grad();
    Tensor wd = weight.defined() ? weight.detach() : Tensor();
    record(out, "layer_norm", {x, weight, bias},
           [xd = x.detach(), wd, mean_t, rstd_t, gx, gw, gb, M, C](const Tensor& g) -> std::vector<Tensor> {
             Tensor dx = gx ? Tensor::empty(xd.shape(), g.dtype()) : Tensor();
             int64_t nblk = num_chunks(M, kNormRows);
             Tensor part_w = Tensor::zeros({nblk, C}, g.dtype()), part_b = Tensor::zeros({nblk, C}, g.dtype());
             dispatch_float(g.dtype(), "layer_norm backward", [&](auto tag) {
               using T = decltype(tag);
               const T* px = ptr<T>(xd);
               const T* pg = ptr<T>(g);
               const T* pw = wd.defined() ? ptr<T>(wd) : nullptr;
               const T* pm = ptr<T>(mean_t);
               const T* pr = ptr<T>(rstd_t);
               T* pd = gx ? ptr<T>(dx) : nullptr;
               T* ppw = ptr<T>(part_w);
               T* ppb = ptr<T>(part_b);
               parallel_for_work(M, kNormRows, 4 * C, [&](int64_t r0, int64_t r1) {
                 T* accw = ppw + (r0 / kNormRows) * C;
                 T* accb = ppb + (r0 / kNormRows) * C;
                 for (int64_t r = r0; r < r1; ++r) {
                   const T* xr = px + r * C;
                   const T* gr = pg + r * C;
                   T mean = pm[r], rstd = pr[r];
                   T s1 = 0, s2 = 0;  // sums of dxhat and dxhat * xhat
#pragma omp simd reduction(+ : s1, s2)
                   for (int64_t i = 0; i < C; ++i) {
                     T h = (xr[i] - mean) * rstd;
                     T dh = pw ? gr[i] * pw[i] : gr[i];
                     s1 += dh;
                     s2 += dh * h;
                     accw[i] += gr[i] * h;
                     accb[i] += gr[i];
                   }
                   if (pd) {
                     T* dr = pd + r * C;
                     T invc = T(1) / static_cast<T>(C);
#pragma omp simd
                     for (int64_t i = 0; i < C; ++i) {
                       T h = (xr[i] - mean) * rstd;
                       T dh = pw ? gr[i] * pw[i] : gr[i];
                       dr[i] = rstd * (dh - s1 * invc - h * s2 * invc);
                     }
                   }
                 }
               });
               return 0;
             });
             Tensor dw = gw ? sum(part_w, {0}) : Tensor();
             Tensor db = gb ? sum(part_b, {0}) : Tensor();
             return {dx, dw, db};
           });
  }
  return out;
}

namespace {
thread_local const BatchNormSyncGuard::Sum* g_batch_norm_sync = nullptr;
}  // namespace

BatchNormSyncGuard::BatchNormSyncGuard(Sum sum) : sum_(std::move(sum)), previous_(g_batch_norm_sync) {
  g_batch_norm_sync = &sum_;
}
BatchNormSyncGuard::~BatchNormSyncGuard() { g_batch_norm_sync = previous_; }

Tensor batch_norm(const Tensor& x, const Tensor& weight, const Tensor& bias, Tensor& running_mean,
                  Tensor& running_var, bool training, double momentum, double eps) {
  check_float(x, "batch_norm", "x");
  if (x.dim() < 2) throw_arg("batch_norm: x must be (M, C), got " + shape_str(x.shape()));
  int64_t C = x.size(-1);
  int64_t M = C == 0 ? 0 : x.numel() / C;
  for (const Tensor* p : {&weight, &bias, static_cast<const Tensor*>(&running_mean), static_cast<const Tensor*>(&running_var)}) {
    if (!p->defined()) continue;
    const char* nm = p == &weight ? "weight" : p == &bias ? "bias" : p == &running_mean ? "running_mean" : "running_var";
    check_float(*p, "batch_norm", nm);
    check_same_dtype(x, *p, "batch_norm");
    if (p->shape() != Shape{C})
      throw_arg(std::string("batch_norm: ") + nm + " " + shape_str(p->shape()) + " does not match the channels of " +
                shape_str(x.shape()));
  }
  if (!training && (!running_mean.defined() || !running_var.defined()))
    throw_arg("batch_norm: eval mode needs running_mean and running_var");
  if (training && M < 2)
    throw_arg("batch_norm: training needs more than one row per channel, got " + shape_str(x.shape()));
  Tensor out = Tensor::empty(x.shape(), x.dtype());
  Tensor mean_t = Tensor::empty({C}, x.dtype()), rstd_t = Tensor::empty({C}, x.dtype());
  int64_t nblk = num_chunks(M, kNormRows);
  // Synchronised statistics: rows of every process; count_all is their number.
  const BatchNormSyncGuard::Sum* sync = training ? g_batch_norm_sync : nullptr;
  int64_t count_all = M;
  dispatch_float(x.dtype(), "batch_norm", [&](auto tag) {
    using T = decltype(tag);
    const T* px = ptr<T>(x);
    T* pm = ptr<T>(mean_t);
    T* pr = ptr<T>(rstd_t);
    if (training) {
      // One pass over memory: each 64-row block (L2-resident) gets its own mean and sum of squared
      // deviations, and the blocks are merged in block order with Chan's pairwise formula.
      std::vector<T> bmean(static_cast<size_t>(nblk * C)), bm2(static_cast<size_t>(nblk * C));
      parallel_for_work(M, kNormRows, 4 * C, [&](int64_t r0, int64_t r1) {
        T* mu = bmean.data() + (r0 / kNormRows) * C;
        T* m2 = bm2.data() + (r0 / kNormRows) * C;
        std::fill_n(mu, C, T(0));
        std::fill_n(m2, C, T(0));
        for (int64_t r = r0; r < r1; ++r) {
          const T* xr = px + r * C;
#pragma omp simd
          for (int64_t i = 0; i < C; ++i) mu[i] += xr[i];
        }
        T inv = T(1) / static_cast<T>(r1 - r0);
#pragma omp simd
        for (int64_t i = 0; i < C; ++i) mu[i] *= inv;
        for (int64_t r = r0; r < r1; ++r) {
          const T* xr = px + r * C;
#pragma omp simd
          for (int64_t i = 0; i < C; ++i) m2[i] += (xr[i] - mu[i]) * (xr[i] - mu[i]);
        }
      });
      std::vector<T> v(bm2.begin(), bm2.begin() + C);
      std::copy_n(bmean.begin(), C, pm);
      for (int64_t b = 1; b < nblk; ++b) {
        T na = static_cast<T>(b * kNormRows), nb = static_cast<T>(std::min(kNormRows, M - b * kNormRows));
        T n = na + nb;
        for (int64_t i = 0; i < C; ++i) {
          T delta = bmean[b * C + i] - pm[i];
          pm[i] += delta * (nb / n);
          v[i] += bm2[b * C + i] + delta * delta * (na * nb / n);
        }
      }
      if (sync) {
        // Per-channel sums and sums of squares in double, added over the processes with the row count.
        std::vector<double> s(static_cast<size_t>(2 * C + 1));
        for (int64_t i = 0; i < C; ++i) {
          const double m = static_cast<double>(pm[i]);
          s[i] = m * static_cast<double>(M);
          s[C + i] = static_cast<double>(v[i]) + m * m * static_cast<double>(M);
        }
        s[2 * C] = static_cast<double>(M);
        (*sync)(s.data(), 2 * C + 1);
        count_all = static_cast<int64_t>(std::llround(s[2 * C]));
        const double n = s[2 * C];
        for (int64_t i = 0; i < C; ++i) {
          const double mean_all = s[i] / n;
          pm[i] = static_cast<T>(mean_all);
          v[i] = static_cast<T>(std::max(0.0, s[C + i] - s[i] * mean_all));
        }
      }
      for (int64_t i = 0; i < C; ++i) pr[i] = T(1) / std::sqrt(v[i] / static_cast<T>(count_all) + static_cast<T>(eps));
      if (running_mean.defined()) {
        T* rm = ptr<T>(running_mean);
        T mom = static_cast<T>(momentum);
        for (int64_t i = 0; i < C; ++i) rm[i] = (T(1) - mom) * rm[i] + mom * pm[i];
      }
      if (running_var.defined()) {
        T* rv = ptr<T>(running_var);
        T mom = static_cast<T>(momentum);
        for (int64_t i = 0; i < C; ++i)
          rv[i] = (T(1) - mom) * rv[i] + mom * v[i] / static_cast<T>(count_all - 1);
      }
    } else {
      const T* rm = ptr<T>(running_mean);
      const T* rv = ptr<T>(running_var);
      for (int64_t i = 0; i < C; ++i) {
        pm[i] = rm[i];
        pr[i] = T(1) / std::sqrt(rv[i] + static_cast<T>(eps));
      }
    }
    // y = x * scale + shift with per-channel scale = rstd*w, shift = b - mean*scale.
    std::vector<T> scale(C), shift(C);
    const T* pw = weight.defined() ? ptr<T>(weight) : nullptr;
    const T* pb = bias.defined() ? ptr<T>(bias) : nullptr;
    for (int64_t i = 0; i < C; ++i) {
      scale[i] = pr[i] * (pw ? pw[i] : T(1));
      shift[i] = (pb ? pb[i] : T(0)) - pm[i] * scale[i];
    }
    T* py = ptr<T>(out);
    parallel_for_work(M, kNormRows, 4 * C, [&](int64_t r0, int64_t r1) {
      for (int64_t r = r0; r < r1; ++r) {
        const T* xr = px + r * C;
        T* yr = py + r * C;
#pragma omp simd
        for (int64_t i = 0; i < C; ++i) yr[i] = xr[i] * scale[i] + shift[i];
      }
    });
    return 0;
  });
  if (needs_grad({&x, &weight, &bias})) {
    bool gx = x.requires_grad(), gw = weight.defined() && weight.requires_grad(),
         gb = bias.defined() && bias.requires_grad();
    Tensor wd = weight.defined() ? weight.detach() : Tensor();
    record(out, "batch_norm", {x, weight, bias},
           [xd = x.detach(), wd, mean_t, rstd_t, gx, gw, gb, M, C, nblk, training, count_all,
            sync_sum = sync ? *sync : BatchNormSyncGuard::Sum()](const Tensor& g) -> std::vector<Tensor> {
             Tensor dx = gx ? Tensor::empty(xd.shape(), g.dtype()) : Tensor();
             Tensor dw = Tensor::empty({C}, g.dtype()), db = Tensor::empty({C}, g.dtype());
             dispatch_float(g.dtype(), "batch_norm backward", [&](auto tag) {
               using T = decltype(tag);
               const T* px = ptr<T>(xd);
               const T* pg = ptr<T>(g);
               const T* pm = ptr<T>(mean_t);
               const T* pr = ptr<T>(rstd_t);
               std::vector<T> part(static_cast<size_t>(nblk * 2 * C), T(0));
               parallel_for_work(M, kNormRows, 4 * C, [&](int64_t r0, int64_t r1) {
                 T* sg = part.data() + (r0 / kNormRows) * 2 * C;
                 T* sgh = sg + C;
                 for (int64_t r = r0; r < r1; ++r) {
                   const T* xr = px + r * C;
                   const T* gr = pg + r * C;
#pragma omp simd
                   for (int64_t i = 0; i < C; ++i) {
                     sg[i] += gr[i];
                     sgh[i] += gr[i] * (xr[i] - pm[i]) * pr[i];
                   }
                 }
               });
               T* sum_g = ptr<T>(db);
               T* sum_gh = ptr<T>(dw);
               for (int64_t i = 0; i < C; ++i) {
                 sum_g[i] = part[i];
                 sum_gh[i] = part[C + i];
               }
               for (int64_t b = 1; b < nblk; ++b)
                 for (int64_t i = 0; i < C; ++i) {
                   sum_g[i] += part[b * 2 * C + i];
                   sum_gh[i] += part[b * 2 * C + C + i];
                 }
               if (gx) {
                 const T* pw = wd.defined() ? ptr<T>(wd) : nullptr;
                 std::vector<T> k(C), c1(C), c2(C);
                 T invm = T(1) / static_cast<T>(count_all);
                 // Synchronised statistics depend on every process's rows: their mean terms are summed too.
                 std::vector<T> all_g(sum_g, sum_g + C), all_gh(sum_gh, sum_gh + C);
                 if (sync_sum) {
                   std::vector<double> s(static_cast<size_t>(2 * C));
                   for (int64_t i = 0; i < C; ++i) s[i] = sum_g[i], s[C + i] = sum_gh[i];
                   sync_sum(s.data(), 2 * C);
                   for (int64_t i = 0; i < C; ++i) all_g[i] = static_cast<T>(s[i]), all_gh[i] = static_cast<T>(s[C + i]);
                 }
                 for (int64_t i = 0; i < C; ++i) {
                   k[i] = pr[i] * (pw ? pw[i] : T(1));
                   // Training: the batch statistics depend on x, which adds the two mean terms.
                   c1[i] = training ? all_g[i] * invm : T(0);
                   c2[i] = training ? all_gh[i] * invm : T(0);
                 }
                 T* pd = ptr<T>(dx);
                 parallel_for_work(M, kNormRows, 4 * C, [&](int64_t r0, int64_t r1) {
                   for (int64_t r = r0; r < r1; ++r) {
                     const T* xr = px + r * C;
                     const T* gr = pg + r * C;
                     T* dr = pd + r * C;
#pragma omp simd
                     for (int64_t i = 0; i < C; ++i) {
                       T h = (xr[i] - pm[i]) * pr[i];
                       dr[i] = k[i] * (gr[i] - c1[i] - h * c2[i]);
                     }
                   }
                 });
               }
               return 0;
             });
             return {dx, gw ? dw : Tensor(), gb ? db : Tensor()};
           });
  }
  return out;
}

}  // namespace lc2wf
