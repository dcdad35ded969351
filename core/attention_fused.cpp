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

inline __m256 lanes8(const int32_t* valid, int64_t v) {
  return _mm256_castsi256_ps(_mm256_loadu_si256(reinterpret_cast<const __m256i*>(valid + 8 * v)));
}

// The probabilities of one row from raw scores and the row statistics; the backward pass calls it with
// the saved statistics, so both passes see the same bits.
inline __m256 prob8(__m256 s, __m256 scale, __m256 m, __m256 inv, const int32_t* valid, int64_t v) {
  __m256 e = exp8_nonpositive(_mm256_fmsub_ps(s, scale, m));
  if (valid) e = _mm256_and_ps(e, lanes8(valid, v));
  return _mm256_mul_ps(e, inv);
}

// Softmax and dropout of one score row in place: s holds raw scores on entry and the dropped-out
// probabilities on exit; p (optional) gets the probabilities. A row whose keys are all masked is zero.
// Element j of query row `first / Lk` has dropout index first + j.
void forward_row(float* s, float* p, int64_t nv, float scale, const int32_t* valid, const DropoutPlan& drop,
                 uint64_t first, float* stat, uint8_t* bits) {
  const __m256 neg_inf = _mm256_set1_ps(-std::numeric_limits<float>::infinity());
  __m256 mx = neg_inf;
  for (int64_t v = 0; v < nv; ++v) {
    __m256 x = _mm256_loadu_ps(s + 8 * v);
    mx = _mm256_max_ps(mx, valid ? _mm256_blendv_ps(neg_inf, x, lanes8(valid, v)) : x);
  }
  const float top = hmax8(mx);
  if (top == -std::numeric_limits<float>::infinity()) {
    for (int64_t j = 0; j < 8 * nv; ++j) s[j] = 0.0f;
    if (p)
      for (int64_t j = 0; j < 8 * nv; ++j) p[j] = 0.0f;
    if (stat) stat[0] = stat[1] = 0.0f;
    if (bits)
      for (int64_t v = 0; v < nv; ++v) bits[v] = 0;
    return;
  }
  // Rounding is monotonic, so max(s) * scale is the maximum of the scaled scores.
  const float m = top * scale;
  const __m256 vscale = _mm256_set1_ps(scale), vm = _mm256_set1_ps(m), one = _mm256_set1_ps(1.0f);
  __m256 sum = _mm256_setzero_ps();
  for (int64_t v = 0; v < nv; ++v) sum = _mm256_add_ps(sum, prob8(_mm256_loadu_ps(s + 8 * v), vscale, vm, one, valid, v));
  const float inv = 1.0f / hsum8(sum);
  const __m256 vinv = _mm256_set1_ps(inv), keep_scale = _mm256_set1_ps(static_cast<float>(drop.scale));
  for (int64_t v = 0; v < nv; ++v) {
    __m256 pv = prob8(_mm256_loadu_ps(s + 8 * v), vscale, vm, vinv, valid, v);
    if (p) _mm256_storeu_ps(p + 8 * v, pv);
    if (drop.active) {
      const __m256 keep = _mm256_castsi256_ps(drop.mask.keep8(first + 8 * static_cast<uint64_t>(v)));
      if (bits) bits[v] = static_cast<uint8_t>(_mm256_movemask_ps(keep));
      pv = _mm256_and_ps(_mm256_mul_ps(pv, keep_scale), keep);
    }
    _mm256_storeu_ps(s + 8 * v, pv);
  }
  if (stat) stat[0] = m, stat[1] = inv;
}

// One row of the backward pass. s holds raw scores, dp the gradient of the dropped-out probabilities;
// on exit pd holds the dropped-out probabilities and dp the score gradient
// dS = P * (dP - sum(P * dP)) * scale with dP = dP~ * keep * keep_scale (sum(P dP) = sum(P~ dP~)).
void backward_row(float* s, float* dp, float* pd, int64_t nv, float scale, const int32_t* valid,
                  const DropoutPlan& drop, const float* stat, const uint8_t* bits) {
  const __m256 vscale = _mm256_set1_ps(scale), vm = _mm256_set1_ps(stat[0]), vinv = _mm256_set1_ps(stat[1]);
  const __m256 keep_scale = _mm256_set1_ps(static_cast<float>(drop.scale));
  __m256 dot = _mm256_setzero_ps();
  for (int64_t v = 0; v < nv; ++v) {
    const __m256 pv = prob8(_mm256_loadu_ps(s + 8 * v), vscale, vm, vinv, valid, v);
    const __m256 pt = drop.active ? _mm256_and_ps(_mm256_mul_ps(pv, keep_scale), bits_to_mask8(bits[v])) : pv;
    _mm256_storeu_ps(s + 8 * v, pv);
    _mm256_storeu_ps(pd + 8 * v, pt);
    dot = _mm256_fmadd_ps(pt, _mm256_loadu_ps(dp + 8 * v), dot);
  }
  const __m256 vdot = _mm256_set1_ps(hsum8(dot));
  for (int64_t v = 0; v < nv; ++v) {
    __m256 g = _mm256_loadu_ps(dp + 8 * v);
    if (drop.active) g = _mm256_and_ps(_mm256_mul_ps(g, keep_scale), bits_to_mask8(bits[v]));
    const __m256 pv = _mm256_mul_ps(_mm256_loadu_ps(s + 8 * v), vscale);
    _mm256_storeu_ps(dp + 8 * v, _mm256_mul_ps(pv, _mm256_sub_ps(g, vdot)));
  }
}

}  // namespace

