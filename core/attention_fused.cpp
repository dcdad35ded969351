// Fused float attention, forward and backward side by side. Per (batch item, head): S = Q K^T, key
// mask, softmax, dropout and P~ V in one pass over cache-resident blocks; the backward pass recomputes
// S with the same product, rebuilds P from the saved row statistics (bit-identical to the forward
// pass, no max or sum reductions) and the dropout mask from the saved keep bits (no hash), then runs
// the four gradient products. Probabilities are never stored.
#include "core/attention_fused.h"

#include <limits>
#include <vector>

#include "core/head_gemm.h"
#include "core/parallel.h"
#include "core/simd256.h"
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

inline __m256 lanes8(const int32_t* valid, int64_t v) {
  return _mm256_castsi256_ps(_mm256_loadu_si256(reinterpret_cast<const __m256i*>(valid + 8 * v)));
}

// exp(s * scale - m) of 8 keys, masked keys zero: the forward pass and the backward recomputation
// both go through here, so P = e * inv has the same bits in both.
inline __m256 shifted_exp8(__m256 s, __m256 scale, __m256 m, const int32_t* valid, int64_t v) {
  __m256 e = exp8_nonpositive(_mm256_fmsub_ps(s, scale, m));
  return valid ? _mm256_and_ps(e, lanes8(valid, v)) : e;
}

// Query rows whose softmax runs interleaved: one row alone is a chain of dependent reductions (max, exp,
// sum, reciprocal) that leaves most of the core idle; independent rows fill it.
constexpr int kRowGroup = 4;

// Softmax and dropout of R consecutive score rows of Lk = 8 * nv keys in place: s holds raw scores on entry
// and the dropped-out probabilities on exit; p (optional) gets the probabilities. A row whose keys are all
// masked is zero. Element j of query row `first / Lk` has dropout index first + j. Each row's arithmetic
// is that of R = 1, so the grouping does not change a bit.
template <int R>
void forward_rows(float* s, float* p, int64_t nv, float scale, const int32_t* valid, const DropoutPlan& drop,
                  uint64_t first, float* stat, uint8_t* bits) {
  const int64_t n = 8 * nv;
  const __m256 neg_inf = _mm256_set1_ps(-std::numeric_limits<float>::infinity());
  __m256 mx[R], sum[R], vm[R], vinv[R];
#pragma GCC unroll 8
  for (int r = 0; r < R; ++r) mx[r] = neg_inf, sum[r] = _mm256_setzero_ps();
  for (int64_t v = 0; v < nv; ++v)
#pragma GCC unroll 8
    for (int r = 0; r < R; ++r) {
      __m256 x = _mm256_loadu_ps(s + r * n + 8 * v);
      mx[r] = _mm256_max_ps(mx[r], valid ? _mm256_blendv_ps(neg_inf, x, lanes8(valid, v)) : x);
    }
  float m[R];
#pragma GCC unroll 8
  for (int r = 0; r < R; ++r) {
    const float top = hmax8(mx[r]);
    if (top == -std::numeric_limits<float>::infinity()) {
      if constexpr (R > 1) {
        // Rare (every key masked): each row on its own path.
        for (int q = 0; q < R; ++q)
          forward_rows<1>(s + q * n, p ? p + q * n : nullptr, nv, scale, valid, drop, first + q * n,
                          stat ? stat + 2 * q : nullptr, bits ? bits + q * nv : nullptr);
        return;
      }
      for (int64_t j = 0; j < n; ++j) s[j] = 0.0f;
      if (p)
        for (int64_t j = 0; j < n; ++j) p[j] = 0.0f;
      if (stat) stat[0] = stat[1] = 0.0f;
      if (bits)
        for (int64_t v = 0; v < nv; ++v) bits[v] = 0;
      return;
    }
    // Rounding is monotonic, so max(s) * scale is the maximum of the scaled scores.
    m[r] = top * scale;
    vm[r] = _mm256_set1_ps(m[r]);
  }
  const __m256 vscale = _mm256_set1_ps(scale);
  for (int64_t v = 0; v < nv; ++v)
#pragma GCC unroll 8
    for (int r = 0; r < R; ++r) {
      const __m256 e = shifted_exp8(_mm256_loadu_ps(s + r * n + 8 * v), vscale, vm[r], valid, v);
      _mm256_storeu_ps(s + r * n + 8 * v, e);
      sum[r] = _mm256_add_ps(sum[r], e);
    }
  float inv[R];
#pragma GCC unroll 8
  for (int r = 0; r < R; ++r) inv[r] = 1.0f / hsum8(sum[r]), vinv[r] = _mm256_set1_ps(inv[r]);
  const __m256 keep_scale = _mm256_set1_ps(static_cast<float>(drop.scale));
  for (int64_t v = 0; v < nv; ++v)
#pragma GCC unroll 8
    for (int r = 0; r < R; ++r) {
      float* row = s + r * n;
      __m256 pv = _mm256_mul_ps(_mm256_loadu_ps(row + 8 * v), vinv[r]);
      if (p) _mm256_storeu_ps(p + r * n + 8 * v, pv);
      if (drop.active) {
        const __m256 keep = _mm256_castsi256_ps(drop.mask.keep8(first + r * n + 8 * static_cast<uint64_t>(v)));
        if (bits) bits[r * nv + v] = static_cast<uint8_t>(_mm256_movemask_ps(keep));
        pv = _mm256_and_ps(_mm256_mul_ps(pv, keep_scale), keep);
      }
      _mm256_storeu_ps(row + 8 * v, pv);
    }
  if (stat)
#pragma GCC unroll 8
    for (int r = 0; r < R; ++r) stat[2 * r] = m[r], stat[2 * r + 1] = inv[r];
}

