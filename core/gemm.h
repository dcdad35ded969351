// Deterministic threaded GEMM: the output is cut into fixed tiles that depend only on (M, N), and each tile
// is one single-threaded Eigen product, so results are bit-identical at any thread count. Float products
// round their operands to bf16 when core/matmul_precision.h says so (double never: gradient checks).
#pragma once

#include <cstdint>

namespace lc2wf {

// C[M x N] (row stride ldc) = op(A) op(B) (+ C when accumulate) (+ bias[col] when bias != nullptr).
// op(A) is M x K: A is row-major M x K (lda) or, when trans_a, K x M. op(B) likewise K x N or N x K.
template <class T>
void gemm(bool trans_a, bool trans_b, int64_t M, int64_t N, int64_t K, const T* A, int64_t lda, const T* B,
          int64_t ldb, T* C, int64_t ldc, bool accumulate, const T* bias = nullptr);

// The same product on one thread (for callers that already parallelise over a batch).
template <class T>
void gemm_serial(bool trans_a, bool trans_b, int64_t M, int64_t N, int64_t K, const T* A, int64_t lda, const T* B,
                 int64_t ldb, T* C, int64_t ldc, bool accumulate, const T* bias = nullptr);

}  // namespace lc2wf