bool fused_supported(int64_t Lk, int64_t D) { return Lk > 0 && D > 0 && Lk % 8 == 0 && D % 8 == 0; }

void fused_forward(const Shape4& s, const float* q, Layout lq, const float* k, Layout lk, const float* v, Layout lv,
                   float* o, Layout lo, const uint8_t* mask, float scale, const DropoutPlan& drop, float* probs,
                   float* stats, uint8_t* keep_bits) {
  const int64_t Lq = s.Lq, Lk = s.Lk, D = s.D, nv = Lk / 8;
  parallel_for_work(s.B * s.H, kPairsPerTask, 4 * Lq * Lk * (D + 4), [&](int64_t p0, int64_t p1) {
    std::vector<float> kt(static_cast<size_t>(D * Lk)), S(static_cast<size_t>(Lq * Lk));
    std::vector<int32_t> valid;
    for (int64_t p = p0; p < p1; ++p) {
      const int64_t b = p / s.H, h = p % s.H;
      prefetch_next_pair(s, p, q, lq, k, lk, v, lv);
      if (mask && (p == p0 || h == 0)) key_lanes(mask + b * Lk, Lk, valid);
      transpose_into(Lk, D, k + lk.at(b, h), lk.row, kt.data());
      head_gemm::gemm_nn(Lq, Lk, D, q + lq.at(b, h), lq.row, kt.data(), Lk, S.data(), Lk);
      for (int64_t i = 0; i < Lq; ++i) {
        const int64_t row = p * Lq + i;
        forward_row(S.data() + i * Lk, probs ? probs + row * Lk : nullptr, nv, scale, mask ? valid.data() : nullptr,
                    drop, static_cast<uint64_t>(row * Lk), stats ? stats + 2 * row : nullptr,
                    keep_bits ? keep_bits + row * nv : nullptr);
      }
      head_gemm::gemm_nn(Lq, D, Lk, S.data(), Lk, v + lv.at(b, h), lv.row, o + lo.at(b, h), lo.row);
    }
  });
}

void fused_backward(const Shape4& s, const float* q, Layout lq, const float* k, Layout lk, const float* v, Layout lv,
                    const float* go, Layout lo, const uint8_t* mask, float scale, const DropoutPlan& drop,
                    const float* stats, const uint8_t* keep_bits, float* dq, Layout ldq, float* dk, Layout ldk,
                    float* dv, Layout ldv) {
  const int64_t Lq = s.Lq, Lk = s.Lk, D = s.D, nv = Lk / 8;
  parallel_for_work(s.B * s.H, kPairsPerTask, 12 * Lq * Lk * (D + 4), [&](int64_t p0, int64_t p1) {
    const size_t n = static_cast<size_t>(Lq * Lk);
    std::vector<float> kt(static_cast<size_t>(D * Lk)), vt(static_cast<size_t>(D * Lk)), S(n), dP(n), Pd(n);
    std::vector<int32_t> valid;
    for (int64_t p = p0; p < p1; ++p) {
      const int64_t b = p / s.H, h = p % s.H;
      prefetch_next_pair(s, p, q, lq, k, lk, v, lv, go, lo);
      if (mask && (p == p0 || h == 0)) key_lanes(mask + b * Lk, Lk, valid);
      const float* Q = q + lq.at(b, h);
      const float* K = k + lk.at(b, h);
      const float* GO = go + lo.at(b, h);
      transpose_into(Lk, D, K, lk.row, kt.data());
      transpose_into(Lk, D, v + lv.at(b, h), lv.row, vt.data());
      head_gemm::gemm_nn(Lq, Lk, D, Q, lq.row, kt.data(), Lk, S.data(), Lk);    // raw scores again
      head_gemm::gemm_nn(Lq, Lk, D, GO, lo.row, vt.data(), Lk, dP.data(), Lk);  // dP~ = g v^T
      for (int64_t i = 0; i < Lq; ++i) {
        const int64_t row = p * Lq + i;
        backward_row(S.data() + i * Lk, dP.data() + i * Lk, Pd.data() + i * Lk, nv, scale,
                     mask ? valid.data() : nullptr, drop, stats + 2 * row, keep_bits ? keep_bits + row * nv : nullptr);
      }
      head_gemm::gemm_nn(Lq, D, Lk, dP.data(), Lk, K, lk.row, dq + ldq.at(b, h), ldq.row);          // dS k
      head_gemm::gemm_tn(Lk, D, Lq, dP.data(), Lk, Q, lq.row, dk + ldk.at(b, h), ldk.row);          // dS^T q
      head_gemm::gemm_tn(Lk, D, Lq, Pd.data(), Lk, GO, lo.row, dv + ldv.at(b, h), ldv.row);         // P~^T g
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
