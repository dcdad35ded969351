// Internal helpers shared by the op files: argument checks, dtype dispatch and elementwise loops.
#pragma once

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <vector>
#include <stdexcept>
#include <string>
#include <type_traits>

#include "core/parallel.h"
#include "core/rng.h"
#include "core/tensor.h"
#include "core/tensor_impl.h"

#if defined(__AVX512F__) || defined(__AVX2__)
#include <immintrin.h>
#endif

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

// Counter-based dropout mask for one reserved block of draws starting at `first`: element i is kept
// when a 24-bit hash of (seed, first, i) is >= p * 2^24. The per-element hash is one 32-bit murmur
// finaliser (a bijection, so the keep rate is exact over 2^32 draws) and vectorises; the keys come
// from the full 64-bit stream. A tensor that is a slice of the batch's (Rng::reserve_tensor) reads the
// block from its offset on: every index below is the tensor's own and the offset is added here.
class DropoutMask {
 public:
  DropoutMask() = default;
  DropoutMask(const Rng& rng, Rng::TensorDraws draws, double p)
      : threshold_(static_cast<uint32_t>(std::ceil(p * 16777216.0))), offset_(draws.offset) {
    uint64_t key = rng.bits(draws.first);
    k0_ = static_cast<uint32_t>(key);
    k1_ = static_cast<uint32_t>(key >> 32);
  }
  bool keep(uint64_t i) const { return keep_block(i + offset_); }

#ifdef __AVX512F__
  // keep(first + l) for lanes l = 0..15; first must be a multiple of 16 (one 2^32 block for all lanes).
  __mmask16 keep16(uint64_t first) const {
    first += offset_;
    const __m512i lane = _mm512_setr_epi32(0, 1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12, 13, 14, 15);
    __m512i h = _mm512_add_epi32(_mm512_set1_epi32(static_cast<int>(static_cast<uint32_t>(first))), lane);
    h = _mm512_add_epi32(_mm512_xor_si512(h, _mm512_set1_epi32(static_cast<int>(k0_))),
                         _mm512_set1_epi32(static_cast<int>(high_key(first))));
    h = _mm512_xor_si512(h, _mm512_srli_epi32(h, 16));
    h = _mm512_mullo_epi32(h, _mm512_set1_epi32(static_cast<int>(0x85EBCA6Bu)));
    h = _mm512_xor_si512(h, _mm512_srli_epi32(h, 13));
    h = _mm512_mullo_epi32(h, _mm512_set1_epi32(static_cast<int>(0xC2B2AE35u)));
    h = _mm512_xor_si512(h, _mm512_srli_epi32(h, 16));
    return _mm512_cmpge_epu32_mask(_mm512_srli_epi32(h, 8), _mm512_set1_epi32(static_cast<int>(threshold_)));
  }
#endif

#if defined(__AVX2__)
  // keep(first + l) for lanes l = 0..7 as all-ones lanes; first must be a multiple of 8.
  __m256i keep8(uint64_t first) const {
    first += offset_;
    const __m256i lane = _mm256_setr_epi32(0, 1, 2, 3, 4, 5, 6, 7);
    __m256i h = _mm256_add_epi32(_mm256_set1_epi32(static_cast<int>(static_cast<uint32_t>(first))), lane);
    h = _mm256_add_epi32(_mm256_xor_si256(h, _mm256_set1_epi32(static_cast<int>(k0_))),
                         _mm256_set1_epi32(static_cast<int>(high_key(first))));
    h = _mm256_xor_si256(h, _mm256_srli_epi32(h, 16));
    h = _mm256_mullo_epi32(h, _mm256_set1_epi32(static_cast<int>(0x85EBCA6Bu)));
    h = _mm256_xor_si256(h, _mm256_srli_epi32(h, 13));
    h = _mm256_mullo_epi32(h, _mm256_set1_epi32(static_cast<int>(0xC2B2AE35u)));
    h = _mm256_xor_si256(h, _mm256_srli_epi32(h, 16));
    // Both sides are below 2^24 + 1, so the signed compare is the unsigned one.
    return _mm256_cmpgt_epi32(_mm256_srli_epi32(h, 8), _mm256_set1_epi32(static_cast<int>(threshold_) - 1));
  }
#endif

