// The tiled, threaded GEMM computes every element as one whole-matrix product would: tiles split rows and
// columns only, so the sum over K (and its rounding) does not depend on the tile size or thread count.
#include "core/gemm.h"

#include <gtest/gtest.h>

#include <cstring>
#include <random>
#include <vector>

#include "core/parallel.h"

namespace lc2wf {
namespace {

std::vector<float> random_floats(size_t n, unsigned seed) {
  std::mt19937 gen(seed);
  std::uniform_real_distribution<float> u(-1.0f, 1.0f);
  std::vector<float> v(n);
  for (float& x : v) x = u(gen);
  return v;
}

// C = op(A) op(B) (+ bias) by the tiled GEMM at `threads` and by one serial product, compared bit for bit.
void expect_tiled_equals_whole(bool ta, bool tb, int64_t M, int64_t N, int64_t K, bool with_bias) {
  const std::vector<float> A = random_floats(static_cast<size_t>(M * K), 1), B = random_floats(static_cast<size_t>(K * N), 2);
  const std::vector<float> bias = random_floats(static_cast<size_t>(N), 3);
  const int64_t lda = ta ? M : K, ldb = tb ? K : N;
  std::vector<float> whole(static_cast<size_t>(M * N)), tiled(static_cast<size_t>(M * N));
  gemm_serial(ta, tb, M, N, K, A.data(), lda, B.data(), ldb, whole.data(), N, false, with_bias ? bias.data() : nullptr);
  const int before = num_threads();
  for (int threads : {1, 2}) {
    set_num_threads(threads);
    gemm(ta, tb, M, N, K, A.data(), lda, B.data(), ldb, tiled.data(), N, false, with_bias ? bias.data() : nullptr);
    EXPECT_EQ(std::memcmp(whole.data(), tiled.data(), whole.size() * sizeof(float)), 0)
        << "M " << M << " N " << N << " K " << K << " ta " << ta << " tb " << tb << " threads " << threads;
  }
  set_num_threads(before);
}

TEST(Gemm, TiledEqualsOneWholeProductBitForBit) {
  // Tall (512-row tiles), medium (128-row tiles), short (column tiles too), the LPT's K of 256 and an odd K.
  for (int64_t M : {int64_t{8192 + 37}, int64_t{1000}, int64_t{300}})
    for (int64_t K : {int64_t{256}, int64_t{7}}) {
      expect_tiled_equals_whole(false, false, M, 256, K, true);
      expect_tiled_equals_whole(false, true, M, 256, K, false);
    }
  expect_tiled_equals_whole(true, false, 256, 256, 8192, false);  // a weight gradient: K is the token count
}

}  // namespace
}  // namespace lc2wf
