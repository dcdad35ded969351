// The fused float attention kernel (core/attention_fused.cpp) against the reference kernel, against
// attention composed from the elementary ops (same dropout stream), and against finite differences.
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "core/head_gemm.h"
#include "core/ops.h"
#include "core/parallel.h"
#include "core/rng.h"
#include "tests/core/gradcheck.h"
#include "tests/core/random_floats.h"

namespace lc2wf {
namespace {

// Restores the process-wide kernel choice when a test ends.
struct FusedSwitch {
  explicit FusedSwitch(bool on) : before(fused_attention_enabled()) { set_fused_attention(on); }
  ~FusedSwitch() { set_fused_attention(before); }
  bool before;
};

// Item 0: no key masked; item 1: the last third masked; item 2: every key masked; then alternating.
Tensor padding_mask(int64_t B, int64_t L) {
  std::vector<uint8_t> m(static_cast<size_t>(B * L), 0);
  for (int64_t b = 0; b < B; ++b)
    for (int64_t j = 0; j < L; ++j) {
      const int64_t kind = b % 3;
      m[static_cast<size_t>(b * L + j)] = kind == 2 || (kind == 1 && j >= L - L / 3);
    }
  return Tensor::from_mask(m, {B, L});
}

Tensor rand32(const Shape& s, Rng& rng, double lo = -2, double hi = 2) {
  return test::random_tensor(s, rng, lo, hi, DType::F32);
}

void expect_close(const Tensor& a, const Tensor& b, double tol, const char* what) {
  std::vector<double> x = a.to_vector(), y = b.to_vector();
  ASSERT_EQ(x.size(), y.size()) << what;
  for (size_t i = 0; i < x.size(); ++i)
    ASSERT_NEAR(x[i], y[i], tol * (1 + std::abs(y[i]))) << what << " at " << i;
}

struct AttentionRun {
  Tensor out, grad, weights;
  uint64_t counter;
};

AttentionRun packed_run(const Tensor& qkv_in, int64_t H, const Tensor& mask, double p, const Tensor& seed, bool fused) {
  FusedSwitch use(fused);
  Tensor qkv = qkv_in.detach().clone().set_requires_grad();
  Rng rng(42);
  Tensor weights;
  Tensor out = packed_attention(qkv, H, mask, p, true, rng, &weights);
  out.backward(seed);
  return {out, qkv.grad(), weights, rng.counter()};
}

// L = 32 and 64 take the 16-lane softmax rows on an AVX-512 build, 8 and 24 the 8-lane ones.
TEST(FusedAttention, MatchesTheReferenceKernel) {
  for (int64_t L : {32, 64, 8, 24}) {
    Rng init(static_cast<uint64_t>(L));
    const int64_t B = 7, H = 4, E = 4 * 32;
    Tensor qkv = rand32({B, L, 3 * E}, init), seed = rand32({B, L, E}, init);
    Tensor mask = padding_mask(B, L);
    for (double p : {0.0, 0.5}) {
      AttentionRun fused = packed_run(qkv, H, mask, p, seed, true), ref = packed_run(qkv, H, mask, p, seed, false);
      EXPECT_EQ(fused.counter, ref.counter);
      expect_close(fused.out, ref.out, 1e-5, "output");
      expect_close(fused.grad, ref.grad, 1e-4, "dqkv");
      expect_close(fused.weights, ref.weights, 1e-6, "weights");
      // Item 2 has every key masked: zero output and zero gradient, no NaN.
      std::vector<double> o = fused.out.to_vector(), g = fused.grad.to_vector();
      for (int64_t i = 0; i < L * E; ++i) ASSERT_EQ(o[static_cast<size_t>(2 * L * E + i)], 0.0);
      for (int64_t i = 0; i < L * 3 * E; ++i) ASSERT_EQ(g[static_cast<size_t>(2 * L * 3 * E + i)], 0.0);
    }
  }
}

// Output and q/k/v gradients of separate-q/k/v attention with dropout, fused kernel against the reference.
void expect_fused_matches_reference(int64_t B, int64_t H, int64_t Lq, int64_t Lk, int64_t D, double dropout, uint64_t init_seed,
                                    const std::string& context) {
  Rng init(init_seed);
  Tensor q = rand32({B, H, Lq, D}, init), k = rand32({B, H, Lk, D}, init), v = rand32({B, H, Lk, D}, init);
  Tensor seed = rand32({B, H, Lq, D}, init), mask = padding_mask(B, Lk);
  std::vector<std::vector<double>> results[2];
  for (bool fused : {false, true}) {
    FusedSwitch use(fused);
    Tensor a = q.clone().set_requires_grad(), b = k.clone().set_requires_grad(), c = v.clone().set_requires_grad();
    Rng rng(8);
    Tensor out = scaled_dot_product_attention(a, b, c, mask, dropout, true, rng);
    out.backward(seed);
    results[fused] = {out.to_vector(), a.grad().to_vector(), b.grad().to_vector(), c.grad().to_vector()};
  }
  for (size_t t = 0; t < 4; ++t)
    for (size_t i = 0; i < results[0][t].size(); ++i)
      ASSERT_NEAR(results[1][t][i], results[0][t][i], 1e-4 * (1 + std::abs(results[0][t][i])))
          << context << " tensor " << t << " at " << i;
}

TEST(FusedAttention, SeparateQkvWithDifferentLengthsMatchesTheReferenceKernel) {
  expect_fused_matches_reference(3, 2, 13, 40, 16, 0.3, 5, "Lq=13 Lk=40");
}

// The fused kernel runs the softmax rows in groups of four: query counts with every remainder (and fewer
// rows than one group), and a shared item whose keys are all masked, against the reference kernel.
TEST(FusedAttention, EveryRowGroupRemainderMatchesTheReferenceKernel) {
  for (int64_t Lq : {1, 2, 3, 5, 6, 7, 9})
    expect_fused_matches_reference(3, 2, Lq, 16, 8, 0.5, static_cast<uint64_t>(200 + Lq), "Lq=" + std::to_string(Lq));
}

// Scores of more than 2^16 floats per head go in blocks of query rows (here 272 + 29: a remainder off the
// row groups of four too), in the forward pass of training as in inference.
TEST(FusedAttention, QueryBlocksMatchTheReferenceKernel) {
  expect_fused_matches_reference(2, 2, 301, 240, 16, 0.3, 17, "Lq=301 Lk=240");
}

// A row's scores, softmax and output are the same arithmetic in any block of query rows: the first rows of
// a long query (several blocks, two threads over the heads) have the bits of a short query alone.
TEST(FusedAttention, QueryBlocksChangeNoBit) {
  FusedSwitch use(true);
  Rng init(19);
  const int64_t B = 1, H = 8, Lq = 700, Lk = 400, D = 32;
  Tensor q = rand32({B, H, Lq, D}, init), k = rand32({B, H, Lk, D}, init), v = rand32({B, H, Lk, D}, init);
  NoGradGuard no_grad;
  Rng rng(1);
  const Tensor all = scaled_dot_product_attention(q, k, v, Tensor(), 0.0, false, rng);
  const Tensor first = scaled_dot_product_attention(slice(q, 2, 0, 4), k, v, Tensor(), 0.0, false, rng);
  EXPECT_EQ(slice(all, 2, 0, 4).to_vector(), first.to_vector());
}

// Inference with a key count off the fused kernel's multiple of 8 (the patch encoder over a building's
// pairs): keys padded and masked inside the op, the real keys' result equals the reference kernel's, with
// and without a key mask (item 2 has every key masked), packed and separate q/k/v; 1,001 keys also go in
// blocks of query rows.
TEST(FusedAttention, InferenceWithAnyKeyCountMatchesTheReferenceKernel) {
  for (int64_t L : {1, 13, 30, 61, 1001}) {
    Rng init(static_cast<uint64_t>(300 + L));
    const int64_t B = 3, H = 4, E = 4 * 8;
    const Tensor qkv = rand32({B, L, 3 * E}, init);
    const Tensor q = rand32({B, H, 5, 8}, init), k = rand32({B, H, L, 8}, init), v = rand32({B, H, L, 8}, init);
    for (const Tensor& mask : {Tensor(), padding_mask(B, L)}) {
      std::vector<double> packed[2], separate[2];
      for (bool fused : {false, true}) {
        FusedSwitch use(fused);
        NoGradGuard no_grad;
        Rng rng(3);
        packed[fused] = packed_attention(qkv, H, mask, 0.5, false, rng).to_vector();
        separate[fused] = scaled_dot_product_attention(q, k, v, mask, 0.5, false, rng).to_vector();
      }
      for (size_t i = 0; i < packed[0].size(); ++i) ASSERT_NEAR(packed[1][i], packed[0][i], 1e-5) << "L=" << L << " at " << i;
      for (size_t i = 0; i < separate[0].size(); ++i) ASSERT_NEAR(separate[1][i], separate[0][i], 1e-5) << "L=" << L << " at " << i;
      // The fused kernel rounds differently from the reference one: equal bits would mean it never ran.
      if (L > 1) EXPECT_NE(packed[1], packed[0]) << "L=" << L << ": the padded fused path was not taken";
    }
  }
}

// Attention from the elementary ops with the same dropout draws: dropout() over the (B, H, L, L)
// probabilities reserves the same block of the stream and keys element i the same way.
Tensor unfused_attention(const Tensor& qkv, int64_t H, const Tensor& mask, double p, Rng& rng) {
  const int64_t B = qkv.size(0), L = qkv.size(1), E = qkv.size(2) / 3, D = E / H;
  auto heads = [&](int64_t part) {
    return slice(qkv, 2, part * E, (part + 1) * E).reshape({B, L, H, D}).permute({0, 2, 1, 3});
  };
  Tensor q = heads(0), k = heads(1), v = heads(2);
  Tensor s = matmul(q, k.transpose(-1, -2)) * (1.0 / std::sqrt(static_cast<double>(D)));
  Tensor probs = softmax(masked_fill(s, mask.reshape({B, 1, 1, L}), -1e30), -1);
  // softmax of a fully masked row is uniform; the op defines it as zero.
  std::vector<double> live(static_cast<size_t>(B));
  std::vector<double> m = mask.to(DType::F64).to_vector();
  for (int64_t b = 0; b < B; ++b) {
    live[static_cast<size_t>(b)] = 0;
    for (int64_t j = 0; j < L; ++j) live[static_cast<size_t>(b)] += m[static_cast<size_t>(b * L + j)] == 0;
    live[static_cast<size_t>(b)] = live[static_cast<size_t>(b)] > 0;
  }
  probs = probs * Tensor::from_vector(live, {B, 1, 1, 1}).to(qkv.dtype());
  Tensor out = matmul(dropout(probs, p, true, rng), v);
  return out.permute({0, 2, 1, 3}).reshape({B, L, E});
}

TEST(FusedAttention, MatchesAttentionFromTheElementaryOps) {
  for (int64_t L : {32, 64}) {
    Rng init(static_cast<uint64_t>(100 + L));
    const int64_t B = 6, H = 8, E = 256;
    Tensor qkv = rand32({B, L, 3 * E}, init), seed = rand32({B, L, E}, init);
    Tensor mask = padding_mask(B, L);
    AttentionRun fused = packed_run(qkv, H, mask, 0.5, seed, true);
    Tensor x = qkv.clone().set_requires_grad();
    Rng rng(42);
    Tensor ref = unfused_attention(x, H, mask, 0.5, rng);
    ref.backward(seed);
    EXPECT_EQ(rng.counter(), fused.counter);
    expect_close(fused.out, ref, 1e-5, "output");
    expect_close(fused.grad, x.grad(), 1e-4, "dqkv");
  }
}

// Central differences of the float op along random directions, summed in double: the loss
// sum(out * R) is smooth in qkv for a fixed dropout stream (the mask does not depend on the values).
TEST(FusedAttention, FiniteDifferenceGradient) {
  FusedSwitch use(true);
  Rng init(9);
  const int64_t B = 3, L = 16, H = 2, E = 2 * 8;
  Tensor qkv = rand32({B, L, 3 * E}, init, -1, 1), R = rand32({B, L, E}, init, -1, 1);
  Tensor mask = padding_mask(B, L);
  for (double p : {0.0, 0.5}) {
    auto loss = [&](const Tensor& x) {
      NoGradGuard no_grad;
      Rng rng(3);
      std::vector<double> o = packed_attention(x, H, mask, p, true, rng).to_vector(), r = R.to_vector();
      double s = 0;
      for (size_t i = 0; i < o.size(); ++i) s += o[i] * r[i];
      return s;
    };
    Tensor x = qkv.clone().set_requires_grad();
    Rng rng(3);
    packed_attention(x, H, mask, p, true, rng).backward(R);
    std::vector<double> grad = x.grad().to_vector();
    for (int dir = 0; dir < 6; ++dir) {
      Tensor u = rand32(qkv.shape(), init, -1, 1);
      std::vector<double> uv = u.to_vector();
      const double eps = 1e-2;
      const double fd = (loss(qkv + u * eps) - loss(qkv - u * eps)) / (2 * eps);
      double analytic = 0;
      for (size_t i = 0; i < uv.size(); ++i) analytic += grad[i] * uv[i];
      EXPECT_NEAR(fd, analytic, 3e-4 * (1 + std::abs(analytic))) << "p=" << p << " direction " << dir;
    }
  }
}

TEST(FusedAttention, BitIdenticalAtOneAndTwoThreads) {
  FusedSwitch use(true);
  Rng init(11);
  Tensor qkv = rand32({20, 32, 3 * 256}, init), seed = rand32({20, 32, 256}, init);
  Tensor mask = padding_mask(20, 32);
  std::vector<double> results[2];
  const int before = num_threads();
  for (int threads : {1, 2}) {
    set_num_threads(threads);
    AttentionRun r = packed_run(qkv, 8, mask, 0.5, seed, true);
    results[threads - 1] = r.out.to_vector();
    std::vector<double> g = r.grad.to_vector();
    results[threads - 1].insert(results[threads - 1].end(), g.begin(), g.end());
  }
  set_num_threads(before);
  EXPECT_EQ(results[0], results[1]);
}


#ifdef LC2WF_SIMD256
// C[i][j] as one fmaf chain over k from zero: what every register block of the head products computes,
// so both the AVX-512 and the AVX2 blocks must match it bit for bit (strides wider than the blocks).
std::vector<float> fma_chain_product(bool trans_a, int64_t M, int64_t N, int64_t K, const std::vector<float>& A,
                                     int64_t lda, const std::vector<float>& B, int64_t ldb) {
  std::vector<float> C(static_cast<size_t>(M * N));
  for (int64_t i = 0; i < M; ++i)
    for (int64_t j = 0; j < N; ++j) {
      float c = 0.0f;
      for (int64_t k = 0; k < K; ++k)
        c = std::fmaf(A[static_cast<size_t>(trans_a ? k * lda + i : i * lda + k)], B[static_cast<size_t>(k * ldb + j)], c);
      C[static_cast<size_t>(i * N + j)] = c;
    }
  return C;
}

TEST(HeadGemm, EveryBlockIsOneFmaChainPerElement) {
  int checked = 0;
  for (const bool trans_a : {false, true})
    for (const int64_t M : {1, 2, 5, 7, 8, 11, 12, 13, 32, 64})
      for (const int64_t N : {8, 16, 24, 32, 40, 64, 72})
        for (const int64_t K : {1, 5, 32, 64}) {
          const int64_t lda = (trans_a ? M : K) + 3, ldb = N + 8, ldc = N + 16;
          const std::vector<float> A = test::random_floats(static_cast<size_t>((trans_a ? K : M) * lda), 11);
          const std::vector<float> B = test::random_floats(static_cast<size_t>(K * ldb), 12);
          const std::vector<float> want = fma_chain_product(trans_a, M, N, K, A, lda, B, ldb);
          // The dispatching product (AVX-512 panels where compiled in) and the AVX2 blocks alone.
          for (const bool avx2_only : {false, true}) {
            std::vector<float> C(static_cast<size_t>(M * ldc), -7.0f);
            if (avx2_only && trans_a) head_gemm::columns_avx2<true>(M, 0, N, K, A.data(), lda, B.data(), ldb, C.data(), ldc);
            else if (avx2_only) head_gemm::columns_avx2<false>(M, 0, N, K, A.data(), lda, B.data(), ldb, C.data(), ldc);
            else if (trans_a) head_gemm::gemm_tn(M, N, K, A.data(), lda, B.data(), ldb, C.data(), ldc);
            else head_gemm::gemm_nn(M, N, K, A.data(), lda, B.data(), ldb, C.data(), ldc);
            for (int64_t i = 0; i < M; ++i)
              for (int64_t j = 0; j < ldc; ++j) {
                const float got = C[static_cast<size_t>(i * ldc + j)];
                if (j >= N) {
                  ASSERT_EQ(got, -7.0f) << "wrote past column " << N << " (M " << M << ", K " << K << ")";
                  continue;
                }
                ASSERT_EQ(got, want[static_cast<size_t>(i * N + j)])
                    << (trans_a ? "A^T B" : "A B") << (avx2_only ? " avx2" : "") << " M " << M << " N " << N << " K "
                    << K << " at (" << i << ", " << j << ")";
                ++checked;
              }
          }
        }
  EXPECT_GT(checked, 100000);
}
#endif

}  // namespace
}  // namespace lc2wf
