// Fused float attention, forward and backward side by side. Per (batch item, head): S = Q K^T, key
// mask, softmax, dropout and P~ V in one pass over cache-resident blocks; the backward pass recomputes
// S with the same product, rebuilds P from the saved row statistics (bit-identical to the forward
// pass, no max or sum reductions) and the dropout mask from the saved keep bits (no hash), then runs
// the four gradient products. Probabilities are never stored.
#include "core/attention_fused.h"

#include <algorithm>
#include <limits>
#include <vector>

#include "core/head_gemm.h"
#include "core/parallel.h"
#include "core/simd256.h"
#include "core/simd512.h"
#include "core/small_gemm.h"

namespace lc2wf::attention {

#ifdef LC2WF_SIMD256

namespace {

// Key-mask lanes of one batch item: all ones for a key that takes part, zero for a padded one.
void key_lanes(const uint8_t* mrow, int64_t Lk, std::vector<int32_t>& lanes) {
  lanes.resize(static_cast<size_t>(Lk));
  for (int64_t j = 0; j < Lk; ++j) lanes[static_cast<size_t>(j)] = mrow[j] ? 0 : -1;
}

// One head's rows copied out of a strided layout into a contiguous block that stays in L1. In the packed
// (B, L, 3E) layout the rows of q, k and v sit 3 KiB apart and fall into a few L1 sets, so products
// rereading them in place would miss.
void copy_head(int64_t rows, int64_t cols, const float* src, int64_t lds, float* dst) {
  for (int64_t r = 0; r < rows; ++r)
    for (int64_t c = 0; c < cols; c += 8) _mm256_storeu_ps(dst + r * cols + c, _mm256_loadu_ps(src + r * lds + c));
}

// Per-thread scratch reused across calls, so no call allocates (at L = 512 one head's blocks take 3.5 MB).
float* thread_scratch(size_t floats) {
  thread_local std::vector<float> buffer;
  if (buffer.size() < floats) buffer.resize(floats);
  return buffer.data();
}

// The softmax rows are written once over a lane width: 8 lanes (AVX2) for any key count that is a multiple
// of 8, 16 lanes (AVX-512) where the CPU has them and the key count is a multiple of 16, which halves the
// instructions of the exp, the reductions and the dropout hash. Keep bits are one bit per key either way.
struct Lanes8 {
  static constexpr int64_t kN = 8;
  using V = __m256;
  using M = __m256;  // all-ones lanes
  static V load(const float* p) { return _mm256_loadu_ps(p); }
  static void store(float* p, V x) { _mm256_storeu_ps(p, x); }
  static V set1(float x) { return _mm256_set1_ps(x); }
  static V add(V a, V b) { return _mm256_add_ps(a, b); }
  static V sub(V a, V b) { return _mm256_sub_ps(a, b); }
  static V mul(V a, V b) { return _mm256_mul_ps(a, b); }
  static V fmadd(V a, V b, V c) { return _mm256_fmadd_ps(a, b, c); }
  static V fmsub(V a, V b, V c) { return _mm256_fmsub_ps(a, b, c); }
  static V max(V a, V b) { return _mm256_max_ps(a, b); }
  static V exp_nonpositive(V x) { return exp8_nonpositive(x); }
  static float hmax(V x) { return hmax8(x); }
  static float hsum(V x) { return hsum8(x); }
  static V zero_unless(M m, V x) { return _mm256_and_ps(x, m); }
  static V select(M m, V x, V otherwise) { return _mm256_blendv_ps(otherwise, x, m); }
  static M key_mask(const int32_t* valid, int64_t v) {
    return _mm256_castsi256_ps(_mm256_loadu_si256(reinterpret_cast<const __m256i*>(valid + kN * v)));
  }
  static M keep(const DropoutMask& mask, uint64_t first) { return _mm256_castsi256_ps(mask.keep8(first)); }
  static void store_bits(uint8_t* bits, int64_t v, M m) { bits[v] = static_cast<uint8_t>(_mm256_movemask_ps(m)); }
  static M load_bits(const uint8_t* bits, int64_t v) { return bits_to_mask8(bits[v]); }
};

#ifdef __AVX512F__
struct Lanes16 {
  static constexpr int64_t kN = 16;
  using V = __m512;
  using M = __mmask16;
  static V load(const float* p) { return _mm512_loadu_ps(p); }
  static void store(float* p, V x) { _mm512_storeu_ps(p, x); }
  static V set1(float x) { return _mm512_set1_ps(x); }
  static V add(V a, V b) { return _mm512_add_ps(a, b); }
  static V sub(V a, V b) { return _mm512_sub_ps(a, b); }
  static V mul(V a, V b) { return _mm512_mul_ps(a, b); }
  static V fmadd(V a, V b, V c) { return _mm512_fmadd_ps(a, b, c); }
  static V fmsub(V a, V b, V c) { return _mm512_fmsub_ps(a, b, c); }
  static V max(V a, V b) { return _mm512_max_ps(a, b); }
  static V exp_nonpositive(V x) { return exp16(x); }
  static float hmax(V x) { return _mm512_reduce_max_ps(x); }
  static float hsum(V x) { return _mm512_reduce_add_ps(x); }
  static V zero_unless(M m, V x) { return _mm512_maskz_mov_ps(m, x); }
  static V select(M m, V x, V otherwise) { return _mm512_mask_mov_ps(otherwise, m, x); }
  static M key_mask(const int32_t* valid, int64_t v) {
    const __m512i lanes = _mm512_loadu_si512(valid + kN * v);
    return _mm512_test_epi32_mask(lanes, lanes);
  }
  static M keep(const DropoutMask& mask, uint64_t first) { return mask.keep16(first); }
  // Two bytes, low keys first: the layout of two 8-lane chunks.
  static void store_bits(uint8_t* bits, int64_t v, M m) {
    bits[2 * v] = static_cast<uint8_t>(m), bits[2 * v + 1] = static_cast<uint8_t>(m >> 8);
  }
  static M load_bits(const uint8_t* bits, int64_t v) {
    return static_cast<M>(bits[2 * v] | (static_cast<unsigned>(bits[2 * v + 1]) << 8));
  }
};
#endif

// exp(s * scale - m) of one chunk of keys, masked keys zero: the forward pass and the backward
// recomputation both go through here, so P = e * inv has the same bits in both.
template <class T>
inline typename T::V shifted_exp(typename T::V s, typename T::V scale, typename T::V m, const int32_t* valid,
                                 int64_t v) {
  const typename T::V e = T::exp_nonpositive(T::fmsub(s, scale, m));
  return valid ? T::zero_unless(T::key_mask(valid, v), e) : e;
}

// Query rows whose softmax runs interleaved: one row alone is a chain of dependent reductions (max, exp,
// sum, reciprocal) that leaves most of the core idle; independent rows fill it.
constexpr int kRowGroup = 4;

// Softmax and dropout of R consecutive score rows of n keys (nc chunks of T::kN) in place: s holds raw
// scores on entry and the dropped-out probabilities on exit; p (optional) gets the probabilities. A row
// whose keys are all masked is zero. Element j of query row `first / n` has dropout index first + j. Each
// row's arithmetic is that of R = 1, so the grouping does not change a bit.
template <class T, int R>
void forward_rows(float* s, float* p, int64_t n, float scale, const int32_t* valid, const DropoutPlan& drop,
                  uint64_t first, float* stat, uint8_t* bits) {
  using V = typename T::V;
  const int64_t nc = n / T::kN, row_bytes = n / 8;
  const V neg_inf = T::set1(-std::numeric_limits<float>::infinity());
  V mx[R], sum[R], vm[R], vinv[R];
#pragma GCC unroll 8
  for (int r = 0; r < R; ++r) mx[r] = neg_inf, sum[r] = T::set1(0.0f);
  for (int64_t v = 0; v < nc; ++v)
#pragma GCC unroll 8
    for (int r = 0; r < R; ++r) {
      const V x = T::load(s + r * n + T::kN * v);
      mx[r] = T::max(mx[r], valid ? T::select(T::key_mask(valid, v), x, neg_inf) : x);
    }
  float m[R];
#pragma GCC unroll 8
  for (int r = 0; r < R; ++r) {
    const float top = T::hmax(mx[r]);
    if (top == -std::numeric_limits<float>::infinity()) {
      if constexpr (R > 1) {
        // Rare (every key masked): each row on its own path.
        for (int q = 0; q < R; ++q)
          forward_rows<T, 1>(s + q * n, p ? p + q * n : nullptr, n, scale, valid, drop, first + q * n,
                             stat ? stat + 2 * q : nullptr, bits ? bits + q * row_bytes : nullptr);
        return;
      }
      for (int64_t j = 0; j < n; ++j) s[j] = 0.0f;
      if (p)
        for (int64_t j = 0; j < n; ++j) p[j] = 0.0f;
      if (stat) stat[0] = stat[1] = 0.0f;
      if (bits)
        for (int64_t v = 0; v < row_bytes; ++v) bits[v] = 0;
      return;
    }
    // Rounding is monotonic, so max(s) * scale is the maximum of the scaled scores.
    m[r] = top * scale;
    vm[r] = T::set1(m[r]);
  }
  const V vscale = T::set1(scale);
  for (int64_t v = 0; v < nc; ++v)
#pragma GCC unroll 8
    for (int r = 0; r < R; ++r) {
      const V e = shifted_exp<T>(T::load(s + r * n + T::kN * v), vscale, vm[r], valid, v);
      T::store(s + r * n + T::kN * v, e);
      sum[r] = T::add(sum[r], e);
    }
  float inv[R];
#pragma GCC unroll 8
  for (int r = 0; r < R; ++r) inv[r] = 1.0f / T::hsum(sum[r]), vinv[r] = T::set1(inv[r]);
  const V keep_scale = T::set1(static_cast<float>(drop.scale));
  for (int64_t v = 0; v < nc; ++v)
#pragma GCC unroll 8
    for (int r = 0; r < R; ++r) {
      float* row = s + r * n;
      V pv = T::mul(T::load(row + T::kN * v), vinv[r]);
      if (p) T::store(p + r * n + T::kN * v, pv);
      if (drop.active) {
        const typename T::M keep = T::keep(drop.mask, first + r * n + T::kN * static_cast<uint64_t>(v));
        if (bits) T::store_bits(bits + r * row_bytes, v, keep);
        pv = T::zero_unless(keep, T::mul(pv, keep_scale));
      }
      T::store(row + T::kN * v, pv);
    }
  if (stat)
#pragma GCC unroll 8
    for (int r = 0; r < R; ++r) stat[2 * r] = m[r], stat[2 * r + 1] = inv[r];
}

// R consecutive rows of the backward pass (n keys). s holds raw scores, dp the gradient of the
// dropped-out probabilities; on exit pd holds the dropped-out probabilities and dp the score gradient
// dS = P * (dP - sum(P * dP)) * scale with dP = dP~ * keep * keep_scale (sum(P dP) = sum(P~ dP~)).
// Interleaved like forward_rows, each row's arithmetic that of R = 1.
template <class T, int R>
void backward_rows(float* s, float* dp, float* pd, int64_t n, float scale, const int32_t* valid,
                   const DropoutPlan& drop, const float* stat, const uint8_t* bits) {
  using V = typename T::V;
  const int64_t nc = n / T::kN, row_bytes = n / 8;
  const V vscale = T::set1(scale), keep_scale = T::set1(static_cast<float>(drop.scale));
  V vm[R], vinv[R], dot[R];
#pragma GCC unroll 8
  for (int r = 0; r < R; ++r) vm[r] = T::set1(stat[2 * r]), vinv[r] = T::set1(stat[2 * r + 1]), dot[r] = T::set1(0.0f);
  for (int64_t v = 0; v < nc; ++v)
#pragma GCC unroll 8
    for (int r = 0; r < R; ++r) {
      const int64_t at = r * n + T::kN * v;
      const V pv = T::mul(shifted_exp<T>(T::load(s + at), vscale, vm[r], valid, v), vinv[r]);
      const V pt = drop.active ? T::zero_unless(T::load_bits(bits + r * row_bytes, v), T::mul(pv, keep_scale)) : pv;
      T::store(s + at, pv);
      T::store(pd + at, pt);
      dot[r] = T::fmadd(pt, T::load(dp + at), dot[r]);
    }
#pragma GCC unroll 8
  for (int r = 0; r < R; ++r) dot[r] = T::set1(T::hsum(dot[r]));
  for (int64_t v = 0; v < nc; ++v)
#pragma GCC unroll 8
    for (int r = 0; r < R; ++r) {
      const int64_t at = r * n + T::kN * v;
      V g = T::load(dp + at);
      if (drop.active) g = T::zero_unless(T::load_bits(bits + r * row_bytes, v), T::mul(g, keep_scale));
      const V pv = T::mul(T::load(s + at), vscale);
      T::store(dp + at, T::mul(pv, T::sub(g, dot[r])));
    }
}

// The row kernels for a key count: 16 lanes where the build has AVX-512 and n is a multiple of 16.
struct RowKernels {
  void (*forward_group)(float*, float*, int64_t, float, const int32_t*, const DropoutPlan&, uint64_t, float*, uint8_t*);
  void (*forward_one)(float*, float*, int64_t, float, const int32_t*, const DropoutPlan&, uint64_t, float*, uint8_t*);
  void (*backward_group)(float*, float*, float*, int64_t, float, const int32_t*, const DropoutPlan&, const float*,
                         const uint8_t*);
  void (*backward_one)(float*, float*, float*, int64_t, float, const int32_t*, const DropoutPlan&, const float*,
                       const uint8_t*);
};

template <class T>
constexpr RowKernels row_kernels_of() {
  return {forward_rows<T, kRowGroup>, forward_rows<T, 1>, backward_rows<T, kRowGroup>, backward_rows<T, 1>};
}

// The widest rows this build has: the lane width padded inference key counts round up to as well.
#ifdef __AVX512F__
using WidestLanes = Lanes16;
#else
using WidestLanes = Lanes8;
#endif

RowKernels row_kernels(int64_t n) {
  if (n % WidestLanes::kN == 0) return row_kernels_of<WidestLanes>();
  return row_kernels_of<Lanes8>();
}

}  // namespace

bool fused_supported(int64_t Lk, int64_t D) { return Lk > 0 && D > 0 && Lk % 8 == 0 && D % 8 == 0; }

int64_t padded_key_count(int64_t Lk) { return (Lk + WidestLanes::kN - 1) / WidestLanes::kN * WidestLanes::kN; }

// Query rows per pass of one head: the scores of a block stay in L2 next to k^T and v. Short patches (training's
// 32 and 64 lines) are one block; a building's thousands of pair patches at inference go in blocks. Each
// row's scores, softmax and output are the same arithmetic in any block, so blocking changes no bit.
int64_t query_block(int64_t Lq, int64_t Lk) {
  constexpr int64_t kBlockScores = int64_t{1} << 16;  // floats (256 KiB)
  if (Lq * Lk <= kBlockScores) return Lq;
  return std::max<int64_t>(kRowGroup, kBlockScores / Lk / kRowGroup * kRowGroup);
}

void fused_forward(const Shape4& s, const float* q, Layout lq, const float* k, Layout lk, const float* v, Layout lv,
                   float* o, Layout lo, const uint8_t* mask, float scale, const DropoutPlan& drop, float* probs,
                   float* stats, uint8_t* keep_bits) {
  const int64_t H = s.H, Lq = s.Lq, Lk = s.Lk, D = s.D, nv = Lk / 8, qb = query_block(Lq, Lk);
  const RowKernels kernels = row_kernels(Lk);
  // One task per (batch item, head): inference scores one building at a time, so the heads are the parallelism.
  parallel_for_work(s.B * H, kPairsPerTask, 4 * Lq * Lk * (D + 4), [&](int64_t p0, int64_t p1) {
    float* kt = thread_scratch(static_cast<size_t>(D * Lk + Lk * D + qb * Lk));
    float *vc = kt + D * Lk, *S = vc + Lk * D;
    std::vector<int32_t> valid;
    for (int64_t p = p0; p < p1; ++p) {
      const int64_t b = p / H, h = p % H;
      if (mask && (p == p0 || h == 0)) key_lanes(mask + b * Lk, Lk, valid);
      transpose_into(Lk, D, k + lk.at(b, h), lk.row, kt);
      copy_head(Lk, D, v + lv.at(b, h), lv.row, vc);
      const NextPairRows<float> next(s, p, q, lq, k, lk, v, lv);
      for (int64_t i0 = 0; i0 < Lq; i0 += qb) {
        const int64_t rows_in_block = std::min(qb, Lq - i0);
        // q is read in place: each row block of the product touches a few of its rows (see head_gemm).
        head_gemm::gemm_nn(rows_in_block, Lk, D, q + lq.at(b, h) + i0 * lq.row, lq.row, kt, Lk, S, Lk);
        for (int64_t i = i0; i < i0 + rows_in_block;) {
          const int64_t row = p * Lq + i, group = i + kRowGroup <= i0 + rows_in_block ? kRowGroup : 1;
          for (int64_t r = i; r < i + group; ++r) next.share(r);
          auto rows = group == kRowGroup ? kernels.forward_group : kernels.forward_one;
          rows(S + (i - i0) * Lk, probs ? probs + row * Lk : nullptr, Lk, scale, mask ? valid.data() : nullptr, drop,
               static_cast<uint64_t>(row * Lk), stats ? stats + 2 * row : nullptr,
               keep_bits ? keep_bits + row * nv : nullptr);
          i += group;
        }
        head_gemm::gemm_nn(rows_in_block, D, Lk, S, Lk, vc, D, o + lo.at(b, h) + i0 * lo.row, lo.row);
      }
    }
  });
}

void fused_backward(const Shape4& s, const float* q, Layout lq, const float* k, Layout lk, const float* v, Layout lv,
                    const float* go, Layout lo, const uint8_t* mask, float scale, const DropoutPlan& drop,
                    const float* stats, const uint8_t* keep_bits, float* dq, Layout ldq, float* dk, Layout ldk,
                    float* dv, Layout ldv) {
  const int64_t H = s.H, Lq = s.Lq, Lk = s.Lk, D = s.D, nv = Lk / 8;
  const int64_t qn = Lq * D, kn = Lk * D, sn = Lq * Lk;
  const RowKernels kernels = row_kernels(Lk);
  parallel_for_work(s.B * H, kPairsPerTask, 12 * Lq * Lk * (D + 4), [&](int64_t p0, int64_t p1) {
    float* kt = thread_scratch(static_cast<size_t>(2 * D * Lk + 2 * qn + kn + 3 * sn));
    float *vt = kt + D * Lk, *Q = vt + D * Lk, *K = Q + qn, *G = K + kn, *S = G + qn, *dP = S + sn, *Pd = dP + sn;
    std::vector<int32_t> valid;
    for (int64_t p = p0; p < p1; ++p) {
      const int64_t b = p / H, h = p % H;
      if (mask && (p == p0 || h == 0)) key_lanes(mask + b * Lk, Lk, valid);
      copy_head(Lq, D, q + lq.at(b, h), lq.row, Q);
      copy_head(Lk, D, k + lk.at(b, h), lk.row, K);
      copy_head(Lq, D, go + lo.at(b, h), lo.row, G);
      transpose_into(Lk, D, K, D, kt);
      transpose_into(Lk, D, v + lv.at(b, h), lv.row, vt);
      head_gemm::gemm_nn(Lq, Lk, D, Q, D, kt, Lk, S, Lk);   // raw scores again
      head_gemm::gemm_nn(Lq, Lk, D, G, D, vt, Lk, dP, Lk);  // dP~ = g v^T
      const NextPairRows<float> next(s, p, q, lq, k, lk, v, lv, go, lo);
      for (int64_t i = 0; i < Lq;) {
        const int64_t row = p * Lq + i, group = i + kRowGroup <= Lq ? kRowGroup : 1;
        for (int64_t r = i; r < i + group; ++r) next.share(r);
        auto rows = group == kRowGroup ? kernels.backward_group : kernels.backward_one;
        rows(S + i * Lk, dP + i * Lk, Pd + i * Lk, Lk, scale, mask ? valid.data() : nullptr, drop, stats + 2 * row,
             keep_bits ? keep_bits + row * nv : nullptr);
        i += group;
      }
      head_gemm::gemm_nn(Lq, D, Lk, dP, Lk, K, D, dq + ldq.at(b, h), ldq.row);  // dS k
      head_gemm::gemm_tn(Lk, D, Lq, dP, Lk, Q, D, dk + ldk.at(b, h), ldk.row);  // dS^T q
      head_gemm::gemm_tn(Lk, D, Lq, Pd, Lk, G, D, dv + ldv.at(b, h), ldv.row);  // P~^T g
    }
  });
}

#else

bool fused_supported(int64_t, int64_t) { return false; }
int64_t padded_key_count(int64_t Lk) { return Lk; }
void fused_forward(const Shape4&, const float*, Layout, const float*, Layout, const float*, Layout, float*, Layout,
                   const uint8_t*, float, const DropoutPlan&, float*, float*, uint8_t*) {}
void fused_backward(const Shape4&, const float*, Layout, const float*, Layout, const float*, Layout, const float*,
                    Layout, const uint8_t*, float, const DropoutPlan&, const float*, const uint8_t*, float*, Layout,
                    float*, Layout, float*, Layout) {}

#endif

}  // namespace lc2wf::attention
