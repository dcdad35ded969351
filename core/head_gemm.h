// AVX2 register-blocked products for one attention head: C (M x N) = A B, N a multiple of 8. The
// auto-vectorised small_gemm keeps 4 rows x N columns of accumulators, which spill from the 16 ymm
// registers at N = 32 and 64; here a block is 6 rows x 16 columns (12 accumulators, 2 B registers and
// a broadcast), so every k step is 12 FMAs for 8 loads.
#pragma once

#include <cstdint>

#include "core/simd256.h"

#ifdef LC2WF_SIMD256
namespace lc2wf::head_gemm {

// A(i, k) is A[i * lda + k], or A[k * lda + i] when kTransA (C = A^T B without a transpose copy).
// The accumulators are named variables: GCC kept an array of them on the stack, one store per FMA.
template <int MR, int NV, bool kTransA>
inline void block(int64_t K, const float* A, int64_t lda, const float* B, int64_t ldb, float* C, int64_t ldc) {
  static_assert(MR >= 1 && MR <= 6 && (NV == 1 || NV == 2));
  __m256 c00 = _mm256_setzero_ps(), c01 = c00, c10 = c00, c11 = c00, c20 = c00, c21 = c00, c30 = c00, c31 = c00,
         c40 = c00, c41 = c00, c50 = c00, c51 = c00;
  for (int64_t k = 0; k < K; ++k) {
    const __m256 b0 = _mm256_loadu_ps(B + k * ldb);
    const __m256 b1 = NV == 2 ? _mm256_loadu_ps(B + k * ldb + 8) : b0;
    auto row = [&](int i, __m256& x0, __m256& x1) {
      const __m256 a = _mm256_broadcast_ss(kTransA ? A + k * lda + i : A + i * lda + k);
      x0 = _mm256_fmadd_ps(a, b0, x0);
      if constexpr (NV == 2) x1 = _mm256_fmadd_ps(a, b1, x1);
    };
    row(0, c00, c01);
    if constexpr (MR > 1) row(1, c10, c11);
    if constexpr (MR > 2) row(2, c20, c21);
    if constexpr (MR > 3) row(3, c30, c31);
    if constexpr (MR > 4) row(4, c40, c41);
    if constexpr (MR > 5) row(5, c50, c51);
  }
  auto store = [&](int i, __m256 x0, __m256 x1) {
    _mm256_storeu_ps(C + i * ldc, x0);
    if constexpr (NV == 2) _mm256_storeu_ps(C + i * ldc + 8, x1);
  };
  store(0, c00, c01);
  if constexpr (MR > 1) store(1, c10, c11);
  if constexpr (MR > 2) store(2, c20, c21);
  if constexpr (MR > 3) store(3, c30, c31);
  if constexpr (MR > 4) store(4, c40, c41);
  if constexpr (MR > 5) store(5, c50, c51);
}

template <int NV, bool kTransA>
inline void block_rows(int rows, int64_t K, const float* A, int64_t lda, const float* B, int64_t ldb, float* C,
                       int64_t ldc) {
  switch (rows) {
    case 6: block<6, NV, kTransA>(K, A, lda, B, ldb, C, ldc); return;
    case 5: block<5, NV, kTransA>(K, A, lda, B, ldb, C, ldc); return;
    case 4: block<4, NV, kTransA>(K, A, lda, B, ldb, C, ldc); return;
    case 3: block<3, NV, kTransA>(K, A, lda, B, ldb, C, ldc); return;
    case 2: block<2, NV, kTransA>(K, A, lda, B, ldb, C, ldc); return;
    default: block<1, NV, kTransA>(K, A, lda, B, ldb, C, ldc); return;
  }
}

// Row blocks of 6, except that a remaining 8 rows go as 4 + 4 (more accumulators than 6 + 2).
template <bool kTransA>
void columns_avx2(int64_t M, int64_t j0, int64_t N, int64_t K, const float* A, int64_t lda, const float* B,
                  int64_t ldb, float* C, int64_t ldc) {
  for (int64_t j = j0; j < N; j += 16) {
    const bool pair = j + 16 <= N;
    for (int64_t i = 0; i < M;) {
      const int64_t left = M - i;
      const int rows = left == 8 ? 4 : static_cast<int>(left < 6 ? left : 6);
      const float* a = kTransA ? A + i : A + i * lda;
      if (pair)
        block_rows<2, kTransA>(rows, K, a, lda, B + j, ldb, C + i * ldc + j, ldc);
      else
        block_rows<1, kTransA>(rows, K, a, lda, B + j, ldb, C + i * ldc + j, ldc);
      i += rows;
    }
  }
}

#ifdef __AVX512F__
// AVX-512: 32 registers hold a block of 12 rows x 32 columns (24 accumulators, 2 B registers, a
// broadcast), 24 FMAs for 2 loads and 12 broadcasts. Each C element is still one FMA chain over k from
// zero, so the results are bit-identical to the AVX2 blocks.
template <int MR, bool kTransA>
inline void block512(int64_t K, const float* A, int64_t lda, const float* B, int64_t ldb, float* C, int64_t ldc) {
  static_assert(MR >= 1 && MR <= 12);
  __m512 c[MR][2];
#pragma GCC unroll 12
  for (int i = 0; i < MR; ++i) c[i][0] = c[i][1] = _mm512_setzero_ps();
  for (int64_t k = 0; k < K; ++k) {
    const __m512 b0 = _mm512_loadu_ps(B + k * ldb), b1 = _mm512_loadu_ps(B + k * ldb + 16);
#pragma GCC unroll 12
    for (int i = 0; i < MR; ++i) {
      const __m512 a = _mm512_set1_ps(kTransA ? A[k * lda + i] : A[i * lda + k]);
      c[i][0] = _mm512_fmadd_ps(a, b0, c[i][0]);
      c[i][1] = _mm512_fmadd_ps(a, b1, c[i][1]);
    }
  }
#pragma GCC unroll 12
  for (int i = 0; i < MR; ++i) {
    _mm512_storeu_ps(C + i * ldc, c[i][0]);
    _mm512_storeu_ps(C + i * ldc + 16, c[i][1]);
  }
}

template <bool kTransA>
inline void block512_rows(int rows, int64_t K, const float* A, int64_t lda, const float* B, int64_t ldb, float* C,
                          int64_t ldc) {
  switch (rows) {
    case 12: block512<12, kTransA>(K, A, lda, B, ldb, C, ldc); return;
    case 10: block512<10, kTransA>(K, A, lda, B, ldb, C, ldc); return;
    case 8: block512<8, kTransA>(K, A, lda, B, ldb, C, ldc); return;
    case 6: block512<6, kTransA>(K, A, lda, B, ldb, C, ldc); return;
    case 4: block512<4, kTransA>(K, A, lda, B, ldb, C, ldc); return;
    case 2: block512<2, kTransA>(K, A, lda, B, ldb, C, ldc); return;
    default: block512<1, kTransA>(K, A, lda, B, ldb, C, ldc); return;
  }
}
#endif

// Whole 32-column panels on the AVX-512 blocks where the CPU has them (rows in blocks of 12, the rest
// in even blocks), the remaining columns on the AVX2 ones. A row block runs across every panel before the
// next one starts, so A may be read in place from a strided layout: its few rows stay in L1 meanwhile.
template <bool kTransA>
__attribute__((noinline)) void product(int64_t M, int64_t N, int64_t K, const float* A, int64_t lda, const float* B,
                                       int64_t ldb, float* C, int64_t ldc) {
  int64_t j = 0;
#ifdef __AVX512F__
  const int64_t panels_end = N / 32 * 32;
  for (int64_t i = 0; i < M;) {
    const int64_t left = M - i;
    const int rows = left >= 12 ? 12 : left >= 2 ? static_cast<int>(left & ~int64_t{1}) : 1;
    for (int64_t jp = 0; jp < panels_end; jp += 32)
      block512_rows<kTransA>(rows, K, kTransA ? A + i : A + i * lda, lda, B + jp, ldb, C + i * ldc + jp, ldc);
    i += rows;
  }
  j = panels_end;
#endif
  columns_avx2<kTransA>(M, j, N, K, A, lda, B, ldb, C, ldc);
}

// C = A B, A (M x K, row stride lda).
inline void gemm_nn(int64_t M, int64_t N, int64_t K, const float* A, int64_t lda, const float* B, int64_t ldb,
                    float* C, int64_t ldc) {
  product<false>(M, N, K, A, lda, B, ldb, C, ldc);
}

// C = A^T B, A stored (K x M, row stride lda).
inline void gemm_tn(int64_t M, int64_t N, int64_t K, const float* A, int64_t lda, const float* B, int64_t ldb,
                    float* C, int64_t ldc) {
  product<true>(M, N, K, A, lda, B, ldb, C, ldc);
}

}  // namespace lc2wf::head_gemm
#endif
