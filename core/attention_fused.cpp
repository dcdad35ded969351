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
#include "core/small_gemm.h"

namespace lc2wf::attention {

#ifdef LC2WF_SIMD256

namespace {

// Key-mask lanes of one batch item: all ones for a key that takes part, zero for a padded one.
void key_lanes(const uint8_t* mrow, int64_t Lk, std::vector<int32_t>& lanes) {
  lanes.resize(static_cast<size_t>(Lk));
  for (int64_t j = 0; j < Lk; ++j) lanes[static_cast<size_t>(j)] = mrow[j] ? 0 : -1;
}

// Copies one batch item's heads between a strided layout and contiguous head-major blocks
// (H x rows x D), rows outer when that walks the source in memory order (the packed (B, L, 3E) layout):
// a sequential stream the hardware prefetchers follow, where reading head by head jumps 3 KiB per row
// and spends the kernel's time waiting on memory. In the packed layout the rows of one head also fall
// into a few L1 sets, so products rereading them in place would miss.
template <bool kToBlock>
void move_heads(int64_t H, int64_t rows, int64_t D, float* strided, Layout l, int64_t b, float* block) {
  auto move = [&](int64_t h, int64_t r) {
    float* x = strided + l.at(b, h) + r * l.row;
    float* y = block + (h * rows + r) * D;
    for (int64_t c = 0; c < D; c += 8) {
      if constexpr (kToBlock)
        _mm256_storeu_ps(y + c, _mm256_loadu_ps(x + c));
      else
        _mm256_storeu_ps(x + c, _mm256_loadu_ps(y + c));
    }
  };
  if (l.row >= l.head) {
    for (int64_t r = 0; r < rows; ++r)
      for (int64_t h = 0; h < H; ++h) move(h, r);
  } else {
    for (int64_t h = 0; h < H; ++h)
      for (int64_t r = 0; r < rows; ++r) move(h, r);
  }
}

void gather_heads(int64_t H, int64_t rows, int64_t D, const float* src, Layout l, int64_t b, float* block) {
  move_heads<true>(H, rows, D, const_cast<float*>(src), l, b, block);
}

void scatter_heads(int64_t H, int64_t rows, int64_t D, const float* block, float* dst, Layout l, int64_t b) {
  move_heads<false>(H, rows, D, dst, l, b, const_cast<float*>(block));
}

// The memory of one batch item's rows of an operand: [first, last) in floats from the operand's base.
struct Span {
  const float* first;
  const float* last;
};

Span item_span(const float* base, Layout l, int64_t b, int64_t H, int64_t rows, int64_t D) {
  const float* first = base + l.at(b, 0);
  return {first, first + (H - 1) * l.head + (rows - 1) * l.row + D};
}

// Requests part `part` of `parts` of the next batch item's operand memory, so the gather of that item
// reads cached lines; spread over the heads of the current item so the requests never
// pile up. Spans of the packed layout overlap (q, k, v share rows) and are merged first.
class NextItemPrefetch {
 public:
  void add(Span s) {
    for (Span& t : spans_)
      if (s.first <= t.last && t.first <= s.last) {
        t.first = std::min(t.first, s.first), t.last = std::max(t.last, s.last);
        return;
      }
    spans_.push_back(s);
  }
  void part(int64_t part, int64_t parts) const {
    for (const Span& s : spans_) {
      const int64_t lines = (s.last - s.first + 15) / 16;
      for (int64_t l = lines * part / parts; l < lines * (part + 1) / parts; ++l) __builtin_prefetch(s.first + 16 * l, 0, 3);
    }
  }

