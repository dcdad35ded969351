// The tiled, threaded GEMM: the same bits at any thread count, the whole product's values, and the kernel
// behind it (OpenBLAS where it runs a kernel of this CPU's class, else Eigen).
#include "core/gemm.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <cstring>
#include <string>
#include <vector>

#include "core/blas_backend.h"
#include "core/parallel.h"
#include "random_floats.h"

namespace lc2wf {
namespace {

using test::random_floats;

// C = op(A) op(B) (+ bias) by the tiled GEMM at 1 and 2 threads (bit for bit: the tiles depend only on M
// and N) and by one serial product: bit for bit with Eigen, whose sum over K does not depend on where an
// element sits in the product; within fp32 rounding with OpenBLAS, whose edge kernels sum in another order.
void expect_tiled_equals_whole(bool ta, bool tb, int64_t M, int64_t N, int64_t K, bool with_bias) {
  const std::vector<float> A = random_floats(static_cast<size_t>(M * K), 1), B = random_floats(static_cast<size_t>(K * N), 2);
  const std::vector<float> bias = random_floats(static_cast<size_t>(N), 3);
  const int64_t lda = ta ? M : K, ldb = tb ? K : N;
  std::vector<float> whole(static_cast<size_t>(M * N));
  std::vector<std::vector<float>> tiled;
  gemm_serial(ta, tb, M, N, K, A.data(), lda, B.data(), ldb, whole.data(), N, false, with_bias ? bias.data() : nullptr);
  const int before = num_threads();
  for (int threads : {1, 2}) {
    set_num_threads(threads);
    tiled.emplace_back(static_cast<size_t>(M * N));
    gemm(ta, tb, M, N, K, A.data(), lda, B.data(), ldb, tiled.back().data(), N, false, with_bias ? bias.data() : nullptr);
  }
  set_num_threads(before);
  const std::string where = "M " + std::to_string(M) + " N " + std::to_string(N) + " K " + std::to_string(K) +
                            " ta " + std::to_string(ta) + " tb " + std::to_string(tb);
  EXPECT_EQ(std::memcmp(tiled[0].data(), tiled[1].data(), whole.size() * sizeof(float)), 0) << "1 vs 2 threads, " << where;
  if (gemm_backend_name().rfind("eigen", 0) == 0) {
    EXPECT_EQ(std::memcmp(whole.data(), tiled[0].data(), whole.size() * sizeof(float)), 0) << where;
    return;
  }
  double worst = 0;  // |difference| / (sqrt(K) * 2^-23), operands in [-1, 1]: a few roundings of the sum
  for (size_t i = 0; i < whole.size(); ++i)
    worst = std::max(worst, std::abs(double(whole[i]) - tiled[0][i]) / (std::sqrt(double(K)) * std::ldexp(1.0, -23)));
  EXPECT_LT(worst, 64.0) << where;
}

TEST(Gemm, TiledMatchesOneWholeProduct) {
  // Tall (512-row tiles), medium (128-row tiles), short (column tiles too), the LPT's K of 256 and an odd K.
  for (int64_t M : {int64_t{8192 + 37}, int64_t{1000}, int64_t{300}})
    for (int64_t K : {int64_t{256}, int64_t{7}}) {
      expect_tiled_equals_whole(false, false, M, 256, K, true);
      expect_tiled_equals_whole(false, true, M, 256, K, false);
    }
  expect_tiled_equals_whole(true, false, 256, 256, 8192, false);  // a weight gradient: K is the token count
}

TEST(Gemm, OpenBlasKernelClassComesFromTheCpuNotFromOpenBlas) {
  EXPECT_EQ(openblas_core_for(true, true), "SkylakeX");
  EXPECT_EQ(openblas_core_for(false, true), "Haswell");
  EXPECT_EQ(openblas_core_for(false, false), "");
  EXPECT_TRUE(openblas_core_acceptable("Haswell", "Haswell"));
  EXPECT_TRUE(openblas_core_acceptable("Zen", "Haswell"));
  EXPECT_TRUE(openblas_core_acceptable("Haswell", "SkylakeX"));
  EXPECT_TRUE(openblas_core_acceptable("SKYLAKEX", "SkylakeX"));
  EXPECT_FALSE(openblas_core_acceptable("Prescott", "Haswell")) << "OpenBLAS's fallback on CPUs it does not know";
  EXPECT_FALSE(openblas_core_acceptable("Prescott", "SkylakeX"));
  EXPECT_FALSE(openblas_core_acceptable("SkylakeX", "Haswell")) << "an AVX-512 kernel on a CPU without AVX-512";
  EXPECT_FALSE(openblas_core_acceptable("", "Haswell"));
}

TEST(Gemm, UsesOpenBlasWhereItIsInstalledAndTheCpuHasAvx2) {
  const std::string name = gemm_backend_name();
  std::printf("gemm backend: %s\n", name.c_str());
  const bool installed = std::filesystem::exists("/usr/lib/x86_64-linux-gnu/openblas-pthread/libopenblas.so.0");
  const bool forced_eigen = std::getenv("LC2WF_GEMM") && std::string(std::getenv("LC2WF_GEMM")) == "eigen";
#if defined(__x86_64__) && defined(__GNUC__)
  if (installed && !forced_eigen && __builtin_cpu_supports("avx2") && __builtin_cpu_supports("fma"))
    EXPECT_EQ(name.rfind("openblas", 0), 0u) << "tools/setup-deps.sh installs libopenblas0-pthread; got " << name;
#endif
  if (name.rfind("openblas", 0) != 0) GTEST_SKIP() << name;
  // Its products against a double reference, every transpose, accumulate on and off.
  const int64_t M = 67, N = 45, K = 300;
  const std::vector<float> A = random_floats(M * K, 8), B = random_floats(K * N, 9), C0 = random_floats(M * N, 10);
  for (bool ta : {false, true})
    for (bool tb : {false, true})
      for (bool accumulate : {false, true}) {
        std::vector<float> C = C0;
        const int64_t lda = ta ? M : K, ldb = tb ? K : N;
        ASSERT_TRUE(openblas_sgemm(ta, tb, M, N, K, A.data(), lda, B.data(), ldb, C.data(), N, accumulate));
        double worst = 0;
        for (int64_t i = 0; i < M; ++i)
          for (int64_t j = 0; j < N; ++j) {
            double ref = accumulate ? C0[i * N + j] : 0.0;
            for (int64_t k = 0; k < K; ++k)
              ref += double(ta ? A[k * lda + i] : A[i * lda + k]) * double(tb ? B[j * ldb + k] : B[k * ldb + j]);
            worst = std::max(worst, std::abs(ref - C[i * N + j]));
          }
        EXPECT_LT(worst, 1e-4) << "ta " << ta << " tb " << tb << " accumulate " << accumulate;
      }
}

// Many small products at once from the pool's threads, each against the same product made alone: a
// kernel library that shares scratch buffers between concurrent callers (OpenBLAS's single-threaded
// build: ≈ 0.7 % of such products wrong) fails here.
TEST(Gemm, ConcurrentProductsEqualTheSameProductsMadeAlone) {
  struct Case {
    bool ta, tb;
    int64_t M, N, K;
  };
  const std::vector<Case> cases{{false, true, 64, 64, 64}, {true, false, 32, 64, 128}, {false, false, 48, 32, 96}, {false, true, 40, 72, 64}};
  std::vector<std::vector<float>> A, B, alone;
  for (size_t c = 0; c < cases.size(); ++c) {
    const Case& k = cases[c];
    A.push_back(random_floats(static_cast<size_t>(k.M * k.K), 20 + c));
    B.push_back(random_floats(static_cast<size_t>(k.K * k.N), 30 + c));
    alone.emplace_back(static_cast<size_t>(k.M * k.N));
    gemm_serial(k.ta, k.tb, k.M, k.N, k.K, A[c].data(), k.ta ? k.M : k.K, B[c].data(), k.tb ? k.K : k.N, alone[c].data(), k.N, false);
  }
  const int before = num_threads();
  set_num_threads(2);
  constexpr int64_t kProducts = 40000;
  std::vector<int> wrong(kProducts, 0);
  parallel_for(kProducts, 1000, [&](int64_t p0, int64_t p1) {
    std::vector<float> C;
    for (int64_t p = p0; p < p1; ++p) {
      // Neighbouring chunks (the ones running at the same time) are a case apart: shared scratch then mixes
      // different products instead of writing the same values twice.
      const size_t c = static_cast<size_t>(p + p / 1000) % cases.size();
      const Case& k = cases[c];
      C.assign(alone[c].size(), 0.0f);
      gemm_serial(k.ta, k.tb, k.M, k.N, k.K, A[c].data(), k.ta ? k.M : k.K, B[c].data(), k.tb ? k.K : k.N, C.data(), k.N, false);
      wrong[p] = std::memcmp(C.data(), alone[c].data(), C.size() * sizeof(float)) != 0;
    }
  });
  set_num_threads(before);
  EXPECT_EQ(std::count(wrong.begin(), wrong.end(), 1), 0) << "of " << kProducts << " products with " << gemm_backend_name();
}

}  // namespace
}  // namespace lc2wf
