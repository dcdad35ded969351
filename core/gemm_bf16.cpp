#include "core/gemm_bf16.h"

#if defined(__x86_64__) && defined(__GNUC__)

#include <immintrin.h>

#include <algorithm>
#include <utility>
#include <vector>

// Compiled for AVX512-BF16 function by function, so the library still runs on CPUs without it (callers
// check cpu_has_bf16_dot_product() first).
#define LC2WF_BF16_TARGET __attribute__((target("avx512f,avx512bw,avx512vl,avx512dq,avx512bf16")))

namespace lc2wf {
namespace {

constexpr int64_t kChunk = 256;  // K values packed at a time: the packed slices stay in L2
constexpr int kRows = 8;         // rows of C per micro-kernel call (16 accumulators + 2 B registers)
constexpr int64_t kCols = 32;    // columns of C per micro-kernel call: two registers of 16 floats
// Largest packed op(B) a thread keeps for the next tile of the same product (pairs; 1 MiB): a Linear
// layer's 256 x 256 weights are 128 KiB, an activation operand is not kept.
constexpr int64_t kKeptPairs = int64_t{1} << 18;

LC2WF_BF16_TARGET inline __mmask16 first_lanes(int64_t n) {
  return n >= 16 ? __mmask16(0xffff) : n <= 0 ? __mmask16(0) : __mmask16((1u << n) - 1u);
}

// The rounding is the CPU's (vcvtne2ps2bf16: nearest even like round_to_bf16; denormals become zero, as
// vdpbf16ps would treat them anyway; a NaN stays a NaN). A pair per 32-bit lane, the lower index in the
// low half: vdpbf16ps multiplies low halves together and high halves together.

// 32 consecutive floats (n of them present, the rest zero) -> 16 pairs (x[2t], x[2t + 1]).
LC2WF_BF16_TARGET inline __m512i pairs_of_consecutive(const float* x, int64_t n) {
  const __m512 lo = _mm512_maskz_loadu_ps(first_lanes(n), x), hi = _mm512_maskz_loadu_ps(first_lanes(n - 16), x + 16);
  return (__m512i)_mm512_cvtne2ps_pbh(hi, lo);
}

// 16 floats of two rows (n present) -> 16 pairs (x0[t], x1[t]); x1 null: the second halves are zero.
LC2WF_BF16_TARGET inline __m512i pairs_of_rows(const float* x0, const float* x1, int64_t n) {
  const __m512 r0 = _mm512_maskz_loadu_ps(first_lanes(n), x0);
  const __m512 r1 = x1 ? _mm512_maskz_loadu_ps(first_lanes(n), x1) : _mm512_setzero_ps();
  const __m512i both = (__m512i)_mm512_cvtne2ps_pbh(r1, r0);  // x0's 16 values, then x1's
  const __m512i interleave = _mm512_set_epi16(31, 15, 30, 14, 29, 13, 28, 12, 27, 11, 26, 10, 25, 9, 24, 8, 23, 7,
                                              22, 6, 21, 5, 20, 4, 19, 3, 18, 2, 17, 1, 16, 0);
  return _mm512_permutexvar_epi16(interleave, both);
}

// op(A)[r][k0 + k] for r < rows, k < kn as pairs (A[r][2p], A[r][2p + 1]), laid out as A is read: pair (r, p)
// at out[r * kp + p] (row-major) when !ta, at out[p * rows + r] when ta. Returns the two strides (row, pair).
LC2WF_BF16_TARGET std::pair<int64_t, int64_t> pack_a(bool ta, const float* A, int64_t lda, int64_t rows, int64_t k0,
                                                     int64_t kn, uint32_t* out) {
  const int64_t kp = (kn + 1) / 2;
  if (!ta) {
    for (int64_t r = 0; r < rows; ++r)
      for (int64_t p = 0; p < kp; p += 16)
        _mm512_mask_storeu_epi32(out + r * kp + p, first_lanes(kp - p),
                                 pairs_of_consecutive(A + r * lda + k0 + 2 * p, kn - 2 * p));
    return {kp, 1};
  }
  for (int64_t p = 0; p < kp; ++p) {
    const float* x0 = A + (k0 + 2 * p) * lda;
    const float* x1 = 2 * p + 1 < kn ? x0 + lda : nullptr;
    for (int64_t r = 0; r < rows; r += 16)
      _mm512_mask_storeu_epi32(out + p * rows + r, first_lanes(rows - r), pairs_of_rows(x0 + r, x1 ? x1 + r : nullptr, rows - r));
  }
  return {1, rows};
}

// op(B)[k0 + k][j] for k < kn, j < cols as pairs in blocks of 32 columns:
// out[(block * kp + p) * 32 + j % 32] = (B[2p][j], B[2p + 1][j]); columns past `cols` are zero.
LC2WF_BF16_TARGET void pack_b(bool tb, const float* B, int64_t ldb, int64_t cols, int64_t k0, int64_t kn,
                              uint32_t* out) {
  const int64_t kp = (kn + 1) / 2, blocks = (cols + kCols - 1) / kCols;
  if (!tb) {
    for (int64_t blk = 0; blk < blocks; ++blk)
      for (int64_t p = 0; p < kp; ++p)
        for (int64_t h = 0; h < kCols; h += 16) {
          const int64_t j = blk * kCols + h;
          const float* x0 = B + (k0 + 2 * p) * ldb + j;
          const float* x1 = 2 * p + 1 < kn ? x0 + ldb : nullptr;
          _mm512_storeu_si512(out + (blk * kp + p) * kCols + h, pairs_of_rows(x0, x1, cols - j));
        }
    return;
  }
  if (cols % kCols) std::fill(out + (blocks - 1) * kp * kCols, out + blocks * kp * kCols, 0u);
  alignas(64) uint32_t lanes[16];
  for (int64_t j = 0; j < cols; ++j) {
    uint32_t* column = out + (j / kCols) * kp * kCols + j % kCols;
    for (int64_t p = 0; p < kp; p += 16) {
      _mm512_store_si512(lanes, pairs_of_consecutive(B + j * ldb + k0 + 2 * p, kn - 2 * p));
      for (int64_t t = 0; t < std::min<int64_t>(16, kp - p); ++t) column[(p + t) * kCols] = lanes[t];
    }
  }
}

// C[R x n] (+)= a (R rows of kp pairs; pair (i, p) at a[i * rs + p * ps]) . b (kp x 32 pairs), n <= 32
// columns stored.
template <int R>
LC2WF_BF16_TARGET void micro_kernel(const uint32_t* a, int64_t rs, int64_t ps, int64_t kp, const uint32_t* b, float* C,
                                    int64_t ldc, int64_t n, bool add) {
  __m512 acc[R][2];
  for (int i = 0; i < R; ++i) acc[i][0] = acc[i][1] = _mm512_setzero_ps();
  for (int64_t p = 0; p < kp; ++p) {
    const __m512bh b0 = (__m512bh)_mm512_loadu_si512(b + p * kCols);
    const __m512bh b1 = (__m512bh)_mm512_loadu_si512(b + p * kCols + 16);
    for (int i = 0; i < R; ++i) {
      const __m512bh ai = (__m512bh)_mm512_set1_epi32(static_cast<int>(a[i * rs + p * ps]));
      acc[i][0] = _mm512_dpbf16_ps(acc[i][0], ai, b0);
      acc[i][1] = _mm512_dpbf16_ps(acc[i][1], ai, b1);
    }
  }
  const __mmask16 m0 = first_lanes(n), m1 = first_lanes(n - 16);
  for (int i = 0; i < R; ++i) {
    float* row = C + i * ldc;
    if (add) {
      acc[i][0] = _mm512_add_ps(acc[i][0], _mm512_maskz_loadu_ps(m0, row));
      acc[i][1] = _mm512_add_ps(acc[i][1], _mm512_maskz_loadu_ps(m1, row + 16));
    }
    _mm512_mask_storeu_ps(row, m0, acc[i][0]);
    _mm512_mask_storeu_ps(row + 16, m1, acc[i][1]);
  }
}

using MicroKernel = void (*)(const uint32_t*, int64_t, int64_t, int64_t, const uint32_t*, float*, int64_t, int64_t, bool);
constexpr MicroKernel kKernels[kRows + 1] = {nullptr,          micro_kernel<1>, micro_kernel<2>, micro_kernel<3>, micro_kernel<4>,
                                             micro_kernel<5>, micro_kernel<6>, micro_kernel<7>, micro_kernel<8>};

}  // namespace

void gemm_bf16_dot(bool ta, bool tb, int64_t M, int64_t N, int64_t K, const float* A, int64_t lda, const float* B,
                   int64_t ldb, float* C, int64_t ldc, bool accumulate, uint64_t product) {
  if (M == 0 || N == 0) return;
  if (K == 0) {
    if (!accumulate)
      for (int64_t i = 0; i < M; ++i) std::fill(C + i * ldc, C + i * ldc + N, 0.0f);
    return;
  }
  thread_local std::vector<uint32_t> a_pack, b_pack;
  thread_local struct { uint64_t product = 0; const float* B = nullptr; int64_t N = -1, K = -1; } packed;
  const int64_t blocks = (N + kCols - 1) / kCols, chunks = (K + kChunk - 1) / kChunk;
  const int64_t chunk_size = blocks * (kChunk / 2) * kCols;  // packed pairs of one K chunk of op(B), at most
  const bool keep = product != 0 && chunks * chunk_size <= kKeptPairs;
  const bool reuse = keep && packed.product == product && packed.B == B && packed.N == N && packed.K == K;
  if (!reuse) packed.product = 0;  // b_pack is overwritten below
  b_pack.resize(static_cast<size_t>((keep ? chunks : 1) * chunk_size));
  for (int64_t k0 = 0; k0 < K; k0 += kChunk) {
    const int64_t kn = std::min(kChunk, K - k0), kp = (kn + 1) / 2;
    uint32_t* b = b_pack.data() + (keep ? k0 / kChunk * chunk_size : 0);
    a_pack.resize(static_cast<size_t>(M * kp));
    const auto [rs, ps] = pack_a(ta, A, lda, M, k0, kn, a_pack.data());
    if (!reuse) pack_b(tb, B, ldb, N, k0, kn, b);
    const bool add = k0 > 0 || accumulate;
    for (int64_t blk = 0; blk < blocks; ++blk)
      for (int64_t r = 0; r < M; r += kRows) {
        const int64_t rows = std::min<int64_t>(kRows, M - r);
        kKernels[rows](a_pack.data() + r * rs, rs, ps, kp, b + blk * kp * kCols, C + r * ldc + blk * kCols, ldc,
                       std::min(kCols, N - blk * kCols), add);
      }
  }
  if (keep) packed = {product, B, N, K};
}

}  // namespace lc2wf

#else

#include <stdexcept>

namespace lc2wf {

void gemm_bf16_dot(bool, bool, int64_t, int64_t, int64_t, const float*, int64_t, const float*, int64_t, float*, int64_t,
                   bool, uint64_t) {
  throw std::logic_error("gemm_bf16_dot: this build has no AVX512-BF16 kernel");
}

}  // namespace lc2wf

#endif
