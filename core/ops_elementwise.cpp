// Elementwise ops with NumPy broadcasting; every broadcasting backward goes through sum_to.
#include <cmath>

#include "core/autograd.h"
#include "core/kernels.h"
#include "core/ops.h"

namespace lc2wf {

Shape broadcast_shapes(const Shape& a, const Shape& b) {
  size_t nd = std::max(a.size(), b.size());
  Shape out(nd);
  for (size_t i = 0; i < nd; ++i) {
    int64_t da = i < nd - a.size() ? 1 : a[i - (nd - a.size())];
    int64_t db = i < nd - b.size() ? 1 : b[i - (nd - b.size())];
    if (da != db && da != 1 && db != 1)
      throw_arg("cannot broadcast shapes " + shape_str(a) + " and " + shape_str(b));
    out[i] = da == 1 ? db : da;
  }
  return out;
}

Tensor sum_to(const Tensor& grad, const Shape& shape) {
  if (grad.shape() == shape) return grad;
  const Shape& g = grad.shape();
  if (shape.size() > g.size()) throw_arg("sum_to: cannot reduce " + shape_str(g) + " to " + shape_str(shape));
  size_t lead = g.size() - shape.size();
  std::vector<int64_t> axes;
  for (size_t i = 0; i < g.size(); ++i) {
    int64_t target = i < lead ? 1 : shape[i - lead];
    if (target == g[i]) {
      if (i < lead) axes.push_back(static_cast<int64_t>(i));  // size-1 leading axes vanish in the reshape
      continue;
    }
    if (target != 1) throw_arg("sum_to: cannot reduce " + shape_str(g) + " to " + shape_str(shape));
    axes.push_back(static_cast<int64_t>(i));
  }
  return sum(grad, axes, true).reshape(shape);
}

namespace {

template <class F>
Tensor binary_forward(const Tensor& a, const Tensor& b, const char* op, F f) {
  check_float(a, op, "a");
  check_float(b, op, "b");
  check_same_dtype(a, b, op);
  Shape shape = broadcast_shapes(a.shape(), b.shape());
  Tensor out = Tensor::empty(shape, a.dtype());
  dispatch_float(a.dtype(), op, [&](auto tag) {
    using T = decltype(tag);
    const T* pa = ptr<T>(a);
    const T* pb = ptr<T>(b);
    T* po = ptr<T>(out);
    if (a.shape() == b.shape())
      map2(pa, pb, po, out.numel(), f);
    else
      broadcast_loop(pa, pb, po, plan_broadcast(shape, a.shape(), b.shape()), f);
    return 0;
  });
  return out;
}

// Unary op whose backward needs the input x and/or the output y: dx = bwd(g, x, y).
enum Saves { kX = 1, kY = 2 };

template <class Fwd, class Bwd>
Tensor unary_op(const Tensor& a, const char* name, int saves, Fwd fwd, Bwd bwd) {
  check_float(a, name, "a");
  Tensor out = Tensor::empty(a.shape(), a.dtype());
  dispatch_float(a.dtype(), name, [&](auto tag) {
    using T = decltype(tag);
    map1(ptr<T>(a), ptr<T>(out), a.numel(), [&](T x) { return fwd(x); });
    return 0;
  });
  if (needs_grad({&a})) {
    Tensor x = (saves & kX) ? a.detach() : Tensor();
    Tensor y = (saves & kY) ? out.detach() : Tensor();
    record(out, name, {a}, [x, y, name, bwd](const Tensor& g) -> std::vector<Tensor> {
      Tensor dx = Tensor::empty(g.shape(), g.dtype());
      dispatch_float(g.dtype(), name, [&](auto tag) {
        using T = decltype(tag);
        const T* pg = ptr<T>(g);
        const T* px = x.defined() ? ptr<T>(x) : pg;
        const T* py = y.defined() ? ptr<T>(y) : pg;
        map3(pg, px, py, ptr<T>(dx), g.numel(), [&](T gv, T xv, T yv) { return bwd(gv, xv, yv); });
        return 0;
      });
      return {dx};
    });
  }
  return out;
}

}  // namespace

Tensor add(const Tensor& a, const Tensor& b) {
  Tensor out = binary_forward(a, b, "add", [](auto x, auto y) { return x + y; });
  if (needs_grad({&a, &b})) {
    record(out, "add", {a, b}, [sa = a.shape(), sb = b.shape()](const Tensor& g) -> std::vector<Tensor> {
      return {sum_to(g, sa), sum_to(g, sb)};
    });
  }
  return out;
}

Tensor sub(const Tensor& a, const Tensor& b) {
  Tensor out = binary_forward(a, b, "sub", [](auto x, auto y) { return x - y; });
  if (needs_grad({&a, &b})) {
    bool gb = b.requires_grad();
    record(out, "sub", {a, b}, [sa = a.shape(), sb = b.shape(), gb](const Tensor& g) -> std::vector<Tensor> {
      return {sum_to(g, sa), gb ? sum_to(neg(g), sb) : Tensor()};
    });
  }
  return out;
}

Tensor mul(const Tensor& a, const Tensor& b) {
  Tensor out = binary_forward(a, b, "mul", [](auto x, auto y) { return x * y; });
  if (needs_grad({&a, &b})) {
    bool ga = a.requires_grad(), gb = b.requires_grad();
    Tensor ad = gb ? a.detach() : Tensor();
    Tensor bd = ga ? b.detach() : Tensor();
    record(out, "mul", {a, b}, [ad, bd, ga, gb, sa = a.shape(), sb = b.shape()](const Tensor& g) -> std::vector<Tensor> {
      return {ga ? sum_to(mul(g, bd), sa) : Tensor(), gb ? sum_to(mul(g, ad), sb) : Tensor()};
    });
  }
  return out;
}

Tensor div(const Tensor& a, const Tensor& b) {
  Tensor out = binary_forward(a, b, "div", [](auto x, auto y) { return x / y; });
  if (needs_grad({&a, &b})) {
    bool ga = a.requires_grad(), gb = b.requires_grad();
    Tensor bd = b.detach();
    Tensor yd = gb ? out.detach() : Tensor();
    record(out, "div", {a, b}, [bd, yd, ga, gb, sa = a.shape(), sb = b.shape()](const Tensor& g) -> std::vector<Tensor> {
      Tensor ga_t = ga ? sum_to(div(g, bd), sa) : Tensor();
      // d(a/b)/db = -(a/b)/b
      Tensor gb_t = gb ? sum_to(neg(div(mul(g, yd), bd)), sb) : Tensor();
      return {ga_t, gb_t};
    });
  }
  return out;
}

Tensor add(const Tensor& a, double s) {
  return unary_op(a, "add_scalar", 0, [s](auto x) { return x + static_cast<decltype(x)>(s); },
                  [](auto g, auto, auto) { return g; });
}

Tensor sub(const Tensor& a, double s) {
  return unary_op(a, "sub_scalar", 0, [s](auto x) { return x - static_cast<decltype(x)>(s); },
                  [](auto g, auto, auto) { return g; });
}

Tensor rsub(double s, const Tensor& a) {
  return unary_op(a, "rsub_scalar", 0, [s](auto x) { return static_cast<decltype(x)>(s) - x; },
                  [](auto g, auto, auto) { return -g; });
}

Tensor mul(const Tensor& a, double s) {
  return unary_op(a, "mul_scalar", 0, [s](auto x) { return x * static_cast<decltype(x)>(s); },
                  [s](auto g, auto, auto) { return g * static_cast<decltype(g)>(s); });
}

Tensor div(const Tensor& a, double s) {
  return unary_op(a, "div_scalar", 0, [s](auto x) { return x / static_cast<decltype(x)>(s); },
                  [s](auto g, auto, auto) { return g / static_cast<decltype(g)>(s); });
}

Tensor rdiv(double s, const Tensor& a) {
  return unary_op(a, "rdiv_scalar", kX | kY, [s](auto x) { return static_cast<decltype(x)>(s) / x; },
                  [](auto g, auto x, auto y) { return -g * y / x; });
}

Tensor neg(const Tensor& a) {
  return unary_op(a, "neg", 0, [](auto x) { return -x; }, [](auto g, auto, auto) { return -g; });
}

Tensor exp(const Tensor& a) {
  return unary_op(a, "exp", kY, [](auto x) { return std::exp(x); }, [](auto g, auto, auto y) { return g * y; });
}

Tensor log(const Tensor& a) {
  return unary_op(a, "log", kX, [](auto x) { return std::log(x); }, [](auto g, auto x, auto) { return g / x; });
}

Tensor sqrt(const Tensor& a) {
  return unary_op(a, "sqrt", kY, [](auto x) { return std::sqrt(x); },
                  [](auto g, auto, auto y) { return g / (y + y); });
}

Tensor pow(const Tensor& a, double p) {
  return unary_op(a, "pow", kX, [p](auto x) { return static_cast<decltype(x)>(std::pow(x, static_cast<decltype(x)>(p))); },
                  [p](auto g, auto x, auto) {
                    using T = decltype(g);
                    return g * static_cast<T>(p) * static_cast<T>(std::pow(x, static_cast<T>(p - 1)));
                  });
}

Tensor relu(const Tensor& a) {
  return unary_op(a, "relu", kY, [](auto x) { return x > 0 ? x : decltype(x)(0); },
                  [](auto g, auto, auto y) { return y > 0 ? g : decltype(g)(0); });
}

Tensor sigmoid(const Tensor& a) {
  return unary_op(a, "sigmoid", kY,
                  [](auto x) {
                    using T = decltype(x);
                    return T(1) / (T(1) + std::exp(-x));
                  },
                  [](auto g, auto, auto y) { return g * y * (decltype(g)(1) - y); });
}

Tensor tanh(const Tensor& a) {
  return unary_op(a, "tanh", kY, [](auto x) { return std::tanh(x); },
                  [](auto g, auto, auto y) { return g * (decltype(g)(1) - y * y); });
}

Tensor abs(const Tensor& a) {
  return unary_op(a, "abs", kX, [](auto x) { return std::abs(x); },
                  [](auto g, auto x, auto) {
                    using T = decltype(g);
                    return x > 0 ? g : (x < 0 ? -g : T(0));
                  });
}

}  // namespace lc2wf
