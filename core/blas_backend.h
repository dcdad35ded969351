// The kernel behind one single-threaded fp32 GEMM tile: OpenBLAS (Debian's libopenblas0-pthread, loaded at
// run time, one thread per call) when it runs a kernel of this CPU's class, else Eigen. On the LPT's tile shapes OpenBLAS is
// 1.4-1.5x faster than Eigen's AVX2 kernel (bench/README.md). The kernel class is chosen here from the
// CPU's features, never left to OpenBLAS's own detection, which falls back to SSE3 on CPUs it does not
// know (≈ 6x slower). LC2WF_GEMM=eigen forces Eigen (benchmarks, comparisons).
#pragma once

#include <cstdint>
#include <string>

namespace lc2wf {

// What gemm<float> uses, e.g. "openblas (Haswell)" or "eigen (no libopenblas0-pthread)". Chosen once.
std::string gemm_backend_name();

// C[M x N] (ldc) = op(A) op(B) (+ C when accumulate) through OpenBLAS on the calling thread. Returns
// false, computing nothing, when OpenBLAS is not the backend or a size exceeds its 32-bit indices.
bool openblas_sgemm(bool trans_a, bool trans_b, int64_t M, int64_t N, int64_t K, const float* A, int64_t lda,
                    const float* B, int64_t ldb, float* C, int64_t ldc, bool accumulate);

// The OpenBLAS kernel class for a CPU with these features ("" = none worth using: Eigen).
std::string openblas_core_for(bool avx512_skylake, bool avx2_fma);

// Whether the class OpenBLAS reports after loading (openblas_get_corename) is one of the wanted class's
// speed: the same, or an AVX2/AVX-512 neighbour; never a fallback such as "Prescott".
bool openblas_core_acceptable(const std::string& loaded, const std::string& wanted);

}  // namespace lc2wf
