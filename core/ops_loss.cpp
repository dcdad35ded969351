// Fused, numerically stable losses.
#include <cmath>

#include "core/autograd.h"
#include "core/kernels.h"
#include "core/ops.h"

namespace lc2wf {

namespace {

Tensor reduce(const Tensor& per_element, Reduction reduction) {
  switch (reduction) {
    case Reduction::None: return per_element;
    case Reduction::Sum: return sum(per_element);
    case Reduction::Mean:
      if (per_element.numel() == 0) throw_arg("loss: mean over an empty tensor");
      return mean(per_element);
  }
  return per_element;
}

}  // namespace

Tensor cross_entropy(const Tensor& logits, const Tensor& target, const Tensor& class_weight, int64_t ignore_index,
                     Reduction reduction) {
  check_float(logits, "cross_entropy", "logits");
  check_dtype(target, DType::I64, "cross_entropy", "target");
  if (logits.dim() != 2 || target.shape() != Shape{logits.size(0)})
    throw_arg("cross_entropy: expected logits (M, C) and target (M), got " + shape_str(logits.shape()) + " and " +
              shape_str(target.shape()));
  int64_t M = logits.size(0), C = logits.size(1);
  if (class_weight.defined()) {
    check_float(class_weight, "cross_entropy", "class_weight");
    check_same_dtype(logits, class_weight, "cross_entropy");
    if (class_weight.shape() != Shape{C})
      throw_arg("cross_entropy: class_weight " + shape_str(class_weight.shape()) + " does not match " +
                std::to_string(C) + " classes");
  }
  const int64_t* t = target.data<int64_t>();
  for (int64_t i = 0; i < M; ++i)
    if (t[i] != ignore_index && (t[i] < 0 || t[i] >= C))
      throw_arg("cross_entropy: target " + std::to_string(t[i]) + " at row " + std::to_string(i) +
                " is outside [0, " + std::to_string(C) + ")");
  Tensor row_w = Tensor::empty({M}, logits.dtype());    // w_t, 0 for ignored rows
  Tensor row_loss = Tensor::empty({M}, logits.dtype());  // w_t * nll
  double weight_sum = 0.0;
  dispatch_float(logits.dtype(), "cross_entropy", [&](auto tag) {
    using T = decltype(tag);
    const T* px = ptr<T>(logits);
    const T* cw = class_weight.defined() ? ptr<T>(class_weight) : nullptr;
    T* pw = ptr<T>(row_w);
    T* pl = ptr<T>(row_loss);
    parallel_for_work(M, std::max<int64_t>(1, kElemGrain / std::max<int64_t>(1, C)), 8 * C, [&](int64_t r0, int64_t r1) {
      for (int64_t r = r0; r < r1; ++r) {
        if (t[r] == ignore_index) {
          pw[r] = 0;
          pl[r] = 0;
          continue;
        }
        const T* xr = px + r * C;
        T m = xr[0];
        for (int64_t j = 1; j < C; ++j) m = std::max(m, xr[j]);
        T s = 0;
        for (int64_t j = 0; j < C; ++j) s += std::exp(xr[j] - m);
        T nll = m + std::log(s) - xr[t[r]];
        pw[r] = cw ? cw[t[r]] : T(1);
        pl[r] = pw[r] * nll;
      }
    });
    for (int64_t r = 0; r < M; ++r) weight_sum += pw[r];
    return 0;
  });
  Tensor out;
  double denom = 1.0;
  {
    NoGradGuard no_grad;
    if (reduction == Reduction::None) {
      out = row_loss;
    } else {
      out = sum(row_loss);
      if (reduction == Reduction::Mean) {
        // All rows ignored: a zero loss with zero gradients rather than 0/0.
        denom = weight_sum > 0 ? weight_sum : 1.0;
        out = div(out, denom);
      }
    }
  }
  if (needs_grad({&logits})) {
    record(out, "cross_entropy", {logits},
           [xd = logits.detach(), tgt = target.clone(), row_w, M, C, reduction, denom](const Tensor& g) -> std::vector<Tensor> {
             Tensor dx = Tensor::empty(xd.shape(), g.dtype());
             dispatch_float(g.dtype(), "cross_entropy backward", [&](auto tag) {
               using T = decltype(tag);
               const T* px = ptr<T>(xd);
               const T* pw = ptr<T>(row_w);
               const T* pg = ptr<T>(g);
               const int64_t* tt = tgt.data<int64_t>();
               T* pd = ptr<T>(dx);
               parallel_for_work(M, std::max<int64_t>(1, kElemGrain / std::max<int64_t>(1, C)), 8 * C, [&](int64_t r0, int64_t r1) {
                 for (int64_t r = r0; r < r1; ++r) {
                   T* dr = pd + r * C;
                   T coef = reduction == Reduction::None ? pg[r] * pw[r] : pg[0] * pw[r] / static_cast<T>(denom);
                   if (pw[r] == T(0) || coef == T(0)) {
                     std::fill_n(dr, C, T(0));
                     continue;
                   }
                   const T* xr = px + r * C;
                   T m = xr[0];
                   for (int64_t j = 1; j < C; ++j) m = std::max(m, xr[j]);
                   T s = 0;
                   for (int64_t j = 0; j < C; ++j) {
                     dr[j] = std::exp(xr[j] - m);
                     s += dr[j];
                   }
                   T inv = coef / s;
                   for (int64_t j = 0; j < C; ++j) dr[j] *= inv;
                   dr[tt[r]] -= coef;
                 }
               });
               return 0;
             });
             return {dx};
           });
  }
  return out;
}

Tensor bce_with_logits(const Tensor& logits, const Tensor& target, Reduction reduction) {
  check_float(logits, "bce_with_logits", "logits");
  check_float(target, "bce_with_logits", "target");
  check_same_dtype(logits, target, "bce_with_logits");
  check_same_shape(logits, target, "bce_with_logits");
  Tensor loss = Tensor::empty(logits.shape(), logits.dtype());
  dispatch_float(logits.dtype(), "bce_with_logits", [&](auto tag) {
    using T = decltype(tag);
    map2(ptr<T>(logits), ptr<T>(target), ptr<T>(loss), loss.numel(), [](T x, T y) {
      return std::max(x, T(0)) - x * y + std::log1p(std::exp(-std::abs(x)));
    });
    return 0;
  });
  if (needs_grad({&logits, &target})) {
    bool gx = logits.requires_grad(), gy = target.requires_grad();
    record(loss, "bce_with_logits", {logits, target},
           [xd = logits.detach(), yd = target.detach(), gx, gy](const Tensor& g) -> std::vector<Tensor> {
             Tensor dx = gx ? Tensor::empty(g.shape(), g.dtype()) : Tensor();
             Tensor dy = gy ? Tensor::empty(g.shape(), g.dtype()) : Tensor();
             dispatch_float(g.dtype(), "bce_with_logits backward", [&](auto tag) {
               using T = decltype(tag);
               const T* pg = ptr<T>(g);
               const T* px = ptr<T>(xd);
               const T* py = ptr<T>(yd);
               // sigmoid written for both signs so exp never overflows.
               if (gx)
                 map3(pg, px, py, ptr<T>(dx), g.numel(), [](T gv, T x, T y) {
                   T e = std::exp(-std::abs(x));
                   T s = x >= 0 ? T(1) / (T(1) + e) : e / (T(1) + e);
                   return gv * (s - y);
                 });
               if (gy) map2(pg, px, ptr<T>(dy), g.numel(), [](T gv, T x) { return -gv * x; });
               return 0;
             });
             return {dx, dy};
           });
  }
  return reduce(loss, reduction);
}

Tensor l1_loss(const Tensor& a, const Tensor& b, Reduction reduction) {
  check_float(a, "l1_loss", "a");
  check_float(b, "l1_loss", "b");
  check_same_shape(a, b, "l1_loss");
  return reduce(abs(sub(a, b)), reduction);
}

Tensor mse_loss(const Tensor& a, const Tensor& b, Reduction reduction) {
  check_float(a, "mse_loss", "a");
  check_float(b, "mse_loss", "b");
  check_same_shape(a, b, "mse_loss");
  Tensor d = sub(a, b);
  return reduce(mul(d, d), reduction);
}

}  // namespace lc2wf
