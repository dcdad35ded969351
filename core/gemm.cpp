#include "core/gemm.h"

#include <Eigen/Core>
#include <algorithm>
#include <atomic>
#include <type_traits>
#include <vector>

#include "core/bf16.h"
#include "core/blas_backend.h"
#include "core/gemm_bf16.h"
#include "core/matmul_precision.h"
#include "core/parallel.h"

namespace lc2wf {

namespace {

constexpr int64_t kTileRows = 128;
constexpr int64_t kTileCols = 256;
// Every row tile packs all of B again: with tall A (the LPT's 10^5-10^6 token rows) 512-row tiles pack B
// 4x less often (≈ 4 % of a training step). Rows only split; K's blocking and so the rounding are the same.
constexpr int64_t kTallTileRows = 512;

template <class T>
using RowMat = Eigen::Matrix<T, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;
template <class T>
using ConstMap = Eigen::Map<const RowMat<T>, Eigen::Unaligned, Eigen::OuterStride<>>;
template <class T>
using MutMap = Eigen::Map<RowMat<T>, Eigen::Unaligned, Eigen::OuterStride<>>;

// bf16 operands: K is walked in chunks whose slices of op(A) and op(B) are rounded into scratch copies, so
// the extra memory is O(tile x chunk) and the sum over the chunks stays in fp32. The chunking depends only
// on K, so results stay bit-identical at any thread count.
constexpr int64_t kBf16Chunk = 256;

void gemm_tile_bf16(bool ta, bool tb, int64_t K, const float* A, int64_t lda, const float* B, int64_t ldb,
                    MutMap<float>& c, bool accumulate, int64_t r0, int64_t rows, int64_t c0, int64_t cols,
                    uint64_t product) {
  if (cpu_has_bf16_dot_product()) {  // the real instruction; below, its emulation on other CPUs
    gemm_bf16_dot(ta, tb, rows, cols, K, A + (ta ? r0 : r0 * lda), lda, B + (tb ? c0 * ldb : c0), ldb, c.data(),
                  c.outerStride(), accumulate, product);
    return;
  }
  thread_local std::vector<float> a_slice, b_slice;
  for (int64_t k0 = 0; k0 < K; k0 += kBf16Chunk) {
    const int64_t kn = std::min(kBf16Chunk, K - k0);
    a_slice.resize(static_cast<size_t>(rows * kn));
    b_slice.resize(static_cast<size_t>(kn * cols));
    for (int64_t r = 0; r < rows; ++r)  // a_slice[r][k] = op(A)[r0 + r][k0 + k]
      for (int64_t k = 0; k < kn; ++k)
        a_slice[r * kn + k] = round_to_bf16(ta ? A[(k0 + k) * lda + r0 + r] : A[(r0 + r) * lda + k0 + k]);
    for (int64_t k = 0; k < kn; ++k)  // b_slice[k][j] = op(B)[k0 + k][c0 + j]
      for (int64_t j = 0; j < cols; ++j)
        b_slice[k * cols + j] = round_to_bf16(tb ? B[(c0 + j) * ldb + k0 + k] : B[(k0 + k) * ldb + c0 + j]);
    const bool add = k0 > 0 || accumulate;
    if (openblas_sgemm(false, false, rows, cols, kn, a_slice.data(), kn, b_slice.data(), cols, c.data(), c.outerStride(), add))
      continue;
    Eigen::Map<const RowMat<float>> a(a_slice.data(), rows, kn);
    Eigen::Map<const RowMat<float>> b(b_slice.data(), kn, cols);
    if (!add)
      c.noalias() = a * b;
    else
      c.noalias() += a * b;
  }
}

// The tile's product with bf16 operands when that precision is set (float only); false: fp32 as usual.
template <class T>
bool bf16_tile(bool ta, bool tb, int64_t K, const T* A, int64_t lda, const T* B, int64_t ldb, MutMap<T>& c,
               bool accumulate, int64_t r0, int64_t rows, int64_t c0, int64_t cols, uint64_t product) {
  if constexpr (std::is_same_v<T, float>) {
    if (matmul_precision() != MatmulPrecision::kBf16) return false;
    gemm_tile_bf16(ta, tb, K, A, lda, B, ldb, c, accumulate, r0, rows, c0, cols, product);
    return true;
  }
  return false;
}

// The tile's product through OpenBLAS when it is the backend (float only); false leaves it to Eigen.
template <class T>
bool openblas_tile(bool ta, bool tb, int64_t K, const T* A, int64_t lda, const T* B, int64_t ldb, T* C, int64_t ldc,
                   bool accumulate, int64_t r0, int64_t rows, int64_t c0, int64_t cols) {
  if constexpr (std::is_same_v<T, float>)
    return openblas_sgemm(ta, tb, rows, cols, K, A + (ta ? r0 : r0 * lda), lda, B + (tb ? c0 * ldb : c0), ldb,
                          C + r0 * ldc + c0, ldc, accumulate);
  return false;
}

// One tile C[r0:r0+rows, c0:c0+cols] of the product numbered `product` (tiles of one product share it).
template <class T>
void gemm_tile(bool ta, bool tb, int64_t M, int64_t N, int64_t K, const T* A, int64_t lda, const T* B, int64_t ldb,
               T* C, int64_t ldc, bool accumulate, const T* bias, int64_t r0, int64_t rows, int64_t c0, int64_t cols,
               uint64_t product) {
  MutMap<T> c(C + r0 * ldc + c0, rows, cols, Eigen::OuterStride<>(ldc));
  if (K == 0) {
    if (!accumulate) c.setZero();
  } else if (bf16_tile(ta, tb, K, A, lda, B, ldb, c, accumulate, r0, rows, c0, cols, product)) {
    // done with bf16 operands (core/matmul_precision.h)
  } else if (openblas_tile(ta, tb, K, A, lda, B, ldb, C, ldc, accumulate, r0, rows, c0, cols)) {
    // done by OpenBLAS (core/blas_backend.h)
  } else {
    ConstMap<T> a(A, ta ? K : M, ta ? M : K, Eigen::OuterStride<>(lda));
    ConstMap<T> b(B, tb ? N : K, tb ? K : N, Eigen::OuterStride<>(ldb));
    auto run = [&](const auto& ablk, const auto& bblk) {
      if (accumulate)
        c.noalias() += ablk * bblk;
      else
        c.noalias() = ablk * bblk;
    };
    if (!ta && !tb) run(a.middleRows(r0, rows), b.middleCols(c0, cols));
    else if (!ta && tb) run(a.middleRows(r0, rows), b.middleRows(c0, cols).transpose());
    else if (ta && !tb) run(a.middleCols(r0, rows).transpose(), b.middleCols(c0, cols));
    else run(a.middleCols(r0, rows).transpose(), b.middleRows(c0, cols).transpose());
  }
  if (bias) {
    for (int64_t r = 0; r < rows; ++r) {
      T* row = C + (r0 + r) * ldc + c0;
      for (int64_t j = 0; j < cols; ++j) row[j] += bias[c0 + j];
    }
  }
}

// A number per product, never reused: the bf16 kernel keeps a packed op(B) only within one product.
uint64_t next_product() {
  static std::atomic<uint64_t> counter{0};
  return counter.fetch_add(1, std::memory_order_relaxed) + 1;
}

}  // namespace

template <class T>
void gemm(bool ta, bool tb, int64_t M, int64_t N, int64_t K, const T* A, int64_t lda, const T* B, int64_t ldb, T* C,
          int64_t ldc, bool accumulate, const T* bias) {
  if (M == 0 || N == 0) return;
  const int64_t tile_rows = M >= 16 * kTallTileRows ? kTallTileRows : kTileRows;
  int64_t row_tiles = (M + tile_rows - 1) / tile_rows;
  // Few row tiles: also split the columns so both cores get work.
  int64_t col_tile = row_tiles >= 4 ? N : kTileCols;
  int64_t col_tiles = (N + col_tile - 1) / col_tile;
  const uint64_t product = next_product();
  parallel_for_work(row_tiles * col_tiles, 1, tile_rows * col_tile * std::max<int64_t>(K, 1), [&](int64_t t0, int64_t t1) {
    for (int64_t t = t0; t < t1; ++t) {
      int64_t rt = t / col_tiles, ct = t % col_tiles;
      int64_t r0 = rt * tile_rows, c0 = ct * col_tile;
      gemm_tile(ta, tb, M, N, K, A, lda, B, ldb, C, ldc, accumulate, bias, r0, std::min(tile_rows, M - r0), c0,
                std::min(col_tile, N - c0), product);
    }
  });
}

template <class T>
void gemm_serial(bool ta, bool tb, int64_t M, int64_t N, int64_t K, const T* A, int64_t lda, const T* B, int64_t ldb,
                 T* C, int64_t ldc, bool accumulate, const T* bias) {
  if (M == 0 || N == 0) return;
  gemm_tile(ta, tb, M, N, K, A, lda, B, ldb, C, ldc, accumulate, bias, 0, M, 0, N, next_product());
}

template void gemm<float>(bool, bool, int64_t, int64_t, int64_t, const float*, int64_t, const float*, int64_t, float*,
                          int64_t, bool, const float*);
template void gemm<double>(bool, bool, int64_t, int64_t, int64_t, const double*, int64_t, const double*, int64_t,
                           double*, int64_t, bool, const double*);
template void gemm_serial<float>(bool, bool, int64_t, int64_t, int64_t, const float*, int64_t, const float*, int64_t,
                                 float*, int64_t, bool, const float*);
template void gemm_serial<double>(bool, bool, int64_t, int64_t, int64_t, const double*, int64_t, const double*,
                                  int64_t, double*, int64_t, bool, const double*);

}  // namespace lc2wf
