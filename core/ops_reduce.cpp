// Reductions. Every reduction splits its reduced extent into fixed blocks and combines the block
// partials in block order, so results do not depend on the thread count.
#include <algorithm>
#include <cstring>
#include <limits>

#include "core/autograd.h"
#include "core/kernels.h"
#include "core/ops.h"

namespace lc2wf {

namespace {

constexpr int64_t kRowBlockElems = 1 << 14;  // elements per (outer, block) reduction task

// out[o, i] = sum_r in[o, r, i] with in shaped (outer, R, inner).
template <class T>
void sum_kernel(const T* in, T* out, int64_t outer, int64_t R, int64_t inner) {
  if (R == 0) {
    std::fill_n(out, outer * inner, T(0));
    return;
  }
  int64_t rblock = std::max<int64_t>(1, kRowBlockElems / inner);
  int64_t nblk = (R + rblock - 1) / rblock;
  std::vector<T> partial(static_cast<size_t>(outer * nblk * inner));
  parallel_for_work(outer * nblk, 1, rblock * inner, [&](int64_t t0, int64_t t1) {
    for (int64_t t = t0; t < t1; ++t) {
      int64_t o = t / nblk, blk = t % nblk;
      int64_t r0 = blk * rblock, r1 = std::min(R, r0 + rblock);
      T* acc = partial.data() + t * inner;
      const T* base = in + o * R * inner;
      if (inner == 1) {
        // Full reductions (losses, means) accumulate in double: cheap here and far more accurate.
        double lanes[8] = {};
        int64_t r = r0;
        for (; r + 8 <= r1; r += 8)
          for (int k = 0; k < 8; ++k) lanes[k] += base[r + k];
        double s = ((lanes[0] + lanes[1]) + (lanes[2] + lanes[3])) + ((lanes[4] + lanes[5]) + (lanes[6] + lanes[7]));
        for (; r < r1; ++r) s += base[r];
        acc[0] = static_cast<T>(s);
      } else {
        std::memcpy(acc, base + r0 * inner, sizeof(T) * inner);
        for (int64_t r = r0 + 1; r < r1; ++r) {
          const T* row = base + r * inner;
          for (int64_t i = 0; i < inner; ++i) acc[i] += row[i];
        }
      }
    }
  });
  for (int64_t o = 0; o < outer; ++o) {
    T* dst = out + o * inner;
    const T* src = partial.data() + o * nblk * inner;
    std::memcpy(dst, src, sizeof(T) * inner);
    for (int64_t b = 1; b < nblk; ++b)
      for (int64_t i = 0; i < inner; ++i) dst[i] += src[b * inner + i];
  }
}

std::vector<int64_t> normalize_axes(const std::vector<int64_t>& axes, int64_t ndim, const char* op) {
  std::vector<int64_t> out;
  for (int64_t a : axes) out.push_back(normalize_axis(a, ndim, op));
  std::sort(out.begin(), out.end());
  if (std::adjacent_find(out.begin(), out.end()) != out.end()) throw_arg(std::string(op) + ": repeated axis");
  return out;
}

Shape reduced_shape(const Shape& shape, const std::vector<int64_t>& axes, bool keepdim) {
  Shape out;
  for (int64_t d = 0; d < static_cast<int64_t>(shape.size()); ++d) {
    bool reduced = std::find(axes.begin(), axes.end(), d) != axes.end();
    if (!reduced)
      out.push_back(shape[d]);
    else if (keepdim)
      out.push_back(1);
  }
  return out;
}

// Sum without autograd over sorted axes; result has keepdim shape.
Tensor sum_raw(const Tensor& a, const std::vector<int64_t>& axes) {
  Tensor cur = a;
  Shape shape = a.shape();
  // Reduce runs of adjacent axes at once, from the last run to the first.
  size_t i = axes.size();
  while (i > 0) {
    size_t j = i - 1;
    while (j > 0 && axes[j - 1] == axes[j] - 1) --j;
    int64_t first = axes[j], last = axes[i - 1];
    int64_t outer = prod(shape, 0, first);
    int64_t R = prod(shape, first, last + 1);
    int64_t inner = prod(shape, last + 1, shape.size());
    for (int64_t d = first; d <= last; ++d) shape[d] = 1;
    Tensor next = Tensor::empty(shape, a.dtype());
    dispatch_float(a.dtype(), "sum", [&](auto tag) {
      using T = decltype(tag);
      sum_kernel(ptr<T>(cur), ptr<T>(next), outer, R, inner);
      return 0;
    });
    cur = next;
    i = j;
  }
  return cur;
}

}  // namespace

Tensor sum(const Tensor& a, const std::vector<int64_t>& axes_in, bool keepdim) {
  check_float(a, "sum", "a");
  std::vector<int64_t> axes = normalize_axes(axes_in, a.dim(), "sum");
  if (axes.empty()) return a;
  Tensor out;
  {
    NoGradGuard no_grad;
    out = sum_raw(a, axes);
    if (!keepdim) out = out.reshape(reduced_shape(a.shape(), axes, false));
  }
  if (needs_grad({&a})) {
    record(out, "sum", {a}, [in_shape = a.shape(), kd = reduced_shape(a.shape(), axes, true)](const Tensor& g) -> std::vector<Tensor> {
      return {expand(g.reshape(kd), in_shape)};
    });
  }
  return out;
}

Tensor sum(const Tensor& a) {
  check_float(a, "sum", "a");
  std::vector<int64_t> axes(a.dim());
  for (int64_t d = 0; d < a.dim(); ++d) axes[d] = d;
  if (axes.empty()) return a.clone();
  return sum(a, axes, false);
}

Tensor mean(const Tensor& a, const std::vector<int64_t>& axes_in, bool keepdim) {
  check_float(a, "mean", "a");
  std::vector<int64_t> axes = normalize_axes(axes_in, a.dim(), "mean");
  int64_t count = 1;
  for (int64_t d : axes) count *= a.shape()[d];
  if (count == 0) throw_arg("mean: reducing over an empty extent of " + shape_str(a.shape()));
  return div(sum(a, axes, keepdim), static_cast<double>(count));
}

Tensor mean(const Tensor& a) {
  check_float(a, "mean", "a");
  if (a.numel() == 0) throw_arg("mean: empty tensor " + shape_str(a.shape()));
  return div(sum(a), static_cast<double>(a.numel()));
}

namespace {

Tensor extremum(const Tensor& a, const std::vector<int64_t>& axes_in, bool keepdim, bool is_max, const char* op) {
  check_float(a, op, "a");
  std::vector<int64_t> axes = normalize_axes(axes_in, a.dim(), op);
  if (axes.empty()) return a;
  int64_t nd = a.dim();
  // Move the reduced axes last so every output element reduces one contiguous row.
  std::vector<int64_t> perm;
  for (int64_t d = 0; d < nd; ++d)
    if (std::find(axes.begin(), axes.end(), d) == axes.end()) perm.push_back(d);
  for (int64_t d : axes) perm.push_back(d);
  Tensor moved;
  {
    NoGradGuard no_grad;
    moved = a.permute(perm);
  }
  int64_t R = 1;
  for (int64_t d : axes) R *= a.shape()[d];
  if (R == 0) throw_arg(std::string(op) + ": reducing over an empty extent of " + shape_str(a.shape()));
  int64_t outer = a.numel() / R;
  Shape out_shape = reduced_shape(a.shape(), axes, keepdim);
  Tensor out = Tensor::empty(out_shape, a.dtype());
  std::vector<int64_t> arg(static_cast<size_t>(outer));
  dispatch_float(a.dtype(), op, [&](auto tag) {
    using T = decltype(tag);
    const T* in = ptr<T>(moved);
    T* po = ptr<T>(out);
    parallel_for_work(outer, std::max<int64_t>(1, kElemGrain / R), R, [&](int64_t o0, int64_t o1) {
      for (int64_t o = o0; o < o1; ++o) {
        const T* row = in + o * R;
        int64_t best = 0;
        for (int64_t r = 1; r < R; ++r)
          if (is_max ? row[r] > row[best] : row[r] < row[best]) best = r;
        arg[o] = best;
        po[o] = row[best];
      }
    });
    return 0;
  });
  if (needs_grad({&a})) {
    std::vector<int64_t> inverse(nd);
    for (int64_t i = 0; i < nd; ++i) inverse[perm[i]] = i;
    record(out, op, {a}, [arg = std::move(arg), moved_shape = moved.shape(), inverse, R](const Tensor& g) -> std::vector<Tensor> {
      Tensor scattered = Tensor::zeros(moved_shape, g.dtype());
      dispatch_float(g.dtype(), "max/min backward", [&](auto tag) {
        using T = decltype(tag);
        const T* pg = ptr<T>(g);
        T* ps = ptr<T>(scattered);
        for (size_t o = 0; o < arg.size(); ++o) ps[static_cast<int64_t>(o) * R + arg[o]] = pg[o];
        return 0;
      });
      return {scattered.permute(inverse)};
    });
  }
  return out;
}

}  // namespace

Tensor max(const Tensor& a, const std::vector<int64_t>& axes, bool keepdim) {
  return extremum(a, axes, keepdim, true, "max");
}

Tensor min(const Tensor& a, const std::vector<int64_t>& axes, bool keepdim) {
  return extremum(a, axes, keepdim, false, "min");
}

}  // namespace lc2wf
