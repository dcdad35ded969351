// Shapes, strided head layouts and the dropout plan shared by the reference attention kernel
// (ops_attention.cpp) and the fused AVX2 one (attention_fused.cpp).
#pragma once

#include <cstdint>

#include "core/kernels.h"

namespace lc2wf::attention {

// Where the rows of one head live: element (b, h, i, d) is at b*batch + h*head + i*row + d.
struct Layout {
  int64_t batch, head, row;
  int64_t at(int64_t b, int64_t h) const { return b * batch + h * head; }
};

struct Shape4 {
  int64_t B, H, Lq, Lk, D;
};

struct DropoutPlan {
  DropoutMask mask;
  double scale = 1.0;
  bool active = false;
};

// (batch item, head) pairs per parallel chunk: fixed, so results never depend on the thread count.
constexpr int64_t kPairsPerTask = 4;

// A prefetch the compiler keeps: GCC's vectoriser deletes __builtin_prefetch (and _mm_prefetch) from the
// loops it vectorises, which left the loops below without a single prefetch instruction.
inline void prefetch_line(const void* p) { asm volatile("prefetcht0 %0" : : "m"(*static_cast<const char*>(p))); }

// Software prefetch of one head's rows: the rows sit a packed-row stride apart, which the hardware
// prefetchers pick up too late, so the next pair's operands are requested while this pair computes.
template <class T>
inline void prefetch_rows(const T* base, int64_t rows, int64_t row_stride, int64_t cols) {
  for (int64_t r = 0; r < rows; ++r)
    for (int64_t c = 0; c < cols; c += 64 / static_cast<int64_t>(sizeof(T))) prefetch_line(base + r * row_stride + c);
}

// Prefetches q, k, v (and, in backward, the output gradient) of pair p + 1, if there is one.
template <class T>
inline void prefetch_next_pair(const Shape4& s, int64_t p, const T* q, Layout lq, const T* k, Layout lk, const T* v,
                               Layout lv, const T* go = nullptr, Layout lo = {}) {
  if (p + 1 >= s.B * s.H) return;
  const int64_t nb = (p + 1) / s.H, nh = (p + 1) % s.H;
  prefetch_rows(q + lq.at(nb, nh), s.Lq, lq.row, s.D);
  prefetch_rows(k + lk.at(nb, nh), s.Lk, lk.row, s.D);
  prefetch_rows(v + lv.at(nb, nh), s.Lk, lv.row, s.D);
  if (go) prefetch_rows(go + lo.at(nb, nh), s.Lq, lo.row, s.D);
}

// The rows of pair p + 1, prefetched a share per query row of pair p (share(i)): issued in one burst, the
// prefetches fill the L1 miss buffers and the burst stalls the core (measured no faster than none).
template <class T>
class NextPairRows {
 public:
  NextPairRows(const Shape4& s, int64_t p, const T* q, Layout lq, const T* k, Layout lk, const T* v, Layout lv,
               const T* go = nullptr, Layout lo = {})
      : s_(s), lq_(lq), lk_(lk), lv_(lv), lo_(lo) {
    if (p + 1 >= s.B * s.H) return;
    const int64_t nb = (p + 1) / s.H, nh = (p + 1) % s.H;
    q_ = q + lq.at(nb, nh), k_ = k + lk.at(nb, nh), v_ = v + lv.at(nb, nh);
    if (go) go_ = go + lo.at(nb, nh);
  }
  // Row i of q (and go) and the matching slice of the k and v rows.
  void share(int64_t i) const {
    if (!q_) return;
    prefetch_rows(q_ + i * lq_.row, 1, 0, s_.D);
    if (go_) prefetch_rows(go_ + i * lo_.row, 1, 0, s_.D);
    const int64_t k0 = s_.Lk == s_.Lq ? i : i * s_.Lk / s_.Lq, k1 = s_.Lk == s_.Lq ? i + 1 : (i + 1) * s_.Lk / s_.Lq;
    prefetch_rows(k_ + k0 * lk_.row, k1 - k0, lk_.row, s_.D);
    prefetch_rows(v_ + k0 * lv_.row, k1 - k0, lv_.row, s_.D);
  }

 private:
  const Shape4& s_;
  Layout lq_, lk_, lv_, lo_;
  const T *q_ = nullptr, *k_ = nullptr, *v_ = nullptr, *go_ = nullptr;
};

}  // namespace lc2wf::attention
