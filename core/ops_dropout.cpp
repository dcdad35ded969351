// Dropout and its fusions with the add or ReLU that follows it. This file is compiled without
// floating-point contraction (core/CMakeLists.txt): a fused x + s * scale must round like the two ops it
// replaces, or the fused ops would not be the composed ones bit for bit.
#include <string>

#include "core/autograd.h"
#include "core/kernels.h"
#include "core/ops.h"

namespace lc2wf {

namespace {

// A new tensor out[i] = then(i, src[i] * m[i] / (1 - p)), in one parallel pass over src. make_then(T{})
// returns `then` for the element type T (so it can hold typed pointers, resolved once per call).
template <class MakeThen>
Tensor masked_pass(const DropoutMask& mask, double scale, const Tensor& src, const char* op, MakeThen make_then) {
  Tensor out = Tensor::empty(src.shape(), src.dtype());
  dispatch_float(src.dtype(), op, [&](auto tag) {
    using T = decltype(tag);
    const T* s = ptr<T>(src);
    T* d = ptr<T>(out);
    const auto then = make_then(tag);
    parallel_for_work(src.numel(), kElemGrain, 4, [&](int64_t b, int64_t e) {
      mask.apply_then(s, d, b, e, static_cast<T>(scale), then);
    });
    return 0;
  });
  return out;
}

// src * m / (1 - p): dropout's forward and every dropout backward (the mask is recomputed from the rng's
// (seed, counter) instead of stored).
Tensor masked(const DropoutMask& mask, double scale, const Tensor& src, const char* op) {
  return masked_pass(mask, scale, src, op, [](auto tag) {
    return [](int64_t, decltype(tag) dropped) { return dropped; };
  });
}

DropoutMask draw_mask(Rng& rng, const Tensor& a, double p) {
  return DropoutMask(rng, rng.reserve_tensor(static_cast<uint64_t>(a.numel())), p);
}

}  // namespace

Tensor dropout(const Tensor& a, double p, bool training, Rng& rng) {
  check_float(a, "dropout", "a");
  if (!(p >= 0.0 && p <= 1.0)) throw_arg("dropout: p must be in [0, 1], got " + std::to_string(p));
  if (!training || p == 0.0) return a;
  if (p == 1.0) return mul(a, 0.0);
  const DropoutMask mask = draw_mask(rng, a, p);
  const double scale = 1.0 / (1.0 - p);
  Tensor out = masked(mask, scale, a, "dropout");
  if (needs_grad({&a})) {
    record(out, "dropout", {a}, [mask, scale](const Tensor& g) -> std::vector<Tensor> {
      return {masked(mask, scale, g, "dropout")};
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
  const DropoutMask mask = draw_mask(rng, a, p);
  const double scale = 1.0 / (1.0 - p);
  Tensor out = masked_pass(mask, scale, a, "add_dropout", [&x](auto tag) {
    using T = decltype(tag);
    return [px = ptr<T>(x)](int64_t i, T dropped) { return px[i] + dropped; };
  });
  if (needs_grad({&x, &a})) {
    const bool gx = x.requires_grad(), ga = a.requires_grad();
    record(out, "add_dropout", {x, a}, [mask, scale, gx, ga](const Tensor& g) -> std::vector<Tensor> {
      return {gx ? g : Tensor(), ga ? masked(mask, scale, g, "add_dropout") : Tensor()};
    });
  }
  return out;
}

Tensor dropout_relu(const Tensor& a, double p, bool training, Rng& rng) {
  check_float(a, "dropout_relu", "a");
  if (!training || p == 0.0 || p == 1.0) return relu(dropout(a, p, training, rng));
  if (!(p > 0.0 && p < 1.0)) throw_arg("dropout_relu: p must be in [0, 1], got " + std::to_string(p));
  const DropoutMask mask = draw_mask(rng, a, p);
  const double scale = 1.0 / (1.0 - p);
  Tensor out = masked_pass(mask, scale, a, "dropout_relu", [](auto tag) {
    using T = decltype(tag);
    return [](int64_t, T dropped) { return dropped > 0 ? dropped : T(0); };
  });
  if (needs_grad({&a})) {
    // y > 0 exactly where the mask kept a positive value: the gradient needs y, not the mask.
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
