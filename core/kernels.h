// Internal helpers shared by the op files: argument checks, dtype dispatch and elementwise loops.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <vector>
#include <stdexcept>
#include <string>

#include "core/parallel.h"
#include "core/rng.h"
#include "core/tensor.h"
#include "core/tensor_impl.h"

namespace lc2wf {

// Elements per parallel chunk for streaming loops: large enough to amortise scheduling, fixed so
// chunking never depends on the thread count.
inline constexpr int64_t kElemGrain = 1 << 15;

[[noreturn]] void throw_arg(const std::string& message);

void check_defined(const Tensor& t, const char* op, const char* arg);
void check_float(const Tensor& t, const char* op, const char* arg);  // defined and F32/F64
void check_dtype(const Tensor& t, DType dtype, const char* op, const char* arg);
void check_same_dtype(const Tensor& a, const Tensor& b, const char* op);
void check_same_shape(const Tensor& a, const Tensor& b, const char* op);
int64_t normalize_axis(int64_t axis, int64_t ndim, const char* op);

// Calls f(T{}) with T = float or double according to dtype.
template <class F>
decltype(auto) dispatch_float(DType dtype, const char* op, F&& f) {
  if (dtype == DType::F32) return f(float{});
  if (dtype == DType::F64) return f(double{});
  throw_arg(std::string(op) + ": expected a float tensor (F32 or F64), got " + dtype_name(dtype));
}

// Calls f(U{}) with U an unsigned integer of the element size: layout ops move bits, not values.
template <class F>
decltype(auto) dispatch_bits(DType dtype, F&& f) {
  switch (dtype_size(dtype)) {
    case 1: return f(uint8_t{});
    case 4: return f(uint32_t{});
    default: return f(uint64_t{});
  }
}

template <class T>
T* ptr(const Tensor& t) {
  return static_cast<T*>(t.impl()->raw());
}

// out[i] = f(a[i]) over n elements, in fixed chunks.
template <class T, class F>
void map1(const T* a, T* out, int64_t n, F f) {
  parallel_for_work(n, kElemGrain, 2, [&](int64_t b, int64_t e) {
    for (int64_t i = b; i < e; ++i) out[i] = f(a[i]);
  });
}

template <class T, class F>
void map2(const T* a, const T* b, T* out, int64_t n, F f) {
  parallel_for_work(n, kElemGrain, 2, [&](int64_t s, int64_t e) {
    for (int64_t i = s; i < e; ++i) out[i] = f(a[i], b[i]);
  });
}

template <class T, class F>
void map3(const T* a, const T* b, const T* c, T* out, int64_t n, F f) {
  parallel_for_work(n, kElemGrain, 2, [&](int64_t s, int64_t e) {
    for (int64_t i = s; i < e; ++i) out[i] = f(a[i], b[i], c[i]);
  });
}

// Dropout keeps element n when its 24-bit uniform draw is >= p; threshold in units of 2^-24.
inline uint64_t dropout_threshold(double p) { return static_cast<uint64_t>(std::ceil(p * 16777216.0)); }
inline bool dropout_keep(const Rng& rng, uint64_t n, uint64_t threshold) { return (rng.bits(n) >> 40) >= threshold; }

// Product of shape[begin, end).
inline int64_t prod(const Shape& shape, size_t begin, size_t end) {
  int64_t p = 1;
  for (size_t i = begin; i < end; ++i) p *= shape[i];
  return p;
}

// Coalesced broadcast layout: dims of the output (size-1 dims dropped, runs with the same
// broadcast pattern merged) with element strides of a and b (0 where broadcast).
struct BroadcastPlan {
  std::vector<int64_t> size, sa, sb;
};

BroadcastPlan plan_broadcast(const Shape& out, const Shape& a, const Shape& b);

// out[i] = f(a[ia(i)], b[ib(i)]) over the broadcast output, rows in fixed chunks.
template <class T, class F>
void broadcast_loop(const T* a, const T* b, T* out, const BroadcastPlan& p, F f) {
  if (p.size.empty()) {
    out[0] = f(a[0], b[0]);
    return;
  }
  size_t nd = p.size.size();
  int64_t inner = p.size[nd - 1];
  int64_t ia = p.sa[nd - 1], ib = p.sb[nd - 1];
  int64_t rows = prod(p.size, 0, nd - 1);
  int64_t grain = std::max<int64_t>(1, kElemGrain / inner);
  parallel_for_work(rows, grain, inner, [&](int64_t r0, int64_t r1) {
    for (int64_t r = r0; r < r1; ++r) {
      int64_t oa = 0, ob = 0, rem = r;
      for (size_t d = nd - 1; d-- > 0;) {
        int64_t idx = rem % p.size[d];
        rem /= p.size[d];
        oa += idx * p.sa[d];
        ob += idx * p.sb[d];
      }
      const T* pa = a + oa;
      const T* pb = b + ob;
      T* po = out + r * inner;
      if (ia == 1 && ib == 1) {
        for (int64_t i = 0; i < inner; ++i) po[i] = f(pa[i], pb[i]);
      } else if (ia == 1) {
        T vb = pb[0];
        for (int64_t i = 0; i < inner; ++i) po[i] = f(pa[i], vb);
      } else if (ib == 1) {
        T va = pa[0];
        for (int64_t i = 0; i < inner; ++i) po[i] = f(va, pb[i]);
      } else {
        T v = f(pa[0], pb[0]);
        for (int64_t i = 0; i < inner; ++i) po[i] = v;
      }
    }
  });
}

}  // namespace lc2wf
