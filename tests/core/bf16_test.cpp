// bf16 mixed precision of the GEMM: operands rounded to nearest-even bf16, products summed in fp32, the
// same at any thread count, and only when asked for (double products and the default stay exact fp32).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <random>
#include <stdexcept>
#include <vector>

#include "core/bf16.h"
#include "core/gemm.h"
#include "core/gemm_bf16.h"
#include "core/matmul_precision.h"
#include "core/parallel.h"
#include "random_floats.h"

namespace lc2wf {
namespace {

TEST(Bf16, RoundsToNearestEven) {
  for (float exact : {0.0f, -0.0f, 1.0f, -2.5f, 3.0f * 1024.0f, std::numeric_limits<float>::infinity()})
    EXPECT_EQ(round_to_bf16(exact), exact);
  const float ulp = std::ldexp(1.0f, -7);  // spacing of bf16 values in [1, 2)
  EXPECT_EQ(round_to_bf16(1.0f + ulp / 2), 1.0f) << "a tie goes to the even neighbour (down)";
  EXPECT_EQ(round_to_bf16(1.0f + 3 * ulp / 2), 1.0f + 2 * ulp) << "a tie goes to the even neighbour (up)";
  EXPECT_EQ(round_to_bf16(1.0f + ulp / 2 + std::ldexp(1.0f, -20)), 1.0f + ulp) << "above the tie rounds up";
  EXPECT_EQ(round_to_bf16(-(1.0f + 0.4f * ulp)), -1.0f);
  EXPECT_TRUE(std::isnan(round_to_bf16(std::numeric_limits<float>::quiet_NaN())));
  EXPECT_TRUE(std::isnan(round_to_bf16(std::bit_cast<float>(0x7f800001u)))) << "a NaN with only low bits set";
  EXPECT_EQ(round_to_bf16(std::numeric_limits<float>::max()), std::numeric_limits<float>::infinity());
  std::mt19937 gen(5);
  std::uniform_real_distribution<float> u(-100.0f, 100.0f);
  for (int i = 0; i < 10000; ++i) {
    const float x = u(gen), r = round_to_bf16(x);
    EXPECT_EQ(std::bit_cast<uint32_t>(r) & 0xffffu, 0u);
    EXPECT_LE(std::abs(r - x), std::ldexp(std::abs(x), -8)) << x;  // half a bf16 ulp: 2^-8 relative
  }
}

TEST(Bf16, PrecisionNamesAndErrors) {
  EXPECT_EQ(parse_matmul_precision("bf16", "precision"), MatmulPrecision::kBf16);
  EXPECT_EQ(parse_matmul_precision("fp32", "precision"), MatmulPrecision::kFp32);
  EXPECT_EQ(to_string(MatmulPrecision::kBf16), "bf16");
  // auto follows the CPU: bf16 only where the dot-product instruction makes it faster.
  EXPECT_EQ(parse_matmul_precision("auto", "precision"),
            cpu_has_bf16_dot_product() ? MatmulPrecision::kBf16 : MatmulPrecision::kFp32);
  try {
    parse_matmul_precision("fp16", "config.precision");
    FAIL() << "fp16 accepted";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("config.precision"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("fp16"), std::string::npos) << e.what();
  }
  EXPECT_EQ(matmul_precision(), MatmulPrecision::kFp32) << "fp32 is the default";
}

using test::random_floats;

// C = op(A) op(B) + bias under bf16, against a double product of the bf16-rounded operands (what the
// rounding promises) and against the fp32 product (what it costs), at 1 and 2 threads.
void expect_bf16_product(bool ta, bool tb, int64_t M, int64_t N, int64_t K, bool accumulate) {
  const std::vector<float> A = random_floats(static_cast<size_t>(M * K), 1), B = random_floats(static_cast<size_t>(K * N), 2);
  const std::vector<float> bias = random_floats(static_cast<size_t>(N), 3), C0 = random_floats(static_cast<size_t>(M * N), 4);
  const int64_t lda = ta ? M : K, ldb = tb ? K : N;
  auto a_at = [&](int64_t i, int64_t k) { return ta ? A[k * lda + i] : A[i * lda + k]; };
  auto b_at = [&](int64_t k, int64_t j) { return tb ? B[j * ldb + k] : B[k * ldb + j]; };
  std::vector<float> fp32 = C0;
  gemm(ta, tb, M, N, K, A.data(), lda, B.data(), ldb, fp32.data(), N, accumulate, bias.data());
  MatmulPrecisionGuard bf16(MatmulPrecision::kBf16);
  std::vector<std::vector<float>> results;
  const int before = num_threads();
  for (int threads : {1, 2}) {
    set_num_threads(threads);
    results.push_back(C0);
    gemm(ta, tb, M, N, K, A.data(), lda, B.data(), ldb, results.back().data(), N, accumulate, bias.data());
  }
  set_num_threads(before);
  EXPECT_EQ(std::memcmp(results[0].data(), results[1].data(), results[0].size() * sizeof(float)), 0)
      << "bf16 product differs between 1 and 2 threads";
  double max_rounded = 0, max_vs_fp32 = 0;
  for (int64_t i = 0; i < M; ++i)
    for (int64_t j = 0; j < N; ++j) {
      double exact = 0, magnitude = 0;
      for (int64_t k = 0; k < K; ++k) {
        const double p = double(round_to_bf16(a_at(i, k))) * double(round_to_bf16(b_at(k, j)));
        exact += p;
        magnitude += std::abs(p);
      }
      exact += bias[j] + (accumulate ? C0[i * N + j] : 0.0f);
      const double got = results[0][i * N + j];
      // fp32 summation of K exact products: a few ulps of the sum of magnitudes.
      max_rounded = std::max(max_rounded, std::abs(got - exact) / (magnitude + 1.0));
      max_vs_fp32 = std::max(max_vs_fp32, std::abs(got - fp32[i * N + j]) / (magnitude + 1.0));
    }
  EXPECT_LT(max_rounded, 4e-6) << "M " << M << " N " << N << " K " << K << " ta " << ta << " tb " << tb;
  EXPECT_GT(max_vs_fp32, 1e-5) << "the bf16 path was not taken";
  EXPECT_LT(max_vs_fp32, 1e-2) << "bf16 error beyond its 2^-8 operand rounding";
}

TEST(Bf16, GemmRoundsOperandsAndSumsInFp32) {
  for (bool ta : {false, true})
    for (bool tb : {false, true}) {
      expect_bf16_product(ta, tb, 37, 19, 600, false);  // K spans three chunks
      expect_bf16_product(ta, tb, 300, 45, 70, true);   // several row tiles, accumulate into C
    }
}

// The AVX512-BF16 kernel itself, on shapes that leave partial blocks of rows (8), columns (32), pairs and
// K chunks (256), for every transpose: small integers are exact in bf16 and so is their fp32 sum, so any
// packing or pairing mistake shows as a wrong number; random operands against the rounded double product.
TEST(Bf16, DotProductKernelPacksEveryShapeRight) {
  if (!cpu_has_bf16_dot_product()) GTEST_SKIP() << "this CPU has no AVX512-BF16 (the emulated path is tested above)";
  std::mt19937 rng(11);
  std::uniform_int_distribution<int> small(-8, 8);
  const int64_t shapes[][3] = {{1, 1, 1}, {7, 33, 3}, {9, 31, 257}, {16, 64, 512}, {37, 19, 600}, {8, 32, 2}, {3, 70, 33}};
  for (const auto& s : shapes)
    for (bool ta : {false, true})
      for (bool tb : {false, true})
        for (bool accumulate : {false, true}) {
          const int64_t M = s[0], N = s[1], K = s[2];
          const int64_t lda = (ta ? M : K) + 3, ldb = (tb ? K : N) + 5, ldc = N + 2;  // strides wider than the rows
          std::vector<float> A(static_cast<size_t>((ta ? K : M) * lda)), B(static_cast<size_t>((tb ? N : K) * ldb));
          std::vector<float> C(static_cast<size_t>(M * ldc));
          for (float& x : A) x = static_cast<float>(small(rng));
          for (float& x : B) x = static_cast<float>(small(rng));
          for (float& x : C) x = static_cast<float>(small(rng));
          const std::vector<float> C0 = C;
          gemm_bf16_dot(ta, tb, M, N, K, A.data(), lda, B.data(), ldb, C.data(), ldc, accumulate);
          int64_t wrong = 0;
          for (int64_t i = 0; i < M; ++i)
            for (int64_t j = 0; j < ldc; ++j) {
              const size_t at = static_cast<size_t>(i * ldc + j);
              if (j >= N) {  // outside the product: untouched
                wrong += C[at] != C0[at];
                continue;
              }
              double want = accumulate ? C0[at] : 0.0;
              for (int64_t k = 0; k < K; ++k)
                want += double(ta ? A[k * lda + i] : A[i * lda + k]) * double(tb ? B[j * ldb + k] : B[k * ldb + j]);
              wrong += C[at] != want;
            }
          EXPECT_EQ(wrong, 0) << "M " << M << " N " << N << " K " << K << " ta " << ta << " tb " << tb << " acc " << accumulate;
        }
  // Random operands: rounded to nearest even like round_to_bf16, summed in fp32.
  const std::vector<float> A = random_floats(45 * 300, 21), B = random_floats(300 * 50, 22);
  std::vector<float> C(45 * 50);
  gemm_bf16_dot(false, true, 45, 50, 300, A.data(), 300, B.data(), 300, C.data(), 50, false);
  double worst = 0;
  for (int64_t i = 0; i < 45; ++i)
    for (int64_t j = 0; j < 50; ++j) {
      double want = 0, magnitude = 0;
      for (int64_t k = 0; k < 300; ++k) {
        const double p = double(round_to_bf16(A[i * 300 + k])) * double(round_to_bf16(B[j * 300 + k]));
        want += p;
        magnitude += std::abs(p);
      }
      worst = std::max(worst, std::abs(C[i * 50 + j] - want) / (magnitude + 1.0));
    }
  EXPECT_LT(worst, 4e-6);
  // A NaN operand gives a NaN product, never an infinity or a number.
  std::vector<float> a_nan(2 * 2, 1.0f), b(2 * 2, 1.0f), c(2 * 2);
  a_nan[0] = std::numeric_limits<float>::quiet_NaN();
  gemm_bf16_dot(false, false, 2, 2, 2, a_nan.data(), 2, b.data(), 2, c.data(), 2, false);
  EXPECT_TRUE(std::isnan(c[0]) && std::isnan(c[1]));
  EXPECT_EQ(c[2], 2.0f);
}

// The row tiles of one product (same `product` number) reuse the packed op(B) of the first tile: the
// tiles must equal products made alone, for both layouts of B and with K over several chunks; another
// B under the same number (a column tile) is packed anew.
TEST(Bf16, TilesOfOneProductReuseThePackedWeights) {
  if (!cpu_has_bf16_dot_product()) GTEST_SKIP() << "this CPU has no AVX512-BF16";
  for (const bool tb : {false, true})
    for (const int64_t K : {int64_t{40}, int64_t{600}}) {
      const int64_t M = 20, N = 48, tile = 7;
      const std::vector<float> A = random_floats(static_cast<size_t>(M * K), 31), B = random_floats(static_cast<size_t>(K * N), 32);
      const std::vector<float> B2 = random_floats(static_cast<size_t>(K * N), 33);
      const int64_t ldb = tb ? K : N;
      std::vector<float> alone[2], tiled[2];
      const std::vector<float>* bs[2] = {&B, &B2};
      for (int which = 0; which < 2; ++which) {
        alone[which].resize(static_cast<size_t>(M * N));
        gemm_bf16_dot(false, tb, M, N, K, A.data(), K, bs[which]->data(), ldb, alone[which].data(), N, false);
      }
      // Both Bs under one number, back to back: the second must not take the first one's packing.
      const uint64_t product = 0x5eed0000 + static_cast<uint64_t>(K) + (tb ? 1 : 0);
      for (int which = 0; which < 2; ++which) {
        tiled[which].resize(static_cast<size_t>(M * N));
        for (int64_t r = 0; r < M; r += tile)
          gemm_bf16_dot(false, tb, std::min(tile, M - r), N, K, A.data() + r * K, K, bs[which]->data(), ldb,
                        tiled[which].data() + r * N, N, false, product);
        EXPECT_EQ(tiled[which], alone[which]) << "tb " << tb << " K " << K << (which ? " (second B)" : "");
      }
    }
}

TEST(Bf16, DoubleProductsStayExact) {
  const std::vector<float> af = random_floats(64 * 32, 6), bf = random_floats(32 * 16, 7);
  const std::vector<double> A(af.begin(), af.end()), B(bf.begin(), bf.end());
  std::vector<double> fp64(64 * 16), under_bf16(64 * 16);
  gemm(false, false, 64, 16, 32, A.data(), 32, B.data(), 16, fp64.data(), 16, false);
  MatmulPrecisionGuard bf16(MatmulPrecision::kBf16);
  gemm(false, false, 64, 16, 32, A.data(), 32, B.data(), 16, under_bf16.data(), 16, false);
  EXPECT_EQ(fp64, under_bf16);
}

}  // namespace
}  // namespace lc2wf