// R consecutive rows of the backward pass (Lk = 8 * nv keys). s holds raw scores, dp the gradient of the
// dropped-out probabilities; on exit pd holds the dropped-out probabilities and dp the score gradient
// dS = P * (dP - sum(P * dP)) * scale with dP = dP~ * keep * keep_scale (sum(P dP) = sum(P~ dP~)).
// Interleaved like forward_rows, each row's arithmetic that of R = 1.
template <int R>
void backward_rows(float* s, float* dp, float* pd, int64_t nv, float scale, const int32_t* valid,
                   const DropoutPlan& drop, const float* stat, const uint8_t* bits) {
  const int64_t n = 8 * nv;
  const __m256 vscale = _mm256_set1_ps(scale), keep_scale = _mm256_set1_ps(static_cast<float>(drop.scale));
  __m256 vm[R], vinv[R], dot[R];
#pragma GCC unroll 8
  for (int r = 0; r < R; ++r)
    vm[r] = _mm256_set1_ps(stat[2 * r]), vinv[r] = _mm256_set1_ps(stat[2 * r + 1]), dot[r] = _mm256_setzero_ps();
  for (int64_t v = 0; v < nv; ++v)
#pragma GCC unroll 8
    for (int r = 0; r < R; ++r) {
      const int64_t at = r * n + 8 * v;
      const __m256 pv = _mm256_mul_ps(shifted_exp8(_mm256_loadu_ps(s + at), vscale, vm[r], valid, v), vinv[r]);
      const __m256 pt =
          drop.active ? _mm256_and_ps(_mm256_mul_ps(pv, keep_scale), bits_to_mask8(bits[r * nv + v])) : pv;
      _mm256_storeu_ps(s + at, pv);
      _mm256_storeu_ps(pd + at, pt);
      dot[r] = _mm256_fmadd_ps(pt, _mm256_loadu_ps(dp + at), dot[r]);
    }
#pragma GCC unroll 8
  for (int r = 0; r < R; ++r) dot[r] = _mm256_set1_ps(hsum8(dot[r]));
  for (int64_t v = 0; v < nv; ++v)
#pragma GCC unroll 8
    for (int r = 0; r < R; ++r) {
      const int64_t at = r * n + 8 * v;
      __m256 g = _mm256_loadu_ps(dp + at);
      if (drop.active) g = _mm256_and_ps(_mm256_mul_ps(g, keep_scale), bits_to_mask8(bits[r * nv + v]));
      const __m256 pv = _mm256_mul_ps(_mm256_loadu_ps(s + at), vscale);
      _mm256_storeu_ps(dp + at, _mm256_mul_ps(pv, _mm256_sub_ps(g, dot[r])));
    }
}

}  // namespace

bool fused_supported(int64_t Lk, int64_t D) { return Lk > 0 && D > 0 && Lk % 8 == 0 && D % 8 == 0; }

