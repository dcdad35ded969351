// Forward values against hand-computed or closed-form results, and stability at extreme logits.
#include <gtest/gtest.h>

#include <cmath>

#include "core/ops.h"
#include "tests/core/gradcheck.h"

namespace lc2wf {
namespace {

std::vector<double> vals(const Tensor& t) { return t.to_vector(); }

void expect_near(const std::vector<double>& got, const std::vector<double>& want, double tol = 1e-6) {
  ASSERT_EQ(got.size(), want.size());
  for (size_t i = 0; i < got.size(); ++i) EXPECT_NEAR(got[i], want[i], tol) << "element " << i;
}

bool all_finite(const Tensor& t) {
  for (double v : t.to_vector())
    if (!std::isfinite(v)) return false;
  return true;
}

TEST(Forward, BroadcastArithmetic) {
  Tensor a = Tensor::from_vector(std::vector<float>{1, 2, 3, 4, 5, 6}, {2, 3});
  Tensor b = Tensor::from_vector(std::vector<float>{10, 20, 30}, {3});
  Tensor c = Tensor::from_vector(std::vector<float>{2, 4}, {2, 1});
  expect_near(vals(a + b), {11, 22, 33, 14, 25, 36});
  expect_near(vals(a * c), {2, 4, 6, 16, 20, 24});
  expect_near(vals(a / c - 1.0), {-0.5, 0, 0.5, 0, 0.25, 0.5});
  expect_near(vals(10.0 / a), {10, 5, 10.0 / 3, 2.5, 2, 10.0 / 6});
  EXPECT_EQ((a + b).shape(), (Shape{2, 3}));
  EXPECT_EQ(broadcast_shapes({2, 1, 4}, {3, 1}), (Shape{2, 3, 4}));
}

TEST(Forward, UnaryValues) {
  Tensor a = Tensor::from_vector(std::vector<double>{-2, -0.5, 0.5, 2}, {4});
  expect_near(vals(relu(a)), {0, 0, 0.5, 2});
  expect_near(vals(abs(a)), {2, 0.5, 0.5, 2});
  expect_near(vals(sigmoid(a)), {1 / (1 + std::exp(2.0)), 1 / (1 + std::exp(0.5)), 1 / (1 + std::exp(-0.5)), 1 / (1 + std::exp(-2.0))});
  expect_near(vals(tanh(a)), {std::tanh(-2.0), std::tanh(-0.5), std::tanh(0.5), std::tanh(2.0)});
  expect_near(vals(pow(abs(a), 3.0)), {8, 0.125, 0.125, 8});
  expect_near(vals(sqrt(abs(a))), {std::sqrt(2.0), std::sqrt(0.5), std::sqrt(0.5), std::sqrt(2.0)});
  expect_near(vals(log(exp(a))), {-2, -0.5, 0.5, 2});
}

TEST(Forward, Reductions) {
  Tensor a = Tensor::from_vector(std::vector<float>{1, 5, 3, 4, 2, 6}, {2, 3});
  EXPECT_DOUBLE_EQ(sum(a).item(), 21);
  EXPECT_EQ(sum(a).shape(), Shape{});
  expect_near(vals(sum(a, {0})), {5, 7, 9});
  EXPECT_EQ(sum(a, {1}, true).shape(), (Shape{2, 1}));
  expect_near(vals(mean(a, {1})), {3, 4});
  expect_near(vals(max(a, {1})), {5, 6});
  expect_near(vals(min(a, {0}, true)), {1, 2, 3});
  EXPECT_EQ(min(a, {0}, true).shape(), (Shape{1, 3}));
  EXPECT_DOUBLE_EQ(mean(a).item(), 3.5);
}

TEST(Forward, LargeSumIsAccurate) {
  Tensor a = Tensor::full({1 << 20}, 0.1, DType::F32);
  EXPECT_NEAR(sum(a).item(), 0.1 * (1 << 20), 1.0);
}

TEST(Forward, MatmulAndLinear) {
  Tensor a = Tensor::from_vector(std::vector<float>{1, 2, 3, 4, 5, 6}, {2, 3});
  Tensor b = Tensor::from_vector(std::vector<float>{1, 0, 0, 1, 1, 1}, {3, 2});
  expect_near(vals(matmul(a, b)), {4, 5, 10, 11});
  Tensor bias = Tensor::from_vector(std::vector<float>{100, 200}, {2});
  Tensor w = Tensor::from_vector(std::vector<float>{1, 0, 1, 0, 1, 0}, {2, 3});
  expect_near(vals(linear(a, w, bias)), {104, 202, 110, 205});
  // Batched with broadcast batch dims equals per-item products.
  Rng rng(1);
  Tensor x = test::random_tensor({2, 1, 3, 4}, rng), y = test::random_tensor({5, 4, 2}, rng);
  Tensor z = matmul(x, y);
  ASSERT_EQ(z.shape(), (Shape{2, 5, 3, 2}));
  for (int64_t i = 0; i < 2; ++i)
    for (int64_t j = 0; j < 5; ++j) {
      Tensor xi = slice(x, 0, i, i + 1).reshape({3, 4});
      Tensor yj = slice(y, 0, j, j + 1).reshape({4, 2});
      Tensor zij = slice(slice(z, 0, i, i + 1), 1, j, j + 1).reshape({3, 2});
      expect_near(vals(zij), vals(matmul(xi, yj)), 1e-12);
    }
}

TEST(Forward, LargeGemmMatchesNaive) {
  Rng rng(5);
  Tensor a = test::random_tensor({300, 70}, rng, -1, 1, DType::F32);
  Tensor w = test::random_tensor({520, 70}, rng, -1, 1, DType::F32);
  Tensor y = linear(a, w);
  const float* pa = a.data<float>();
  const float* pw = w.data<float>();
  const float* py = y.data<float>();
  for (int64_t i = 0; i < 300; i += 37)
    for (int64_t j = 0; j < 520; j += 13) {
      double s = 0;
      for (int64_t k = 0; k < 70; ++k) s += double(pa[i * 70 + k]) * pw[j * 70 + k];
      EXPECT_NEAR(py[i * 520 + j], s, 1e-4);
    }
}

TEST(Forward, SmallKLinearMatchesNaive) {  // the first MLP layer's shape takes a dedicated kernel
  Rng rng(6);
  for (int64_t out : {64, 20}) {
    Tensor a = test::random_tensor({1000, 7}, rng, -1, 1, DType::F32);
    Tensor w = test::random_tensor({out, 7}, rng, -1, 1, DType::F32);
    Tensor b = test::random_tensor({out}, rng, -1, 1, DType::F32);
    Tensor y = linear(a, w, b);
    const float* pa = a.data<float>();
    const float* pw = w.data<float>();
    const float* py = y.data<float>();
    for (int64_t i = 0; i < 1000; i += 7)
      for (int64_t j = 0; j < out; ++j) {
        double s = b.data<float>()[j];
        for (int64_t k = 0; k < 7; ++k) s += double(pa[i * 7 + k]) * pw[j * 7 + k];
        EXPECT_NEAR(py[i * out + j], s, 1e-5);
      }
  }
}

TEST(Forward, ShapeOps) {
  Tensor a = Tensor::from_vector(std::vector<float>{0, 1, 2, 3, 4, 5}, {2, 3});
  expect_near(vals(a.transpose(0, 1)), {0, 3, 1, 4, 2, 5});
  expect_near(vals(concat({a, a}, 0)), {0, 1, 2, 3, 4, 5, 0, 1, 2, 3, 4, 5});
  expect_near(vals(concat({a, a}, 1)), {0, 1, 2, 0, 1, 2, 3, 4, 5, 3, 4, 5});
  EXPECT_EQ(stack({a, a, a}, 0).shape(), (Shape{3, 2, 3}));
  expect_near(vals(slice(a, 1, -2, 3)), {1, 2, 4, 5});
  expect_near(vals(slice(a, 1, 0, 3, 2)), {0, 2, 3, 5});
  Tensor idx = Tensor::from_vector(std::vector<int64_t>{2, 2, 0}, {3});
  expect_near(vals(index_select(a, 1, idx)), {2, 2, 0, 5, 5, 3});
  Tensor gi = Tensor::from_vector(std::vector<int64_t>{2, 0, 1, 1}, {2, 2});
  expect_near(vals(gather(a, 1, gi)), {2, 0, 4, 4});
  expect_near(vals(repeat(Tensor::from_vector(std::vector<float>{1, 2}, {2}), {2, 2})), {1, 2, 1, 2, 1, 2, 1, 2});
  expect_near(vals(expand(Tensor::from_vector(std::vector<float>{7, 8}, {2, 1}), {2, 3})), {7, 7, 7, 8, 8, 8});
  // reshape aliases storage: a write through one handle shows through the other.
  Tensor r = a.reshape({3, 2});
  r.data<float>()[0] = 42;
  EXPECT_EQ(a.data<float>()[0], 42);
  EXPECT_EQ(a.reshape({-1, 2}).shape(), (Shape{3, 2}));
}

TEST(Forward, MaskedFillAndWhere) {
  Tensor a = Tensor::from_vector(std::vector<float>{1, 2, 3, 4}, {2, 2});
  Tensor m = Tensor::from_mask({1, 0}, {2});
  expect_near(vals(masked_fill(a, m, -9)), {-9, 2, -9, 4});
  Tensor b = Tensor::full({2, 2}, 0.5);
  expect_near(vals(where(m, a, b)), {1, 0.5, 3, 0.5});
}

TEST(Forward, SoftmaxStableAtHugeLogits) {
  Tensor a = Tensor::from_vector(std::vector<float>{1e4f, -1e4f, 0, 1e4f, 1e4f, -1e4f}, {2, 3});
  Tensor s = softmax(a, -1);
  EXPECT_TRUE(all_finite(s));
  expect_near(vals(s), {1, 0, 0, 0.5, 0.5, 0});
  Tensor ls = log_softmax(a, -1);
  EXPECT_TRUE(all_finite(ls));
  expect_near(vals(ls), {0, -2e4, -1e4, -std::log(2.0), -std::log(2.0), -2e4 - std::log(2.0)}, 1e-2);
  expect_near(vals(softmax(Tensor::from_vector(std::vector<float>{0, std::log(3.0f)}, {2}), 0)), {0.25, 0.75});
}

TEST(Forward, CrossEntropyValuesAndStability) {
  Tensor logits = Tensor::from_vector(std::vector<double>{0, 0, std::log(2.0), 1e4, -1e4, 0}, {2, 3});
  Tensor target = Tensor::from_vector(std::vector<int64_t>{2, 1}, {2});
  // Row 0: p(2) = 2/4 -> nll = log 2; row 1: nll = 2e4.
  Tensor none = cross_entropy(logits, target, Tensor(), -100, Reduction::None);
  expect_near(vals(none), {std::log(2.0), 2e4});
  Tensor w = Tensor::from_vector(std::vector<double>{1, 3, 1}, {3});
  EXPECT_NEAR(cross_entropy(logits, target, w).item(), (std::log(2.0) + 3 * 2e4) / 4, 1e-9);
  Tensor ignored = Tensor::from_vector(std::vector<int64_t>{2, -100}, {2});
  EXPECT_NEAR(cross_entropy(logits, ignored).item(), std::log(2.0), 1e-12);
  Tensor all_ignored = Tensor::from_vector(std::vector<int64_t>{-1, -1}, {2});
  Tensor l = logits.clone().set_requires_grad();
  Tensor loss = cross_entropy(l, all_ignored, Tensor(), -1);
  EXPECT_EQ(loss.item(), 0.0);
  loss.backward();
  EXPECT_TRUE(all_finite(l.grad()));
  // F32 at +-1e4.
  Tensor lf = logits.to(DType::F32).set_requires_grad();
  Tensor cf = cross_entropy(lf, target);
  cf.backward();
  EXPECT_TRUE(std::isfinite(cf.item()));
  EXPECT_TRUE(all_finite(lf.grad()));
}

TEST(Forward, BceWithLogitsStable) {
  Tensor x = Tensor::from_vector(std::vector<float>{1e4f, -1e4f, 1e4f, -1e4f, 0.0f, 2.0f}, {6});
  Tensor y = Tensor::from_vector(std::vector<float>{1, 0, 0, 1, 1, 0}, {6});
  Tensor xl = x.clone().set_requires_grad();
  Tensor l = bce_with_logits(xl, y, Reduction::None);
  expect_near(vals(l), {0, 0, 1e4, 1e4, std::log(2.0), 2 + std::log1p(std::exp(-2.0))}, 1e-3);
  sum(l).backward();
  EXPECT_TRUE(all_finite(xl.grad()));
  expect_near(vals(xl.grad()), {0, 0, 1, -1, -0.5, 1 / (1 + std::exp(-2.0))}, 1e-6);
  EXPECT_TRUE(all_finite(sigmoid(x)));
}

TEST(Forward, L1AndMse) {
  Tensor a = Tensor::from_vector(std::vector<float>{1, 2, 3}, {3});
  Tensor b = Tensor::from_vector(std::vector<float>{2, 2, 5}, {3});
  EXPECT_NEAR(l1_loss(a, b).item(), 1.0, 1e-6);
  EXPECT_NEAR(mse_loss(a, b, Reduction::Sum).item(), 5.0, 1e-6);
}

TEST(Forward, LayerNormValues) {
  Tensor x = Tensor::from_vector(std::vector<double>{1, 2, 3, 4, 10, 10, 10, 10}, {2, 4});
  Tensor w = Tensor::full({4}, 2.0, DType::F64), b = Tensor::full({4}, 1.0, DType::F64);
  Tensor y = layer_norm(x, w, b, 0.0 + 1e-12);
  double s = std::sqrt(1.25);
  expect_near(vals(y), {1 - 3 / s, 1 - 1 / s, 1 + 1 / s, 1 + 3 / s, 1, 1, 1, 1}, 1e-6);
}

TEST(Forward, BatchNormRunningStatsAndEval) {
  Tensor x = Tensor::from_vector(std::vector<double>{1, 10, 3, 20, 5, 30}, {3, 2});
  Tensor rm = Tensor::zeros({2}, DType::F64), rv = Tensor::ones({2}, DType::F64);
  Tensor y = batch_norm(x, Tensor(), Tensor(), rm, rv, true, 0.1, 0.0);
  double s0 = std::sqrt(8.0 / 3), s1 = std::sqrt(200.0 / 3);
  expect_near(vals(y), {-2 / s0, -10 / s1, 0, 0, 2 / s0, 10 / s1}, 1e-9);
  // Running variance uses the unbiased estimate, like PyTorch.
  expect_near(vals(rm), {0.3, 2.0}, 1e-12);
  expect_near(vals(rv), {0.9 + 0.1 * 4, 0.9 + 0.1 * 100}, 1e-12);
  Tensor ye = batch_norm(x, Tensor(), Tensor(), rm, rv, false, 0.1, 0.0);
  expect_near(vals(ye), {(1 - 0.3) / std::sqrt(1.3), (10 - 2) / std::sqrt(10.9), (3 - 0.3) / std::sqrt(1.3),
                         (20 - 2) / std::sqrt(10.9), (5 - 0.3) / std::sqrt(1.3), (30 - 2) / std::sqrt(10.9)},
              1e-9);
  expect_near(vals(rm), {0.3, 2.0}, 1e-12);  // eval leaves the buffers alone
}

TEST(Forward, DropoutRateScaleAndEval) {
  Rng rng(3);
  Tensor a = Tensor::ones({100000});
  Tensor d = dropout(a, 0.25, true, rng);
  std::vector<double> v = vals(d);
  int64_t kept = 0;
  for (double x : v) {
    ASSERT_TRUE(x == 0.0 || std::abs(x - 1 / 0.75) < 1e-6);
    kept += x != 0.0;
  }
  EXPECT_NEAR(kept / 100000.0, 0.75, 0.01);
  EXPECT_EQ(rng.counter(), 100000u);
  Tensor e = dropout(a, 0.25, false, rng);
  EXPECT_EQ(e.impl(), a.impl());
  EXPECT_EQ(rng.counter(), 100000u);
}

// Reference attention from the elementary ops.
Tensor reference_attention(const Tensor& q, const Tensor& k, const Tensor& v, const Tensor& mask) {
  double scale = 1.0 / std::sqrt(static_cast<double>(q.size(-1)));
  Tensor s = matmul(q, k.transpose(-1, -2)) * scale;
  int64_t B = q.size(0), L = k.size(2);
  Tensor m4 = mask.reshape({B, 1, 1, L});
  Tensor p = softmax(masked_fill(s, m4, -1e30), -1);
  return matmul(p, v);
}

TEST(Forward, AttentionMatchesReferenceAndZeroesMaskedRows) {
  Rng rng(9);
  int64_t B = 3, H = 2, L = 5, D = 4;
  Tensor q = test::random_tensor({B, H, L, D}, rng), k = test::random_tensor({B, H, L, D}, rng),
         v = test::random_tensor({B, H, L, D}, rng);
  Tensor mask = Tensor::from_mask({0, 0, 0, 1, 1, 1, 1, 1, 1, 1, 0, 0, 0, 0, 0}, {B, L});
  Rng r(1);
  Tensor attn;
  Tensor out = scaled_dot_product_attention(q, k, v, mask, 0.0, false, r, &attn);
  Tensor ref = reference_attention(q, k, v, mask);
  std::vector<double> o = vals(out), rf = vals(ref);
  for (int64_t b = 0; b < B; ++b)
    for (int64_t i = 0; i < H * L * D; ++i) {
      double want = b == 1 ? 0.0 : rf[b * H * L * D + i];  // item 1: every key masked -> zeros
      EXPECT_NEAR(o[b * H * L * D + i], want, 1e-12);
    }
  ASSERT_EQ(attn.shape(), (Shape{B, L, L}));
  std::vector<double> w = vals(attn);
  for (int64_t i = 0; i < L; ++i) {
    double row = 0;
    for (int64_t j = 0; j < L; ++j) row += w[i * L + j];
    EXPECT_NEAR(row, 1.0, 1e-12);
    EXPECT_EQ(w[i * L + 3], 0.0);
  }
  // The packed layout gives the same numbers.
  Tensor qkv = concat({q.permute({0, 2, 1, 3}).reshape({B, L, H * D}), k.permute({0, 2, 1, 3}).reshape({B, L, H * D}),
                       v.permute({0, 2, 1, 3}).reshape({B, L, H * D})},
                      2);
  Tensor packed = packed_attention(qkv, H, mask, 0.0, false, r);
  expect_near(vals(packed), vals(out.permute({0, 2, 1, 3}).reshape({B, L, H * D})), 1e-12);
}

TEST(Forward, AttentionDropoutIsDeterministicPerStreamState) {
  Rng rng(2);
  Tensor qkv = test::random_tensor({2, 8, 24}, rng);
  Rng a(5), b(5), c(6);
  Tensor x = packed_attention(qkv, 4, Tensor(), 0.5, true, a);
  Tensor y = packed_attention(qkv, 4, Tensor(), 0.5, true, b);
  Tensor z = packed_attention(qkv, 4, Tensor(), 0.5, true, c);
  EXPECT_EQ(vals(x), vals(y));
  EXPECT_NE(vals(x), vals(z));
  EXPECT_EQ(a.counter(), 2u * 4 * 8 * 8);
}

}  // namespace
}  // namespace lc2wf

