#include "core/gemm.h"

#include <Eigen/Core>
#include <algorithm>

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

// One tile C[r0:r0+rows, c0:c0+cols].
template <class T>
void gemm_tile(bool ta, bool tb, int64_t M, int64_t N, int64_t K, const T* A, int64_t lda, const T* B, int64_t ldb,
               T* C, int64_t ldc, bool accumulate, const T* bias, int64_t r0, int64_t rows, int64_t c0, int64_t cols) {
  MutMap<T> c(C + r0 * ldc + c0, rows, cols, Eigen::OuterStride<>(ldc));
  if (K == 0) {
    if (!accumulate) c.setZero();
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
  parallel_for_work(row_tiles * col_tiles, 1, tile_rows * col_tile * std::max<int64_t>(K, 1), [&](int64_t t0, int64_t t1) {
    for (int64_t t = t0; t < t1; ++t) {
      int64_t rt = t / col_tiles, ct = t % col_tiles;
      int64_t r0 = rt * tile_rows, c0 = ct * col_tile;
      gemm_tile(ta, tb, M, N, K, A, lda, B, ldb, C, ldc, accumulate, bias, r0, std::min(tile_rows, M - r0), c0,
                std::min(col_tile, N - c0));
    }
  });
}

template <class T>
void gemm_serial(bool ta, bool tb, int64_t M, int64_t N, int64_t K, const T* A, int64_t lda, const T* B, int64_t ldb,
                 T* C, int64_t ldc, bool accumulate, const T* bias) {
  if (M == 0 || N == 0) return;
  gemm_tile(ta, tb, M, N, K, A, lda, B, ldb, C, ldc, accumulate, bias, 0, M, 0, N);
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