 private:
  std::vector<Span> spans_;
};

// Per-thread scratch reused across calls: one batch item's blocks are 0.1-2 MB, and a fresh allocation
// per item would be mapped and page-faulted in every time. Holds the largest shape seen.
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
  const __m256 vscale = _mm256_set1_ps(scale), vm = _mm256_set1_ps(m);
  __m256 sum = _mm256_setzero_ps();
  for (int64_t v = 0; v < nv; ++v) {
    const __m256 e = shifted_exp8(_mm256_loadu_ps(s + 8 * v), vscale, vm, valid, v);
    _mm256_storeu_ps(s + 8 * v, e);
    sum = _mm256_add_ps(sum, e);
  }
  const float inv = 1.0f / hsum8(sum);
  const __m256 vinv = _mm256_set1_ps(inv), keep_scale = _mm256_set1_ps(static_cast<float>(drop.scale));
  for (int64_t v = 0; v < nv; ++v) {
    __m256 pv = _mm256_mul_ps(_mm256_loadu_ps(s + 8 * v), vinv);
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
    const __m256 pv = _mm256_mul_ps(shifted_exp8(_mm256_loadu_ps(s + 8 * v), vscale, vm, valid, v), vinv);
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
  const int64_t H = s.H, Lq = s.Lq, Lk = s.Lk, D = s.D, nv = Lk / 8;
  const int64_t qn = Lq * D, kn = Lk * D;
  parallel_for_work(s.B, 1, H * 4 * Lq * Lk * (D + 4), [&](int64_t b0, int64_t b1) {
    float* qb = thread_scratch(static_cast<size_t>(H * (2 * qn + 2 * kn) + D * Lk + Lq * Lk));
    float *kb = qb + H * qn, *vb = kb + H * kn, *ob = vb + H * kn, *kt = ob + H * qn, *S = kt + D * Lk;
    std::vector<int32_t> valid;
    for (int64_t b = b0; b < b1; ++b) {
      if (mask) key_lanes(mask + b * Lk, Lk, valid);
      gather_heads(H, Lq, D, q, lq, b, qb);
      gather_heads(H, Lk, D, k, lk, b, kb);
      gather_heads(H, Lk, D, v, lv, b, vb);
      NextItemPrefetch next;
      if (b + 1 < s.B) {
        next.add(item_span(q, lq, b + 1, H, Lq, D));
        next.add(item_span(k, lk, b + 1, H, Lk, D));
        next.add(item_span(v, lv, b + 1, H, Lk, D));
      }
      for (int64_t h = 0; h < H; ++h) {
        const int64_t p = b * H + h;
        next.part(h, H);
        transpose_into(Lk, D, kb + h * kn, D, kt);
        head_gemm::gemm_nn(Lq, Lk, D, qb + h * qn, D, kt, Lk, S, Lk);
        for (int64_t i = 0; i < Lq; ++i) {
          const int64_t row = p * Lq + i;
          forward_row(S + i * Lk, probs ? probs + row * Lk : nullptr, nv, scale, mask ? valid.data() : nullptr, drop,
                      static_cast<uint64_t>(row * Lk), stats ? stats + 2 * row : nullptr,
                      keep_bits ? keep_bits + row * nv : nullptr);
        }
        head_gemm::gemm_nn(Lq, D, Lk, S, Lk, vb + h * kn, D, ob + h * qn, D);
      }
      scatter_heads(H, Lq, D, ob, o, lo, b);
    }
  });
}

// Each batch item's q, k, v and g are gathered once, every head's dq, dk, dv go to blocks that are
// scattered once; the dq, dk, dv layouts must not overlap the inputs.
void fused_backward(const Shape4& s, const float* q, Layout lq, const float* k, Layout lk, const float* v, Layout lv,
                    const float* go, Layout lo, const uint8_t* mask, float scale, const DropoutPlan& drop,
                    const float* stats, const uint8_t* keep_bits, float* dq, Layout ldq, float* dk, Layout ldk,
                    float* dv, Layout ldv) {
  const int64_t H = s.H, Lq = s.Lq, Lk = s.Lk, D = s.D, nv = Lk / 8;
  const int64_t qn = Lq * D, kn = Lk * D, sn = Lq * Lk;
  parallel_for_work(s.B, 1, H * 12 * Lq * Lk * (D + 4), [&](int64_t b0, int64_t b1) {
    float* qb = thread_scratch(static_cast<size_t>(H * (4 * qn + 4 * kn) + 2 * D * Lk + 3 * sn));
    float *kb = qb + H * qn, *vb = kb + H * kn, *gb = vb + H * kn;
    float *dqb = gb + H * qn, *dkb = dqb + H * qn, *dvb = dkb + H * kn;
    float *kt = dvb + H * kn, *vt = kt + D * Lk, *S = vt + D * Lk, *dP = S + sn, *Pd = dP + sn;
    std::vector<int32_t> valid;
    for (int64_t b = b0; b < b1; ++b) {
      if (mask) key_lanes(mask + b * Lk, Lk, valid);
      gather_heads(H, Lq, D, q, lq, b, qb);
      gather_heads(H, Lk, D, k, lk, b, kb);
      gather_heads(H, Lk, D, v, lv, b, vb);
      gather_heads(H, Lq, D, go, lo, b, gb);
      NextItemPrefetch next;
      if (b + 1 < s.B) {
        next.add(item_span(q, lq, b + 1, H, Lq, D));
        next.add(item_span(k, lk, b + 1, H, Lk, D));
        next.add(item_span(v, lv, b + 1, H, Lk, D));
        next.add(item_span(go, lo, b + 1, H, Lq, D));
      }
      for (int64_t h = 0; h < H; ++h) {
        const int64_t p = b * H + h;
        next.part(h, H);
        const float *Q = qb + h * qn, *K = kb + h * kn, *G = gb + h * qn;
        transpose_into(Lk, D, K, D, kt);
        transpose_into(Lk, D, vb + h * kn, D, vt);
        head_gemm::gemm_nn(Lq, Lk, D, Q, D, kt, Lk, S, Lk);   // raw scores again
        head_gemm::gemm_nn(Lq, Lk, D, G, D, vt, Lk, dP, Lk);  // dP~ = g v^T
        for (int64_t i = 0; i < Lq; ++i) {
          const int64_t row = p * Lq + i;
          backward_row(S + i * Lk, dP + i * Lk, Pd + i * Lk, nv, scale, mask ? valid.data() : nullptr, drop,
                       stats + 2 * row, keep_bits ? keep_bits + row * nv : nullptr);
        }
        head_gemm::gemm_nn(Lq, D, Lk, dP, Lk, K, D, dqb + h * qn, D);  // dS k
        head_gemm::gemm_tn(Lk, D, Lq, dP, Lk, Q, D, dkb + h * kn, D);  // dS^T q
        head_gemm::gemm_tn(Lk, D, Lq, Pd, Lk, G, D, dvb + h * kn, D);  // P~^T g
      }
      scatter_heads(H, Lq, D, dqb, dq, ldq, b);
      scatter_heads(H, Lk, D, dkb, dk, ldk, b);
      scatter_heads(H, Lk, D, dvb, dv, ldv, b);
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
