// Layout and indexing ops. They move raw element bits, so they work for every dtype; only float
// tensors carry gradients.
#include <algorithm>
#include <cstring>

#include "core/autograd.h"
#include "core/kernels.h"
#include "core/ops.h"

namespace lc2wf {

namespace {

// Copies a (outer, len_src, inner) block into (outer, len_dst, inner) at axis offset `at` (or the
// reverse when `to_src`), i.e. the concat/slice move.
void copy_axis_block(const Tensor& src, const Tensor& dst, int64_t outer, int64_t len, int64_t inner,
                     int64_t src_len, int64_t src_at, int64_t dst_len, int64_t dst_at) {
  size_t es = dtype_size(src.dtype());
  const char* s = static_cast<const char*>(src.impl()->raw());
  char* d = static_cast<char*>(dst.impl()->raw());
  size_t row = static_cast<size_t>(len * inner) * es;
  parallel_for_work(outer, std::max<int64_t>(1, kElemGrain / std::max<int64_t>(1, len * inner)), len * inner, [&](int64_t o0, int64_t o1) {
    for (int64_t o = o0; o < o1; ++o)
      std::memcpy(d + ((o * dst_len + dst_at) * inner) * es, s + ((o * src_len + src_at) * inner) * es, row);
  });
}

}  // namespace

Tensor Tensor::permute(const std::vector<int64_t>& axes) const {
  int64_t nd = dim();
  if (static_cast<int64_t>(axes.size()) != nd)
    throw_arg("permute: " + std::to_string(axes.size()) + " axes for a " + std::to_string(nd) + "-d tensor " +
              shape_str(shape()));
  std::vector<int64_t> ax(nd);
  std::vector<bool> seen(nd, false);
  for (int64_t i = 0; i < nd; ++i) {
    ax[i] = normalize_axis(axes[i], nd, "permute");
    if (seen[ax[i]]) throw_arg("permute: repeated axis in the permutation");
    seen[ax[i]] = true;
  }
  const Shape& in = shape();
  Shape out_shape(nd);
  std::vector<int64_t> in_stride(nd, 1);
  for (int64_t d = nd - 2; d >= 0; --d) in_stride[d] = in_stride[d + 1] * in[d + 1];
  for (int64_t i = 0; i < nd; ++i) out_shape[i] = in[ax[i]];
  Tensor out = Tensor::empty(out_shape, dtype());
  if (nd > 0 && numel() > 0) {
    int64_t inner = out_shape[nd - 1];
    int64_t inner_stride = in_stride[ax[nd - 1]];
    int64_t rows = numel() / inner;
    dispatch_bits(dtype(), [&](auto tag) {
      using U = decltype(tag);
      const U* src = static_cast<const U*>(impl()->raw());
      U* dst = static_cast<U*>(out.impl()->raw());
      parallel_for_work(rows, std::max<int64_t>(1, kElemGrain / inner), inner, [&](int64_t r0, int64_t r1) {
        for (int64_t r = r0; r < r1; ++r) {
          int64_t off = 0, rem = r;
          for (int64_t i = nd - 2; i >= 0; --i) {
            off += (rem % out_shape[i]) * in_stride[ax[i]];
            rem /= out_shape[i];
          }
          U* o = dst + r * inner;
          if (inner_stride == 1)
            std::memcpy(o, src + off, sizeof(U) * inner);
          else
            for (int64_t j = 0; j < inner; ++j) o[j] = src[off + j * inner_stride];
        }
      });
      return 0;
    });
  } else if (nd == 0) {
    std::memcpy(out.impl()->raw(), impl()->raw(), dtype_size(dtype()));
  }
  if (needs_grad({this})) {
    std::vector<int64_t> inverse(nd);
    for (int64_t i = 0; i < nd; ++i) inverse[ax[i]] = i;
    record(out, "permute", {*this}, [inverse](const Tensor& g) -> std::vector<Tensor> { return {g.permute(inverse)}; });
  }
  return out;
}

Tensor concat(const std::vector<Tensor>& parts, int64_t axis) {
  if (parts.empty()) throw_arg("concat: no tensors given");
  check_defined(parts[0], "concat", "parts[0]");
  int64_t nd = parts[0].dim();
  if (nd == 0) throw_arg("concat: cannot concatenate 0-d tensors");
  axis = normalize_axis(axis, nd, "concat");
  Shape out_shape = parts[0].shape();
  out_shape[axis] = 0;
  for (size_t i = 0; i < parts.size(); ++i) {
    check_defined(parts[i], "concat", "parts[i]");
    check_same_dtype(parts[0], parts[i], "concat");
    const Shape& s = parts[i].shape();
    bool ok = static_cast<int64_t>(s.size()) == nd;
    for (int64_t d = 0; ok && d < nd; ++d) ok = d == axis || s[d] == parts[0].shape()[d];
    if (!ok)
      throw_arg("concat: part " + std::to_string(i) + " has shape " + shape_str(s) + ", incompatible with " +
                shape_str(parts[0].shape()) + " along axis " + std::to_string(axis));
    out_shape[axis] += s[axis];
  }
  Tensor out = Tensor::empty(out_shape, parts[0].dtype());
  int64_t outer = prod(out_shape, 0, axis), inner = prod(out_shape, axis + 1, nd), total = out_shape[axis];
  std::vector<int64_t> offsets;
  int64_t at = 0;
  for (const Tensor& p : parts) {
    offsets.push_back(at);
    int64_t len = p.shape()[axis];
    copy_axis_block(p, out, outer, len, inner, len, 0, total, at);
    at += len;
  }
  if (needs_grad(parts)) {
    std::vector<Shape> shapes;
    std::vector<bool> wants;
    for (const Tensor& p : parts) {
      shapes.push_back(p.shape());
      wants.push_back(p.requires_grad());
    }
    record(out, "concat", parts, [shapes, wants, offsets, axis, outer, inner, total](const Tensor& g) -> std::vector<Tensor> {
      std::vector<Tensor> grads(shapes.size());
      for (size_t i = 0; i < shapes.size(); ++i) {
        if (!wants[i]) continue;
        int64_t len = shapes[i][axis];
        grads[i] = Tensor::empty(shapes[i], g.dtype());
        copy_axis_block(g, grads[i], outer, len, inner, total, offsets[i], len, 0);
      }
      return grads;
    });
  }
  return out;
}

Tensor stack(const std::vector<Tensor>& parts, int64_t axis) {
  if (parts.empty()) throw_arg("stack: no tensors given");
  check_defined(parts[0], "stack", "parts[0]");
  int64_t nd = parts[0].dim();
  axis = normalize_axis(axis, nd + 1, "stack");
  std::vector<Tensor> expanded;
  for (size_t i = 0; i < parts.size(); ++i) {
    check_defined(parts[i], "stack", "parts[i]");
    if (parts[i].shape() != parts[0].shape())
      throw_arg("stack: part " + std::to_string(i) + " has shape " + shape_str(parts[i].shape()) + ", expected " +
                shape_str(parts[0].shape()));
    Shape s = parts[i].shape();
    s.insert(s.begin() + axis, 1);
    expanded.push_back(parts[i].reshape(s));
  }
  return concat(expanded, axis);
}

Tensor slice(const Tensor& a, int64_t axis, int64_t start, int64_t end, int64_t step) {
  check_defined(a, "slice", "a");
  if (a.dim() == 0) throw_arg("slice: cannot slice a 0-d tensor");
  axis = normalize_axis(axis, a.dim(), "slice");
  if (step <= 0) throw_arg("slice: step must be positive, got " + std::to_string(step));
  int64_t n = a.shape()[axis];
  if (start < 0) start += n;
  if (end < 0) end += n;
  start = std::clamp<int64_t>(start, 0, n);
  end = std::clamp<int64_t>(end, start, n);
  int64_t len = (end - start + step - 1) / step;
  Shape out_shape = a.shape();
  out_shape[axis] = len;
  Tensor out = Tensor::empty(out_shape, a.dtype());
  int64_t outer = prod(out_shape, 0, axis), inner = prod(out_shape, axis + 1, out_shape.size());
  if (step == 1) {
    copy_axis_block(a, out, outer, len, inner, n, start, len, 0);
  } else {
    for (int64_t j = 0; j < len; ++j) copy_axis_block(a, out, outer, 1, inner, n, start + j * step, len, j);
  }
  if (needs_grad({&a})) {
    record(out, "slice", {a}, [in_shape = a.shape(), outer, inner, n, start, step, len](const Tensor& g) -> std::vector<Tensor> {
      Tensor da = Tensor::zeros(in_shape, g.dtype());
      if (step == 1) {
        copy_axis_block(g, da, outer, len, inner, len, 0, n, start);
      } else {
        for (int64_t j = 0; j < len; ++j) copy_axis_block(g, da, outer, 1, inner, len, j, n, start + j * step);
      }
      return {da};
    });
  }
  return out;
}

Tensor index_select(const Tensor& a, int64_t axis, const Tensor& index) {
  check_defined(a, "index_select", "a");
  check_dtype(index, DType::I64, "index_select", "index");
  if (index.dim() != 1) throw_arg("index_select: index must be 1-D, got " + shape_str(index.shape()));
  if (a.dim() == 0) throw_arg("index_select: cannot index a 0-d tensor");
  axis = normalize_axis(axis, a.dim(), "index_select");
  int64_t n = a.shape()[axis], k = index.numel();
  const int64_t* idx = index.data<int64_t>();
  for (int64_t j = 0; j < k; ++j)
    if (idx[j] < 0 || idx[j] >= n)
      throw_arg("index_select: index " + std::to_string(idx[j]) + " at position " + std::to_string(j) +
                " is out of range for axis " + std::to_string(axis) + " of " + shape_str(a.shape()));
  Shape out_shape = a.shape();
  out_shape[axis] = k;
  Tensor out = Tensor::empty(out_shape, a.dtype());
  int64_t outer = prod(out_shape, 0, axis), inner = prod(out_shape, axis + 1, out_shape.size());
  size_t es = dtype_size(a.dtype());
  const char* src = static_cast<const char*>(a.impl()->raw());
  char* dst = static_cast<char*>(out.impl()->raw());
  parallel_for_work(outer * k, std::max<int64_t>(1, kElemGrain / std::max<int64_t>(1, inner)), inner, [&](int64_t t0, int64_t t1) {
    for (int64_t t = t0; t < t1; ++t) {
      int64_t o = t / k, j = t % k;
      std::memcpy(dst + t * inner * es, src + ((o * n + idx[j]) * inner) * es, inner * es);
    }
  });
  if (needs_grad({&a})) {
    record(out, "index_select", {a}, [in_shape = a.shape(), ind = index.clone(), outer, inner, n, k](const Tensor& g) -> std::vector<Tensor> {
      Tensor da = Tensor::zeros(in_shape, g.dtype());
      const int64_t* ix = ind.data<int64_t>();
      dispatch_float(g.dtype(), "index_select backward", [&](auto tag) {
        using T = decltype(tag);
        const T* pg = ptr<T>(g);
        T* pd = ptr<T>(da);
        // Parallel over the outer axis only: repeated indices then add in a fixed order.
        parallel_for_work(outer, 1, k * inner, [&](int64_t o0, int64_t o1) {
          for (int64_t o = o0; o < o1; ++o)
            for (int64_t j = 0; j < k; ++j) {
              const T* gr = pg + (o * k + j) * inner;
              T* dr = pd + (o * n + ix[j]) * inner;
              for (int64_t i = 0; i < inner; ++i) dr[i] += gr[i];
            }
        });
        return 0;
      });
      return {da};
    });
  }
  return out;
}

Tensor gather(const Tensor& a, int64_t axis, const Tensor& index) {
  check_defined(a, "gather", "a");
  check_dtype(index, DType::I64, "gather", "index");
  int64_t nd = a.dim();
  if (index.dim() != nd || nd == 0)
    throw_arg("gather: index " + shape_str(index.shape()) + " must have the same number of dims as " + shape_str(a.shape()));
  axis = normalize_axis(axis, nd, "gather");
  for (int64_t d = 0; d < nd; ++d)
    if (d != axis && index.shape()[d] > a.shape()[d])
      throw_arg("gather: index " + shape_str(index.shape()) + " is larger than " + shape_str(a.shape()) +
                " outside axis " + std::to_string(axis));
  const Shape& is = index.shape();
  std::vector<int64_t> a_stride(nd, 1);
  for (int64_t d = nd - 2; d >= 0; --d) a_stride[d] = a_stride[d + 1] * a.shape()[d + 1];
  int64_t n = a.shape()[axis];
  const int64_t* idx = index.data<int64_t>();
  int64_t count = index.numel();
  // Source offset of every output element (validated once, reused by the backward).
  std::vector<int64_t> src_off(static_cast<size_t>(count));
  for (int64_t i = 0; i < count; ++i) {
    int64_t rem = i, off = 0;
    for (int64_t d = nd - 1; d >= 0; --d) {
      int64_t c = rem % is[d];
      rem /= is[d];
      if (d == axis) {
        c = idx[i];
        if (c < 0 || c >= n)
          throw_arg("gather: index " + std::to_string(c) + " at flat position " + std::to_string(i) +
                    " is out of range for axis " + std::to_string(axis) + " of " + shape_str(a.shape()));
      }
      off += c * a_stride[d];
    }
    src_off[i] = off;
  }
  Tensor out = Tensor::empty(is, a.dtype());
  dispatch_bits(a.dtype(), [&](auto tag) {
    using U = decltype(tag);
    const U* s = static_cast<const U*>(a.impl()->raw());
    U* d = static_cast<U*>(out.impl()->raw());
    for (int64_t i = 0; i < count; ++i) d[i] = s[src_off[i]];
    return 0;
  });
  if (needs_grad({&a})) {
    record(out, "gather", {a}, [in_shape = a.shape(), src_off = std::move(src_off)](const Tensor& g) -> std::vector<Tensor> {
      Tensor da = Tensor::zeros(in_shape, g.dtype());
      dispatch_float(g.dtype(), "gather backward", [&](auto tag) {
        using T = decltype(tag);
        const T* pg = ptr<T>(g);
        T* pd = ptr<T>(da);
        for (size_t i = 0; i < src_off.size(); ++i) pd[src_off[i]] += pg[i];
        return 0;
      });
      return {da};
    });
  }
  return out;
}

Tensor expand(const Tensor& a, const Shape& shape) {
  check_defined(a, "expand", "a");
  Shape target = broadcast_shapes(a.shape(), shape);
  if (target != shape) throw_arg("expand: cannot expand " + shape_str(a.shape()) + " to " + shape_str(shape));
  if (a.shape() == shape) return a;
  Tensor out = Tensor::empty(shape, a.dtype());
  if (out.numel() > 0) {
    BroadcastPlan plan = plan_broadcast(shape, a.shape(), a.shape());
    dispatch_bits(a.dtype(), [&](auto tag) {
      using U = decltype(tag);
      const U* s = static_cast<const U*>(a.impl()->raw());
      broadcast_loop(s, s, static_cast<U*>(out.impl()->raw()), plan, [](U x, U) { return x; });
      return 0;
    });
  }
  if (needs_grad({&a})) {
    record(out, "expand", {a}, [src = a.shape()](const Tensor& g) -> std::vector<Tensor> { return {sum_to(g, src)}; });
  }
  return out;
}

Tensor repeat(const Tensor& a, const std::vector<int64_t>& repeats) {
  check_defined(a, "repeat", "a");
  int64_t n = static_cast<int64_t>(repeats.size());
  if (n < a.dim())
    throw_arg("repeat: " + std::to_string(n) + " repeats for a " + std::to_string(a.dim()) + "-d tensor");
  Shape padded(n - a.dim(), 1);
  padded.insert(padded.end(), a.shape().begin(), a.shape().end());
  // Interleave (repeat, size) pairs: [1, s0, 1, s1, ...] expanded to [r0, s0, r1, s1, ...].
  Shape inter, expanded, out_shape;
  for (int64_t i = 0; i < n; ++i) {
    if (repeats[i] < 0) throw_arg("repeat: negative repeat count " + std::to_string(repeats[i]));
    inter.insert(inter.end(), {1, padded[i]});
    expanded.insert(expanded.end(), {repeats[i], padded[i]});
    out_shape.push_back(repeats[i] * padded[i]);
  }
  return expand(a.reshape(inter), expanded).reshape(out_shape);
}

}  // namespace lc2wf
