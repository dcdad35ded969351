// Boolean-mask ops (attention key padding, invalid-line masking).
#include "core/autograd.h"
#include "core/kernels.h"
#include "core/ops.h"

namespace lc2wf {

namespace {

// Zeroes g where mask (same shape) is `zero_where`.
Tensor mask_grad(const Tensor& g, const Tensor& mask, bool zero_where) {
  Tensor out = Tensor::empty(g.shape(), g.dtype());
  const uint8_t* m = mask.data<uint8_t>();
  dispatch_float(g.dtype(), "mask backward", [&](auto tag) {
    using T = decltype(tag);
    const T* pg = ptr<T>(g);
    T* po = ptr<T>(out);
    parallel_for_work(g.numel(), kElemGrain, 1, [&](int64_t b, int64_t e) {
      for (int64_t i = b; i < e; ++i) po[i] = (m[i] != 0) == zero_where ? T(0) : pg[i];
    });
    return 0;
  });
  return out;
}

}  // namespace

Tensor masked_fill(const Tensor& a, const Tensor& mask, double value) {
  check_float(a, "masked_fill", "a");
  check_dtype(mask, DType::Bool, "masked_fill", "mask");
  if (broadcast_shapes(a.shape(), mask.shape()) != a.shape())
    throw_arg("masked_fill: mask " + shape_str(mask.shape()) + " does not broadcast to " + shape_str(a.shape()));
  Tensor m = expand(mask, a.shape());
  Tensor out = Tensor::empty(a.shape(), a.dtype());
  const uint8_t* pm = m.data<uint8_t>();
  dispatch_float(a.dtype(), "masked_fill", [&](auto tag) {
    using T = decltype(tag);
    const T* pa = ptr<T>(a);
    T* po = ptr<T>(out);
    T v = static_cast<T>(value);
    parallel_for_work(a.numel(), kElemGrain, 1, [&](int64_t b, int64_t e) {
      for (int64_t i = b; i < e; ++i) po[i] = pm[i] ? v : pa[i];
    });
    return 0;
  });
  if (needs_grad({&a})) {
    record(out, "masked_fill", {a}, [m](const Tensor& g) -> std::vector<Tensor> { return {mask_grad(g, m, true)}; });
  }
  return out;
}

Tensor where(const Tensor& mask, const Tensor& a, const Tensor& b) {
  check_dtype(mask, DType::Bool, "where", "mask");
  check_float(a, "where", "a");
  check_float(b, "where", "b");
  check_same_dtype(a, b, "where");
  Shape shape = broadcast_shapes(mask.shape(), broadcast_shapes(a.shape(), b.shape()));
  Tensor m = expand(mask, shape);
  Tensor ae = expand(a, shape), be = expand(b, shape);  // differentiable: their backward sums back
  Tensor out = Tensor::empty(shape, a.dtype());
  const uint8_t* pm = m.data<uint8_t>();
  dispatch_float(a.dtype(), "where", [&](auto tag) {
    using T = decltype(tag);
    const T* pa = ptr<T>(ae);
    const T* pb = ptr<T>(be);
    T* po = ptr<T>(out);
    parallel_for_work(out.numel(), kElemGrain, 1, [&](int64_t s, int64_t e) {
      for (int64_t i = s; i < e; ++i) po[i] = pm[i] ? pa[i] : pb[i];
    });
    return 0;
  });
  if (needs_grad({&ae, &be})) {
    bool ga = ae.requires_grad(), gb = be.requires_grad();
    record(out, "where", {ae, be}, [m, ga, gb](const Tensor& g) -> std::vector<Tensor> {
      return {ga ? mask_grad(g, m, false) : Tensor(), gb ? mask_grad(g, m, true) : Tensor()};
    });
  }
  return out;
}

}  // namespace lc2wf
