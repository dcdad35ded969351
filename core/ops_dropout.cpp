// Dropout and its fusions with the add or ReLU that follows it. This file is compiled without
// floating-point contraction (core/CMakeLists.txt): a fused x + s * scale must round like the two ops it
// replaces, or the fused ops would not be the composed ones bit for bit.
#include <string>

#include "core/autograd.h"
#include "core/kernels.h"
#include "core/ops.h"

namespace lc2wf {

Tensor dropout(const Tensor& a, double p, bool training, Rng& rng) {
  check_float(a, "dropout", "a");
  if (!(p >= 0.0 && p <= 1.0)) throw_arg("dropout: p must be in [0, 1], got " + std::to_string(p));
  if (!training || p == 0.0) return a;
  if (p == 1.0) return mul(a, 0.0);
  DropoutMask mask(rng, rng.reserve_tensor(static_cast<uint64_t>(a.numel())), p);
  double scale = 1.0 / (1.0 - p);
  Tensor out = Tensor::empty(a.shape(), a.dtype());
  auto apply = [mask, scale](const Tensor& src, const Tensor& dst) {
    dispatch_float(src.dtype(), "dropout", [&](auto tag) {
      using T = decltype(tag);
      const T* s = ptr<T>(src);
      T* d = ptr<T>(dst);
      T sc = static_cast<T>(scale);
      parallel_for_work(src.numel(), kElemGrain, 4, [&](int64_t b, int64_t e) {
        mask.apply(s, d, b, e, sc);
      });
      return 0;
    });
  };
  apply(a, out);
  if (needs_grad({&a})) {
    // The mask is recomputed from (seed, counter) instead of stored.
    record(out, "dropout", {a}, [apply](const Tensor& g) -> std::vector<Tensor> {
      Tensor dx = Tensor::empty(g.shape(), g.dtype());
      apply(g, dx);
      return {dx};
    });
  }
  return out;
}

Tensor add_dropout(const Tensor& x, const Tensor& a, double p, bool training, Rng& rng) {
  check_float(x, "add_dropout", "x");
  check_float(a, "add_dropout", "a");
  check_same_dtype(x, a, "add_dropout");
  if (x.shape() != a.shape())
    throw_arg("add_dropout: x " + shape_str(x.shape()) + " and a " + shape_str(a.shape()) + " differ in shape");
  if (!training || p == 0.0 || p == 1.0) return add(x, dropout(a, p, training, rng));
  if (!(p > 0.0 && p < 1.0)) throw_arg("add_dropout: p must be in [0, 1], got " + std::to_string(p));
  DropoutMask mask(rng, rng.reserve_tensor(static_cast<uint64_t>(a.numel())), p);
  const double scale = 1.0 / (1.0 - p);
  Tensor out = Tensor::empty(a.shape(), a.dtype());
  dispatch_float(a.dtype(), "add_dropout", [&](auto tag) {
    using T = decltype(tag);
    const T* px = ptr<T>(x);
    parallel_for_work(a.numel(), kElemGrain, 4, [&](int64_t b, int64_t e) {
      mask.apply_then(ptr<T>(a), ptr<T>(out), b, e, static_cast<T>(scale), [px](int64_t i, T dropped) { return px[i] + dropped; });
    });
    return 0;
  });
  if (needs_grad({&x, &a})) {
    const bool gx = x.requires_grad(), ga = a.requires_grad();
    record(out, "add_dropout", {x, a}, [mask, scale, gx, ga](const Tensor& g) -> std::vector<Tensor> {
      Tensor da;
      if (ga) {
        da = Tensor::empty(g.shape(), g.dtype());
        dispatch_float(g.dtype(), "add_dropout", [&](auto tag) {
          using T = decltype(tag);
          parallel_for_work(g.numel(), kElemGrain, 4, [&](int64_t b, int64_t e) {
            mask.apply(ptr<T>(g), ptr<T>(da), b, e, static_cast<T>(scale));
          });
          return 0;
        });
      }
      return {gx ? g : Tensor(), da};
    });
  }
  return out;
}

Tensor dropout_relu(const Tensor& a, double p, bool training, Rng& rng) {
  check_float(a, "dropout_relu", "a");
  if (!training || p == 0.0 || p == 1.0) return relu(dropout(a, p, training, rng));
  if (!(p > 0.0 && p < 1.0)) throw_arg("dropout_relu: p must be in [0, 1], got " + std::to_string(p));
  DropoutMask mask(rng, rng.reserve_tensor(static_cast<uint64_t>(a.numel())), p);
  const double scale = 1.0 / (1.0 - p);
  Tensor out = Tensor::empty(a.shape(), a.dtype());
  dispatch_float(a.dtype(), "dropout_relu", [&](auto tag) {
    using T = decltype(tag);
    parallel_for_work(a.numel(), kElemGrain, 4, [&](int64_t b, int64_t e) {
      mask.apply_then(ptr<T>(a), ptr<T>(out), b, e, static_cast<T>(scale),
                      [](int64_t, T dropped) { return dropped > 0 ? dropped : T(0); });
    });
    return 0;
  });
  if (needs_grad({&a})) {
    record(out, "dropout_relu", {a}, [y = out.detach(), scale](const Tensor& g) -> std::vector<Tensor> {
      Tensor da = Tensor::empty(g.shape(), g.dtype());
      dispatch_float(g.dtype(), "dropout_relu", [&](auto tag) {
        using T = decltype(tag);
        map2(ptr<T>(g), ptr<T>(y), ptr<T>(da), g.numel(),
             [s = static_cast<T>(scale)](T gv, T yv) { return yv > 0 ? gv * s : T(0); });
        return 0;
      });
      return {da};
    });
  }
  return out;
}

}  // namespace lc2wf
