// Behaviour of the Line-Patch Transformer beyond the golden fixtures: input validation, pooling modes,
// loss validation and determinism of training-mode forward passes (dropout) across thread counts.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "core/ops.h"
#include "core/parallel.h"
#include "core/storage_cache.h"
#include "nn/edge_net.h"
#include "nn/junction_net.h"
#include "nn/losses.h"

using ::testing::HasSubstr;

namespace lc2wf {
namespace {

JunctionNetConfig small(const std::string& pool = "mean_all") {
  JunctionNetConfig c;
  c.lpt.lines_per_patch = 6;
  c.lpt.patches = 4;
  c.lpt.mlp_dims = {8, 16};
  c.lpt.hidden_dim = 16;
  c.lpt.num_heads = 4;
  c.lpt.ffn_dim = 16;
  c.lpt.pool = pool;
  c.head.dims = {8};
  return c;
}

Tensor inputs(int64_t B, int64_t G, int64_t N, int64_t F, uint64_t seed) {
  Rng rng(seed);
  std::vector<float> v(B * G * N * F);
  for (auto& x : v) x = static_cast<float>(rng.next_uniform(-1, 1));
  return Tensor::from_vector(v, {B, G, N, F});
}

Tensor mask_every(int64_t B, int64_t G, int64_t N, int64_t k) {
  std::vector<uint8_t> m(B * G * N);
  for (size_t i = 0; i < m.size(); ++i) m[i] = k > 0 && static_cast<int64_t>(i % N) % k == k - 1;
  return Tensor::from_mask(m, {B, G, N});
}

std::string error_of(JunctionNet& net, const Tensor& x, const Tensor& mask) {
  try {
    net.forward(x, mask);
  } catch (const std::invalid_argument& e) {
    return e.what();
  }
  return "";
}

TEST(Lpt, RejectsBadInputsWithClearMessages) {
  JunctionNet net(small());
  const Tensor mask = mask_every(2, 4, 6, 3);
  EXPECT_THAT(error_of(net, inputs(2, 4, 5, 7, 1), mask_every(2, 4, 5, 3)), HasSubstr("expected input (B, G, 6, 7)"));
  EXPECT_THAT(error_of(net, inputs(2, 4, 6, 6, 1), mask), HasSubstr("got [2, 4, 6, 6]"));
  EXPECT_THAT(error_of(net, inputs(2, 4, 6, 7, 1), Tensor::zeros({2, 4, 6})), HasSubstr("Bool mask"));
  EXPECT_THAT(error_of(net, inputs(2, 4, 6, 7, 1), Tensor()), HasSubstr("undefined"));
  EXPECT_THROW(JunctionNet bad(small("max")), std::invalid_argument);
}

TEST(Lpt, PoolingModesAgreeWithoutPaddingAndDifferWithIt) {
  JunctionNet all(small("mean_all"), 3), valid(small("mean_valid"), 3);
  all.eval();
  valid.eval();
  NoGradGuard no_grad;
  const Tensor x = inputs(1, 4, 6, 7, 2);
  const auto a0 = all.forward(x, mask_every(1, 4, 6, 0)).logits.to_vector();
  const auto v0 = valid.forward(x, mask_every(1, 4, 6, 0)).logits.to_vector();
  for (size_t i = 0; i < a0.size(); ++i) EXPECT_NEAR(a0[i], v0[i], 1e-5);
  const auto a1 = all.forward(x, mask_every(1, 4, 6, 2)).logits.to_vector();
  const auto v1 = valid.forward(x, mask_every(1, 4, 6, 2)).logits.to_vector();
  double diff = 0;
  for (size_t i = 0; i < a1.size(); ++i) diff = std::max(diff, std::abs(a1[i] - v1[i]));
  EXPECT_GT(diff, 1e-4);
}

TEST(Lpt, TrainingForwardIsDeterministicAcrossThreadCounts) {
  JunctionNetConfig c = small();
  c.lpt.mlp_dims = {64, 64};
  c.lpt.hidden_dim = 64;
  c.lpt.ffn_dim = 64;
  const Tensor x = inputs(4, 16, 6, 7, 5);
  const Tensor mask = mask_every(4, 16, 6, 4);
  auto run = [&](int threads) {
    set_num_threads(threads);
    JunctionNet net(c, 9);
    const JunctionOutput out = net.forward(x, mask);
    sum(out.logits).backward();
    return std::make_pair(out.offsets.to_vector(), net.named_parameters()[0].second.grad().to_vector());
  };
  const auto one = run(1), two = run(2), again = run(2);
  set_num_threads(0);
  EXPECT_EQ(one, two);
  EXPECT_EQ(two, again);
}

TEST(Lpt, KeptMlpActivationsGiveTheRecomputedValuesAndGradients) {
  // Recomputing the line MLP trades time for memory only: outputs, every gradient and the BatchNorm
  // running statistics (updated once, not again by the recomputation) are the same bits either way.
  auto run = [](bool recompute) {
    JunctionNet net(small(), 9);
    net.set_recompute_mlp(recompute);
    const JunctionOutput out = net.forward(inputs(2, 4, 6, 7, 5), mask_every(2, 4, 6, 4));
    (sum(out.logits) + sum(mul(out.offsets, out.offsets))).backward();
    std::vector<std::vector<double>> values{out.logits.to_vector(), out.offsets.to_vector()};
    for (const auto& [name, p] : net.named_parameters()) values.push_back(p.grad().to_vector());
    for (const auto& [name, b] : net.named_buffers()) values.push_back(b.to_vector());
    return values;
  };
  const auto recomputed = run(true), kept = run(false);
  ASSERT_EQ(recomputed.size(), kept.size());
  EXPECT_GT(recomputed.size(), 20u);
  for (size_t i = 0; i < kept.size(); ++i) EXPECT_EQ(recomputed[i], kept[i]) << "tensor " << i;
}

TEST(Lpt, RecomputingTheMlpKeepsLessForTheBackwardPass) {
  // 4,096 line slots at width 256: the MLP's activations are 4 MB blocks, which the storage cache counts.
  auto live_after_forward = [](bool recompute) {
    JunctionNetConfig c = small();
    c.lpt.mlp_dims = {256, 256};
    c.lpt.hidden_dim = 256;
    c.lpt.lines_per_patch = 32;
    c.lpt.patches = 64;
    JunctionNet net(c, 9);
    net.set_recompute_mlp(recompute);
    const size_t before = storage_cache_stats().live_bytes;
    const JunctionOutput out = net.forward(inputs(2, 64, 32, 7, 5), mask_every(2, 64, 32, 4));
    return storage_cache_stats().live_bytes - before;  // what the graph keeps for backward
  };
  const size_t kept = live_after_forward(false), recomputed = live_after_forward(true);
  // Kept besides: the first layer's Linear and ReLU outputs and the second's Linear output (its ReLU
  // output is the MLP's result, which the encoder keeps either way).
  EXPECT_GE(kept, recomputed + 3 * (size_t{4} << 20));
}

TEST(Lpt, InferenceInChunksEqualsTheWholeForward) {
  // A building with more pair patches than one inference chunk holds: without gradients the lines are
  // encoded chunk by chunk, with them (same eval mode) all at once; the patch encoder sees every patch.
  EdgeNetConfig c;
  c.lpt.lines_per_patch = 64;
  c.lpt.mlp_dims = {8, 16};
  c.lpt.hidden_dim = 16;
  c.lpt.num_heads = 4;
  c.lpt.ffn_dim = 16;
  c.head.dims = {8};
  const int64_t P = 2 * LinePatchTransformer::kInferenceTokensPerChunk / 64 + 5;  // 3 chunks, the last partial
  const Tensor x = inputs(1, P, 64, 6, 8);
  const Tensor mask = mask_every(1, P, 64, 5);
  EdgeNet net(c, 12);
  net.eval();
  const std::vector<double> whole = net.forward(x, mask).to_vector();
  NoGradGuard no_grad;
  const std::vector<double> chunked = net.forward(x, mask).to_vector();
  ASSERT_EQ(whole.size(), chunked.size());
  double diff = 0;
  for (size_t i = 0; i < whole.size(); ++i) diff = std::max(diff, std::abs(whole[i] - chunked[i]));
  EXPECT_LE(diff, 1e-6);
}

TEST(Lpt, DropoutStreamAdvancesOnlyInTraining) {
  JunctionNet net(small(), 4);
  const Tensor x = inputs(1, 4, 6, 7, 6);
  const Tensor mask = mask_every(1, 4, 6, 3);
  const uint64_t start = net.dropout_rng().counter();
  net.forward(x, mask);
  const uint64_t after_train = net.dropout_rng().counter();
  EXPECT_GT(after_train, start);
  net.eval();
  net.forward(x, mask);
  EXPECT_EQ(net.dropout_rng().counter(), after_train);
}

TEST(Losses, EdgeMicroBatchesAddUpToTheBatchLossAndGradient) {
  // Two "buildings" of 3 pairs with different class mixes: the weighted mean is not a mean of means, so
  // each part must be divided by the whole batch's weight sum.
  std::vector<float> z(2 * 3 * 5);
  for (size_t k = 0; k < z.size(); ++k) z[k] = static_cast<float>(std::sin(0.7 * static_cast<double>(k)));
  const std::vector<int64_t> y{1, 1, 0, 3, 4, 2};
  const EdgeLossConfig cfg;
  Tensor whole = Tensor::from_vector(z, {2, 3, 5});
  whole.set_requires_grad();
  const Tensor labels = Tensor::from_vector(y, {2, 3});
  const Tensor full = edge_loss(whole, labels, cfg);
  full.backward();
  const double W = edge_loss_weight(labels, cfg);
  EXPECT_DOUBLE_EQ(W, 3 + 3 + 1 + 1 + 1 + 1);
  double parts = 0;
  std::vector<double> grad;
  for (int b = 0; b < 2; ++b) {
    Tensor part = Tensor::from_vector(std::vector<float>(z.begin() + 15 * b, z.begin() + 15 * (b + 1)), {1, 3, 5});
    part.set_requires_grad();
    const Tensor l = edge_loss(part, Tensor::from_vector(std::vector<int64_t>(y.begin() + 3 * b, y.begin() + 3 * (b + 1)), {1, 3}), cfg, W);
    l.backward();
    parts += l.item();
    for (double g : part.grad().to_vector()) grad.push_back(g);
  }
  EXPECT_NEAR(parts, full.item(), 1e-6);
  const std::vector<double> expected = whole.grad().to_vector();
  ASSERT_EQ(grad.size(), expected.size());
  for (size_t k = 0; k < grad.size(); ++k) EXPECT_NEAR(grad[k], expected[k], 1e-7) << k;
  EXPECT_THROW(edge_loss_weight(Tensor::from_vector(std::vector<int64_t>{5}, {1, 1}), cfg), std::invalid_argument);
}

TEST(Losses, RejectBadTargets) {
  JunctionNet net(small());
  const JunctionOutput out = net.forward(inputs(1, 4, 6, 7, 1), mask_every(1, 4, 6, 3));
  const Tensor offsets = Tensor::zeros({1, 4, 3});
  EXPECT_THROW(junction_loss(out, {Tensor::zeros({1, 4}), offsets}, {}), std::invalid_argument);  // F32 labels
  EXPECT_THROW(junction_loss(out, {Tensor::from_vector(std::vector<int64_t>{0, 1, 2, 0}, {1, 4}), offsets}, {}),
               std::invalid_argument);  // label 2
  EXPECT_THROW(junction_loss(out, {Tensor::from_vector(std::vector<int64_t>{0, 1, 1, 0}, {1, 4}), Tensor::zeros({1, 4, 2})}, {}),
               std::invalid_argument);
  EXPECT_THROW(edge_loss(Tensor::zeros({1, 3, 4}), Tensor::from_vector(std::vector<int64_t>{0, 1, 2}, {1, 3}), {}),
               std::invalid_argument);  // 4 logits, 5 class weights
}

}  // namespace
}  // namespace lc2wf