namespace lc2wf {
namespace {

// The F32 kernels (vectorised exp, register transposes, fixed-size head products) against the F64 path.
TEST(Forward, AttentionF32KernelsMatchF64ForwardAndBackward) {
  for (int64_t L : {32, 64, 13}) {
    Rng rng(static_cast<uint64_t>(L));
    int64_t B = 3, H = 4, E = 128;
    Tensor qkv64 = test::random_tensor({B, L, 3 * E}, rng, -2, 2);
    std::vector<uint8_t> m(static_cast<size_t>(B * L), 0);
    for (int64_t j = L / 2; j < L; ++j) m[static_cast<size_t>(L + j)] = 1;  // item 1: half the keys masked
    for (int64_t j = 0; j < L; ++j) m[static_cast<size_t>(2 * L + j)] = 1;  // item 2: every key masked
    Tensor mask = Tensor::from_mask(m, {B, L});
    Tensor seed64 = test::random_tensor({B, L, E}, rng);
    Tensor q64 = qkv64.clone().set_requires_grad();
    Tensor q32 = qkv64.to(DType::F32).set_requires_grad();
    Rng r64(4), r32(4);
    Tensor o64 = packed_attention(q64, H, mask, 0.2, true, r64);
    Tensor o32 = packed_attention(q32, H, mask, 0.2, true, r32);
    o64.backward(seed64);
    o32.backward(seed64.to(DType::F32));
    expect_near(vals(o32), vals(o64), 2e-5);
    expect_near(vals(q32.grad()), vals(q64.grad()), 2e-4);
  }
}

TEST(Forward, SoftmaxF32MatchesF64) {
  Rng rng(12);
  for (int64_t R : {32, 64, 7}) {
    Tensor x = test::random_tensor({5, R}, rng, -30, 30);
    expect_near(vals(softmax(x.to(DType::F32), -1)), vals(softmax(x, -1)), 1e-6);
    expect_near(vals(log_softmax(x.to(DType::F32), -1)), vals(log_softmax(x, -1)), 1e-4);
  }
}

}  // namespace
}  // namespace lc2wf