  // d[i] = s[i] * (keep(i) ? scale : 0) for i in [begin, end).
  template <class T>
  void apply(const T* __restrict s, T* __restrict d, int64_t begin, int64_t end, T scale) const {
    apply_then(s, d, begin, end, scale, [](int64_t, T dropped) { return dropped; });
  }

  // d[i] = then(i, s[i] * (keep(i) ? scale : 0)) for i in [begin, end): an elementwise step fused into the
  // same pass, so the dropped tensor is never written out.
  template <class T, class Then>
  void apply_then(const T* __restrict s, T* __restrict d, int64_t begin, int64_t end, T scale, Then then) const {
    const uint64_t at = static_cast<uint64_t>(begin) + offset_;
    const uint32_t hk = high_key(at);
    const uint32_t k0 = k0_, thr = threshold_;
    const uint32_t base = static_cast<uint32_t>(at);
    const int64_t n = end - begin;
    s += begin;
    d += begin;
    for (int64_t i = 0; i < n; ++i) {
      uint32_t h = fmix32(((base + static_cast<uint32_t>(i)) ^ k0) + hk);
      d[i] = then(begin + i, keep_or_zero(s[i] * scale, (h >> 8) >= thr));
    }
  }

 private:
  // v, or +0 when !keep, by masking its bits: a float select would be control flow that GCC does not
  // vectorise under the default -ftrapping-math (measured 3 ns per element, 4-5x the vector loop).
  template <class T>
  static T keep_or_zero(T v, bool keep) {
    using Bits = std::conditional_t<sizeof(T) == 4, uint32_t, uint64_t>;
    Bits bits;
    std::memcpy(&bits, &v, sizeof v);
    bits &= Bits{0} - static_cast<Bits>(keep);
    std::memcpy(&v, &bits, sizeof v);
    return v;
  }

  // i is an index into the whole block. high_key(i) is constant over any 2^32-aligned block, so vector
  // loops hash only the low 32 bits per lane.
  uint32_t high_key(uint64_t i) const { return k1_ + static_cast<uint32_t>(i >> 32) * 0x9E3779B9u; }
  bool keep_block(uint64_t i) const {
    uint32_t h = fmix32((static_cast<uint32_t>(i) ^ k0_) + high_key(i));
    return (h >> 8) >= threshold_;
  }
  static uint32_t fmix32(uint32_t h) {
    h ^= h >> 16;
    h *= 0x85EBCA6Bu;
    h ^= h >> 13;
    h *= 0xC2B2AE35u;
    return h ^ (h >> 16);
  }
  uint32_t threshold_ = 0, k0_ = 0, k1_ = 0;
  uint64_t offset_ = 0;
};

// exp that vectorises (Cephes-style polynomial, ~1 ulp in float); exactly 0 below the float range.
inline float fast_exp(float x) {
  float xc = std::min(std::max(x, -87.0f), 88.3f);
  // Round to nearest by the 1.5 * 2^23 trick (|x * log2 e| < 2^22 here); vectorises unlike floor().
  float n = (xc * 1.44269504088896341f + 12582912.0f) - 12582912.0f;
  float r = xc - n * 0.693359375f + n * 2.12194440e-4f;
  float p = 1.9875691500e-4f;
  p = p * r + 1.3981999507e-3f;
  p = p * r + 8.3334519073e-3f;
  p = p * r + 4.1665795894e-2f;
  p = p * r + 1.6666665459e-1f;
  p = p * r + 5.0000001201e-1f;
  float y = p * r * r + r + 1.0f;
  float scale = std::bit_cast<float>((static_cast<int32_t>(n) + 127) << 23);
  return x < -87.0f ? 0.0f : y * scale;
}
inline double fast_exp(double x) { return std::exp(x); }

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