void fused_forward(const Shape4& s, const float* q, Layout lq, const float* k, Layout lk, const float* v, Layout lv,
                   float* o, Layout lo, const uint8_t* mask, float scale, const DropoutPlan& drop, float* probs,
                   float* stats, uint8_t* keep_bits) {
  const int64_t H = s.H, Lq = s.Lq, Lk = s.Lk, D = s.D, nv = Lk / 8;
  parallel_for_work(s.B, 1, H * 4 * Lq * Lk * (D + 4), [&](int64_t b0, int64_t b1) {
    float* kt = thread_scratch(static_cast<size_t>(D * Lk + Lq * D + Lk * D + Lq * Lk));
    float *qc = kt + D * Lk, *vc = qc + Lq * D, *S = vc + Lk * D;
    std::vector<int32_t> valid;
    for (int64_t b = b0; b < b1; ++b) {
      if (mask) key_lanes(mask + b * Lk, Lk, valid);
      for (int64_t h = 0; h < H; ++h) {
        const int64_t p = b * H + h;
        transpose_into(Lk, D, k + lk.at(b, h), lk.row, kt);
        copy_head(Lq, D, q + lq.at(b, h), lq.row, qc);
        copy_head(Lk, D, v + lv.at(b, h), lv.row, vc);
        head_gemm::gemm_nn(Lq, Lk, D, qc, D, kt, Lk, S, Lk);
        const NextPairRows<float> next(s, p, q, lq, k, lk, v, lv);
        for (int64_t i = 0; i < Lq;) {
          const int64_t row = p * Lq + i, group = i + kRowGroup <= Lq ? kRowGroup : 1;
          for (int64_t r = i; r < i + group; ++r) next.share(r);
          auto rows = group == kRowGroup ? forward_rows<kRowGroup> : forward_rows<1>;
          rows(S + i * Lk, probs ? probs + row * Lk : nullptr, nv, scale, mask ? valid.data() : nullptr, drop,
               static_cast<uint64_t>(row * Lk), stats ? stats + 2 * row : nullptr,
               keep_bits ? keep_bits + row * nv : nullptr);
          i += group;
        }
        head_gemm::gemm_nn(Lq, D, Lk, S, Lk, vc, D, o + lo.at(b, h), lo.row);
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
  parallel_for_work(s.B, 1, H * 12 * Lq * Lk * (D + 4), [&](int64_t b0, int64_t b1) {
    float* kt = thread_scratch(static_cast<size_t>(2 * D * Lk + 2 * qn + kn + 3 * sn));
    float *vt = kt + D * Lk, *Q = vt + D * Lk, *K = Q + qn, *G = K + kn, *S = G + qn, *dP = S + sn, *Pd = dP + sn;
    std::vector<int32_t> valid;
    for (int64_t b = b0; b < b1; ++b) {
      if (mask) key_lanes(mask + b * Lk, Lk, valid);
      for (int64_t h = 0; h < H; ++h) {
        const int64_t p = b * H + h;
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
          auto rows = group == kRowGroup ? backward_rows<kRowGroup> : backward_rows<1>;
          rows(S + i * Lk, dP + i * Lk, Pd + i * Lk, nv, scale, mask ? valid.data() : nullptr, drop, stats + 2 * row,
               keep_bits ? keep_bits + row * nv : nullptr);
          i += group;
        }
        head_gemm::gemm_nn(Lq, D, Lk, dP, Lk, K, D, dq + ldq.at(b, h), ldq.row);  // dS k
        head_gemm::gemm_tn(Lk, D, Lq, dP, Lk, Q, D, dk + ldk.at(b, h), ldk.row);  // dS^T q
        head_gemm::gemm_tn(Lk, D, Lq, Pd, Lk, G, D, dv + ldv.at(b, h), ldv.row);  // P~^T g
      }
    }
  });
}

#else

bool fused_supported(int64_t, int64_t) { return false; }
void fused_forward(const Shape4&, const float*, Layout, const float*, Layout, const float*, Layout, float*, Layout,
                   const uint8_t*, float, const DropoutPlan&, float*, float*, uint8_t*) {}
void fused_backward(const Shape4&, const float*, Layout, const float*, Layout, const float*, Layout, const float*,
                    Layout, const uint8_t*, float, const DropoutPlan&, const float*, const uint8_t*, float*, Layout,
                    float*, Layout, float*, Layout) {}

#endif

}  // namespace lc2wf::attention