namespace lc2wf {
namespace {

// The float attention rows of 32 and 64 keys take a vectorised path; the double path is the plain loop
// that the gradient checks cover. Same inputs, mask and dropout stream: outputs and gradients agree.
TEST(Forward, FloatAttentionRowsMatchTheDoublePath) {
  for (int64_t L : {32, 64}) {
    Rng init(L);
    Tensor x64 = test::random_tensor({6, L, 3 * 32}, init, -2, 2);
    std::vector<uint8_t> m(static_cast<size_t>(6 * L));
    for (size_t i = 0; i < m.size(); ++i) m[i] = (i % L) >= static_cast<size_t>(L / 2 + (i / L) * 3) || (i / L == 5);
    Tensor mask = Tensor::from_mask(m, {6, L});  // item 5: every key masked
    Tensor g64 = test::random_tensor({6, L, 32}, init);
    Tensor x32 = x64.to(DType::F32).detach().set_requires_grad();
    x64.set_requires_grad();
    Rng r64(9), r32(9);
    Tensor y64 = packed_attention(x64, 2, mask, 0.3, true, r64);
    Tensor y32 = packed_attention(x32, 2, mask, 0.3, true, r32);
    y64.backward(g64);
    y32.backward(g64.to(DType::F32));
    auto close = [](const Tensor& a, const Tensor& b, const char* what, int64_t L) {
      std::vector<double> va = a.to_vector(), vb = b.to_vector();
      ASSERT_EQ(va.size(), vb.size());
      for (size_t i = 0; i < va.size(); ++i) ASSERT_NEAR(va[i], vb[i], 1e-4 + 1e-4 * std::abs(va[i])) << what << " L=" << L << " at " << i;
    };
    close(y64, y32, "output", L);
    close(x64.grad(), x32.grad(), "dqkv", L);
  }
}

}  // namespace
}  // namespace lc2wf
