// Recompute-in-backward ops: the same values and gradients as the ops they replace, bit for bit, while
// keeping fewer activations alive between the forward and the backward pass.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cstring>

#include "core/ops.h"
#include "core/storage_cache.h"
#include "tests/core/gradcheck.h"

using ::testing::HasSubstr;

namespace lc2wf {
namespace {

Tensor rand32(const Shape& s, uint64_t seed, double lo = -1, double hi = 1) {
  Rng rng(seed);
  return test::random_tensor(s, rng, lo, hi, DType::F32);
}

void expect_bitwise(const Tensor& a, const Tensor& b, const char* what) {
  ASSERT_TRUE(a.defined() && b.defined()) << what;
  ASSERT_EQ(a.shape(), b.shape()) << what;
  EXPECT_EQ(std::memcmp(a.data<float>(), b.data<float>(), a.numel() * sizeof(float)), 0) << what;
}

// Fresh leaves (same values) for each run, so gradients never mix between runs.
std::vector<Tensor> leaves(const std::vector<Tensor>& src) {
  std::vector<Tensor> out;
  for (const Tensor& t : src) out.push_back(t.clone().detach().set_requires_grad());
  return out;
}

TEST(Recompute, LayerNormLinearMatchesTheTwoOpsBitwise) {
  const std::vector<Tensor> src{rand32({3, 50, 64}, 1), rand32({64}, 2, 0.5, 1.5), rand32({64}, 3),
                                rand32({96, 64}, 4), rand32({96}, 5)};
  const Tensor r = rand32({3, 50, 96}, 6);
  std::vector<Tensor> a = leaves(src), b = leaves(src);
  Tensor ya = layer_norm_linear(a[0], a[1], a[2], 1e-5, a[3], a[4]);
  Tensor yb = linear(layer_norm(b[0], b[1], b[2], 1e-5), b[3], b[4]);
  expect_bitwise(ya, yb, "forward");
  sum(mul(ya, r)).backward();
  sum(mul(yb, r)).backward();
  const char* names[] = {"dx", "dnorm_weight", "dnorm_bias", "dweight", "dbias"};
  for (size_t i = 0; i < a.size(); ++i) expect_bitwise(a[i].grad(), b[i].grad(), names[i]);
}

// Linear + BatchNorm + ReLU twice, the shape of the LPT's per-line MLP.
Tensor mlp(const std::vector<Tensor>& p, Tensor& rm, Tensor& rv, bool update_running) {
  Tensor none;
  Tensor h = relu(batch_norm(linear(p[0], p[1], p[2]), p[3], p[4], update_running ? rm : none,
                             update_running ? rv : none, true));
  return relu(batch_norm(linear(h, p[5], p[6]), Tensor(), Tensor(), none, none, true));
}

TEST(Recompute, CheckpointMatchesTheDirectGraphBitwiseAndUpdatesRunningStatsOnce) {
  const std::vector<Tensor> src{rand32({500, 7}, 1), rand32({64, 7}, 2),  rand32({64}, 3), rand32({64}, 4, 0.5, 1.5),
                                rand32({64}, 5),     rand32({128, 64}, 6), rand32({128}, 7)};
  const Tensor r = rand32({500, 128}, 8);
  std::vector<Tensor> a = leaves(src), b = leaves(src);
  Tensor rm_a = Tensor::zeros({64}), rv_a = Tensor::ones({64}), rm_b = Tensor::zeros({64}), rv_b = Tensor::ones({64});
  Tensor ya = checkpoint(a, [&](const std::vector<Tensor>& in, bool recompute) { return mlp(in, rm_a, rv_a, !recompute); });
  Tensor yb = mlp(b, rm_b, rv_b, true);
  expect_bitwise(ya, yb, "forward");
  sum(mul(ya, r)).backward();
  sum(mul(yb, r)).backward();
  for (size_t i = 0; i < a.size(); ++i) expect_bitwise(a[i].grad(), b[i].grad(), ("grad " + std::to_string(i)).c_str());
  expect_bitwise(rm_a, rm_b, "running_mean");
  expect_bitwise(rv_a, rv_b, "running_var");
}

TEST(Recompute, CheckpointRejectsARecomputationOfAnotherShape) {
  Tensor x = rand32({4, 3}, 1).set_requires_grad();
  Tensor y = checkpoint({x}, [](const std::vector<Tensor>& in, bool recompute) {
    return recompute ? sum(in[0], {0}) : relu(in[0]);
  });
  try {
    sum(y).backward();
    FAIL() << "expected std::invalid_argument";
  } catch (const std::invalid_argument& e) {
    EXPECT_THAT(std::string(e.what()), HasSubstr("checkpoint")) << e.what();
  }
}

// Large (>= 1 MiB) buffers alive after the forward pass, beyond those alive before it. The cache is off
// meanwhile so that every buffer counts its own size, not that of a larger recycled block.
template <class F>
size_t live_after_forward(F&& forward) {
  const size_t budget = storage_cache_stats().budget_bytes;
  set_storage_cache_budget(0);
  const size_t before = storage_cache_stats().live_bytes;
  Tensor out = forward();
  const size_t kept = storage_cache_stats().live_bytes - before;
  set_storage_cache_budget(budget);
  return kept;
}

constexpr size_t kMiB = size_t{1} << 20;

TEST(Recompute, LayerNormLinearKeepsOnlyItsOutput) {
  const Tensor x = rand32({4096, 256}, 1).set_requires_grad();  // 4 MiB
  const Tensor w = rand32({768, 256}, 2).set_requires_grad();   // the output: 12 MiB
  const size_t fused = live_after_forward([&] { return layer_norm_linear(x, Tensor(), Tensor(), 1e-5, w); });
  const size_t split = live_after_forward([&] { return linear(layer_norm(x, Tensor(), Tensor()), w); });
  EXPECT_LT(fused, 13 * kMiB);
  EXPECT_GE(split, fused + 4 * kMiB);  // the two ops keep the normalised rows
}

TEST(Recompute, CheckpointKeepsOnlyItsOutput) {
  const Tensor x = rand32({8192, 32}, 1).set_requires_grad();  // 1 MiB
  const Tensor w1 = rand32({256, 32}, 2).set_requires_grad(), w2 = rand32({128, 256}, 3).set_requires_grad();
  auto body = [](const std::vector<Tensor>& in) { return relu(linear(relu(linear(in[0], in[1])), in[2])); };
  const size_t fused = live_after_forward(
      [&] { return checkpoint({x, w1, w2}, [&](const std::vector<Tensor>& in, bool) { return body(in); }); });
  const size_t direct = live_after_forward([&] { return body({x, w1, w2}); });
  EXPECT_LT(fused, 5 * kMiB);            // the 4 MiB output
  EXPECT_GE(direct, fused + 8 * kMiB);   // plus the 8 MiB hidden activation (and the pre-ReLU product)
}

TEST(Recompute, AttentionKeepsNoProbabilities) {
  const Tensor qkv = rand32({64, 32, 3 * 256}, 1).set_requires_grad();  // 6 MiB; probabilities 64*8*32*32*4 = 2 MiB
  Rng rng(5);
  const size_t kept = live_after_forward([&] { return packed_attention(qkv, 8, Tensor(), 0.1, true, rng); });
  EXPECT_LT(kept, 3 * kMiB);  // the 2 MiB output only
}

}  // namespace
}  // namespace lc2wf
