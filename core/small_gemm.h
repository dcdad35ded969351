// Register-blocked products for the small, cache-resident matrices of one attention head
// (32 or 64 rows/cols): C = A B with A (M x K, row stride lda), B (K x N, ldb), C (M x N, ldc).
#pragma once

#include <cstdint>

#ifdef __AVX__
#include <immintrin.h>
#endif

namespace lc2wf {

// A(i, k) sits at A[i * rs + k * cs]: (rs, cs) = (lda, 1) for A as stored, (1, lda) for A stored
// transposed, so one kernel serves C = A B and C = A^T B; kTransA fixes the unit stride at compile time.
// Four rows of C at a time so every row of B loaded from L1 feeds four FMAs; N is a compile-time
// constant so the accumulators live in vector registers. Kept out of line: inlined into the large
// attention loops the accumulators were spilled to the stack.
template <class T, int N, bool kTransA>
__attribute__((noinline)) void small_gemm_strided_fixed(int64_t M, int64_t K, const T* A, int64_t lda, const T* B,
                                                        int64_t ldb, T* C, int64_t ldc) {
  const int64_t rs = kTransA ? 1 : lda, cs = kTransA ? lda : 1;
  int64_t i = 0;
  for (; i + 4 <= M; i += 4) {
    T acc0[N] = {}, acc1[N] = {}, acc2[N] = {}, acc3[N] = {};
    const T* a = A + i * rs;
    for (int64_t k = 0; k < K; ++k) {
      const T* b = B + k * ldb;
      const T* ak = a + k * cs;
      T a0 = ak[0], a1 = ak[rs], a2 = ak[2 * rs], a3 = ak[3 * rs];
      for (int n = 0; n < N; ++n) {
        acc0[n] += a0 * b[n];
        acc1[n] += a1 * b[n];
        acc2[n] += a2 * b[n];
        acc3[n] += a3 * b[n];
      }
    }
    for (int n = 0; n < N; ++n) {
      C[i * ldc + n] = acc0[n];
      C[(i + 1) * ldc + n] = acc1[n];
      C[(i + 2) * ldc + n] = acc2[n];
      C[(i + 3) * ldc + n] = acc3[n];
    }
  }
  for (; i < M; ++i) {
    T acc[N] = {};
    for (int64_t k = 0; k < K; ++k) {
      T av = A[i * rs + k * cs];
      const T* b = B + k * ldb;
      for (int n = 0; n < N; ++n) acc[n] += av * b[n];
    }
    for (int n = 0; n < N; ++n) C[i * ldc + n] = acc[n];
  }
}

template <class T, bool kTransA>
void small_gemm_strided(int64_t M, int64_t N, int64_t K, const T* A, int64_t lda, const T* B, int64_t ldb, T* C,
                        int64_t ldc) {
  const int64_t rs = kTransA ? 1 : lda, cs = kTransA ? lda : 1;
  switch (N) {
    case 16: small_gemm_strided_fixed<T, 16, kTransA>(M, K, A, lda, B, ldb, C, ldc); return;
    case 32: small_gemm_strided_fixed<T, 32, kTransA>(M, K, A, lda, B, ldb, C, ldc); return;
    case 64: small_gemm_strided_fixed<T, 64, kTransA>(M, K, A, lda, B, ldb, C, ldc); return;
    default:
      for (int64_t i = 0; i < M; ++i) {
        T* c = C + i * ldc;
        for (int64_t n = 0; n < N; ++n) c[n] = T(0);
        for (int64_t k = 0; k < K; ++k) {
          T av = A[i * rs + k * cs];
          const T* b = B + k * ldb;
          for (int64_t n = 0; n < N; ++n) c[n] += av * b[n];
        }
      }
  }
}

// C = A B with A (M x K, row stride lda).
template <class T>
inline void small_gemm(int64_t M, int64_t N, int64_t K, const T* A, int64_t lda, const T* B, int64_t ldb, T* C,
                       int64_t ldc) {
  small_gemm_strided<T, false>(M, N, K, A, lda, B, ldb, C, ldc);
}

// C = A^T B with A stored (K x M, row stride lda): saves the explicit transpose of A.
template <class T>
inline void small_gemm_tn(int64_t M, int64_t N, int64_t K, const T* A, int64_t lda, const T* B, int64_t ldb, T* C,
                          int64_t ldc) {
  small_gemm_strided<T, true>(M, N, K, A, lda, B, ldb, C, ldc);
}

// dst (cols x rows, row stride rows) = src^T, src (rows x cols, row stride lds).
template <class T>
inline void transpose_into(int64_t rows, int64_t cols, const T* src, int64_t lds, T* dst) {
  for (int64_t r = 0; r < rows; ++r)
    for (int64_t c = 0; c < cols; ++c) dst[c * rows + r] = src[r * lds + c];
}

#ifdef __AVX__
// 8x8 register transposes: several times faster than the element loop for the head blocks.
template <>
inline void transpose_into<float>(int64_t rows, int64_t cols, const float* src, int64_t lds, float* dst) {
  if (rows % 8 != 0 || cols % 8 != 0) {
    for (int64_t r = 0; r < rows; ++r)
      for (int64_t c = 0; c < cols; ++c) dst[c * rows + r] = src[r * lds + c];
    return;
  }
  for (int64_t r0 = 0; r0 < rows; r0 += 8)
    for (int64_t c0 = 0; c0 < cols; c0 += 8) {
      const float* s = src + r0 * lds + c0;
      __m256 r[8];
      for (int k = 0; k < 8; ++k) r[k] = _mm256_loadu_ps(s + k * lds);
      __m256 t0 = _mm256_unpacklo_ps(r[0], r[1]), t1 = _mm256_unpackhi_ps(r[0], r[1]);
      __m256 t2 = _mm256_unpacklo_ps(r[2], r[3]), t3 = _mm256_unpackhi_ps(r[2], r[3]);
      __m256 t4 = _mm256_unpacklo_ps(r[4], r[5]), t5 = _mm256_unpackhi_ps(r[4], r[5]);
      __m256 t6 = _mm256_unpacklo_ps(r[6], r[7]), t7 = _mm256_unpackhi_ps(r[6], r[7]);
      __m256 s0 = _mm256_shuffle_ps(t0, t2, _MM_SHUFFLE(1, 0, 1, 0));
      __m256 s1 = _mm256_shuffle_ps(t0, t2, _MM_SHUFFLE(3, 2, 3, 2));
      __m256 s2 = _mm256_shuffle_ps(t1, t3, _MM_SHUFFLE(1, 0, 1, 0));
      __m256 s3 = _mm256_shuffle_ps(t1, t3, _MM_SHUFFLE(3, 2, 3, 2));
      __m256 s4 = _mm256_shuffle_ps(t4, t6, _MM_SHUFFLE(1, 0, 1, 0));
      __m256 s5 = _mm256_shuffle_ps(t4, t6, _MM_SHUFFLE(3, 2, 3, 2));
      __m256 s6 = _mm256_shuffle_ps(t5, t7, _MM_SHUFFLE(1, 0, 1, 0));
      __m256 s7 = _mm256_shuffle_ps(t5, t7, _MM_SHUFFLE(3, 2, 3, 2));
      float* d = dst + c0 * rows + r0;
      _mm256_storeu_ps(d + 0 * rows, _mm256_permute2f128_ps(s0, s4, 0x20));
      _mm256_storeu_ps(d + 1 * rows, _mm256_permute2f128_ps(s1, s5, 0x20));
      _mm256_storeu_ps(d + 2 * rows, _mm256_permute2f128_ps(s2, s6, 0x20));
      _mm256_storeu_ps(d + 3 * rows, _mm256_permute2f128_ps(s3, s7, 0x20));
      _mm256_storeu_ps(d + 4 * rows, _mm256_permute2f128_ps(s0, s4, 0x31));
      _mm256_storeu_ps(d + 5 * rows, _mm256_permute2f128_ps(s1, s5, 0x31));
      _mm256_storeu_ps(d + 6 * rows, _mm256_permute2f128_ps(s2, s6, 0x31));
      _mm256_storeu_ps(d + 7 * rows, _mm256_permute2f128_ps(s3, s7, 0x31));
    }
}
#endif

}  // namespace lc2wf
