// bf16 matrix products on the AVX512-BF16 dot product (vdpbf16ps): twice the multiply-adds per instruction
// of an fp32 FMA. Operands are rounded to bf16 while they are packed (nearest even, as round_to_bf16;
// denormals become zero) and the products are summed in fp32, so the result is what the emulated bf16 path
// computes up to the order of the fp32 additions.
#pragma once

#include <cstdint>

namespace lc2wf {

// C = op(A) op(B) (accumulate: C += ...), C row-major M x N with row stride ldc; op(A)[i][k] is
// A[k * lda + i] when ta, else A[i * lda + k] (op(B) likewise). K is summed in chunks whose length depends
// only on K, so the result is the same for any split of C into tiles. Only callable where
// cpu_has_bf16_dot_product() (core/matmul_precision.h) is true. Calls that pass the same nonzero `product`
// (the row tiles of one product, made by one thread) and the same B, N and K reuse the packed op(B) of the
// first when it is small (a Linear layer's weights), instead of packing it again; 0 never reuses.
void gemm_bf16_dot(bool ta, bool tb, int64_t M, int64_t N, int64_t K, const float* A, int64_t lda, const float* B,
                   int64_t ldb, float* C, int64_t ldc, bool accumulate, uint64_t product = 0);

}  // namespace lc2wf
