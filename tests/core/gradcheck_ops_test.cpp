// Finite-difference checks of every differentiable op (F64).
#include <gtest/gtest.h>

#include "core/ops.h"
#include "tests/core/gradcheck.h"

namespace lc2wf {
namespace {

using test::gradcheck;
using test::random_away_from_zero;
using test::random_tensor;

class GradCheck : public ::testing::Test {
 protected:
  Rng rng_{42};
  Tensor rand(const Shape& s, double lo = -1, double hi = 1) { return random_tensor(s, rng_, lo, hi); }
};

TEST_F(GradCheck, BinaryOpsSameShape) {
  Tensor a = rand({3, 4}), b = rand({3, 4}, 0.5, 2.0);
  EXPECT_TRUE(gradcheck([](auto& x) { return add(x[0], x[1]); }, {a, b}));
  EXPECT_TRUE(gradcheck([](auto& x) { return sub(x[0], x[1]); }, {a, b}));
  EXPECT_TRUE(gradcheck([](auto& x) { return mul(x[0], x[1]); }, {a, b}));
  EXPECT_TRUE(gradcheck([](auto& x) { return div(x[0], x[1]); }, {a, b}));
}

TEST_F(GradCheck, BinaryOpsBroadcastLastAxis) {  // [B,T,C] op [C]
  Tensor a = rand({2, 3, 4}), b = rand({4}, 0.5, 2.0);
  EXPECT_TRUE(gradcheck([](auto& x) { return add(x[0], x[1]); }, {a, b}));
  EXPECT_TRUE(gradcheck([](auto& x) { return sub(x[1], x[0]); }, {a, b}));
  EXPECT_TRUE(gradcheck([](auto& x) { return mul(x[0], x[1]); }, {a, b}));
  EXPECT_TRUE(gradcheck([](auto& x) { return div(x[0], x[1]); }, {a, b}));
}

TEST_F(GradCheck, BinaryOpsBroadcastKeepdimAxis) {  // [B,T,C] op [B,T,1]
  Tensor a = rand({2, 3, 4}), b = rand({2, 3, 1}, 0.5, 2.0);
  EXPECT_TRUE(gradcheck([](auto& x) { return mul(x[0], x[1]); }, {a, b}));
  EXPECT_TRUE(gradcheck([](auto& x) { return div(x[0], x[1]); }, {a, b}));
  EXPECT_TRUE(gradcheck([](auto& x) { return sub(x[0], x[1]); }, {a, b}));
}

TEST_F(GradCheck, BinaryOpsBothSidesBroadcast) {  // [B,1,C] op [T,1]
  Tensor a = rand({2, 1, 4}), b = rand({3, 1}, 0.5, 2.0);
  EXPECT_TRUE(gradcheck([](auto& x) { return mul(x[0], x[1]); }, {a, b}));
  Tensor pos = rand({2, 1, 4}, 0.5, 2.0);
  EXPECT_TRUE(gradcheck([](auto& x) { return div(x[1], x[0]); }, {pos, b}));
}

TEST_F(GradCheck, BinaryOpsWithScalarTensor) {
  Tensor a = rand({2, 3}), s = rand({}, 0.5, 2.0), one = rand({1}, 0.5, 2.0);
  EXPECT_TRUE(gradcheck([](auto& x) { return mul(x[0], x[1]); }, {a, s}));
  EXPECT_TRUE(gradcheck([](auto& x) { return div(x[0], x[1]); }, {a, one}));
  EXPECT_TRUE(gradcheck([](auto& x) { return add(x[1], x[0]); }, {a, s}));
}

TEST_F(GradCheck, ScalarOps) {
  Tensor a = rand({3, 4}, 0.5, 2.0);
  EXPECT_TRUE(gradcheck([](auto& x) { return add(x[0], 1.5); }, {a}));
  EXPECT_TRUE(gradcheck([](auto& x) { return sub(x[0], 1.5); }, {a}));
  EXPECT_TRUE(gradcheck([](auto& x) { return rsub(1.5, x[0]); }, {a}));
  EXPECT_TRUE(gradcheck([](auto& x) { return mul(x[0], -2.5); }, {a}));
  EXPECT_TRUE(gradcheck([](auto& x) { return div(x[0], 4.0); }, {a}));
  EXPECT_TRUE(gradcheck([](auto& x) { return rdiv(3.0, x[0]); }, {a}));
  EXPECT_TRUE(gradcheck([](auto& x) { return 2.0 - x[0] * 3.0 + 1.0 / x[0] - (-x[0]); }, {a}));
}

TEST_F(GradCheck, UnaryOps) {
  Tensor a = rand({3, 5}), pos = rand({3, 5}, 0.2, 3.0), away = random_away_from_zero({3, 5}, rng_);
  EXPECT_TRUE(gradcheck([](auto& x) { return neg(x[0]); }, {a}));
  EXPECT_TRUE(gradcheck([](auto& x) { return exp(x[0]); }, {a}));
  EXPECT_TRUE(gradcheck([](auto& x) { return log(x[0]); }, {pos}));
  EXPECT_TRUE(gradcheck([](auto& x) { return sqrt(x[0]); }, {pos}));
  EXPECT_TRUE(gradcheck([](auto& x) { return pow(x[0], 2.5); }, {pos}));
  EXPECT_TRUE(gradcheck([](auto& x) { return pow(x[0], 3.0); }, {a}));
  EXPECT_TRUE(gradcheck([](auto& x) { return relu(x[0]); }, {away}));
  EXPECT_TRUE(gradcheck([](auto& x) { return sigmoid(x[0]); }, {a}));
  EXPECT_TRUE(gradcheck([](auto& x) { return tanh(x[0]); }, {a}));
  EXPECT_TRUE(gradcheck([](auto& x) { return abs(x[0]); }, {away}));
}

TEST_F(GradCheck, Reductions) {
  Tensor a = rand({2, 3, 4});
  EXPECT_TRUE(gradcheck([](auto& x) { return sum(x[0]); }, {a}));
  EXPECT_TRUE(gradcheck([](auto& x) { return mean(x[0]); }, {a}));
  EXPECT_TRUE(gradcheck([](auto& x) { return sum(x[0], {1}); }, {a}));
  EXPECT_TRUE(gradcheck([](auto& x) { return sum(x[0], {0, 2}, true); }, {a}));
  EXPECT_TRUE(gradcheck([](auto& x) { return mean(x[0], {-1}, true); }, {a}));
  EXPECT_TRUE(gradcheck([](auto& x) { return mean(x[0], {0, 1}); }, {a}));
  // Distinct values so the extremum is unique and the function is smooth around it.
  EXPECT_TRUE(gradcheck([](auto& x) { return max(x[0], {1}); }, {a}));
  EXPECT_TRUE(gradcheck([](auto& x) { return max(x[0], {0, 2}, true); }, {a}));
  EXPECT_TRUE(gradcheck([](auto& x) { return min(x[0], {2}); }, {a}));
  EXPECT_TRUE(gradcheck([](auto& x) { return min(x[0], {0, 1}, true); }, {a}));
}

TEST_F(GradCheck, Matmul) {
  EXPECT_TRUE(gradcheck([](auto& x) { return matmul(x[0], x[1]); }, {rand({3, 4}), rand({4, 5})}));
  EXPECT_TRUE(gradcheck([](auto& x) { return matmul(x[0], x[1]); }, {rand({2, 3, 4}), rand({4, 5})}));
  EXPECT_TRUE(gradcheck([](auto& x) { return matmul(x[0], x[1]); }, {rand({2, 3, 4}), rand({2, 4, 5})}));
  // Broadcast batch dims: (2,1,3,4) x (5,4,2) -> (2,5,3,2).
  EXPECT_TRUE(gradcheck([](auto& x) { return matmul(x[0], x[1]); }, {rand({2, 1, 3, 4}), rand({5, 4, 2})}));
}

TEST_F(GradCheck, Linear) {
  EXPECT_TRUE(gradcheck([](auto& x) { return linear(x[0], x[1], x[2]); }, {rand({2, 3, 4}), rand({5, 4}), rand({5})}));
  EXPECT_TRUE(gradcheck([](auto& x) { return linear(x[0], x[1]); }, {rand({6, 4}), rand({3, 4})}));
}

TEST_F(GradCheck, LayoutOps) {
  Tensor a = rand({2, 3, 4});
  EXPECT_TRUE(gradcheck([](auto& x) { return x[0].reshape({4, -1}); }, {a}));
  EXPECT_TRUE(gradcheck([](auto& x) { return x[0].permute({2, 0, 1}); }, {a}));
  EXPECT_TRUE(gradcheck([](auto& x) { return x[0].transpose(0, 2); }, {a}));
  EXPECT_TRUE(gradcheck([](auto& x) { return x[0].clone(); }, {a}));
  EXPECT_TRUE(gradcheck([](auto& x) { return x[0].to(DType::F64); }, {a}));
}

TEST_F(GradCheck, ConcatStackSlice) {
  EXPECT_TRUE(gradcheck([](auto& x) { return concat({x[0], x[1], x[0]}, 1); }, {rand({2, 3, 2}), rand({2, 1, 2})}));
  EXPECT_TRUE(gradcheck([](auto& x) { return concat({x[0], x[1]}, -1); }, {rand({2, 3}), rand({2, 4})}));
  EXPECT_TRUE(gradcheck([](auto& x) { return stack({x[0], x[1]}, 1); }, {rand({2, 3}), rand({2, 3})}));
  EXPECT_TRUE(gradcheck([](auto& x) { return stack({x[0], x[1]}, 2); }, {rand({2, 3}), rand({2, 3})}));
  Tensor a = rand({3, 7, 2});
  EXPECT_TRUE(gradcheck([](auto& x) { return slice(x[0], 1, 1, 6); }, {a}));
  EXPECT_TRUE(gradcheck([](auto& x) { return slice(x[0], 1, -6, 7, 2); }, {a}));
  EXPECT_TRUE(gradcheck([](auto& x) { return slice(x[0], 0, 1, 2); }, {a}));
}

TEST_F(GradCheck, IndexSelectGatherExpandRepeat) {
  Tensor idx = Tensor::from_vector(std::vector<int64_t>{2, 0, 2, 1}, {4});
  EXPECT_TRUE(gradcheck([&](auto& x) { return index_select(x[0], 1, idx); }, {rand({2, 3, 2})}));
  EXPECT_TRUE(gradcheck([&](auto& x) { return index_select(x[0], 0, idx); }, {rand({3, 2})}));
  Tensor gi = Tensor::from_vector(std::vector<int64_t>{0, 2, 2, 1, 1, 1, 0, 0}, {2, 2, 2});
  EXPECT_TRUE(gradcheck([&](auto& x) { return gather(x[0], 1, gi); }, {rand({2, 3, 2})}));
  EXPECT_TRUE(gradcheck([&](auto& x) { return gather(x[0], 2, gi); }, {rand({2, 3, 3})}));
  EXPECT_TRUE(gradcheck([](auto& x) { return expand(x[0], {2, 3, 4}); }, {rand({3, 1})}));
  EXPECT_TRUE(gradcheck([](auto& x) { return repeat(x[0], {2, 1, 3}); }, {rand({3, 2})}));
}

TEST_F(GradCheck, MaskedFillAndWhereWithFullyMaskedRows) {
  // Row 1 is fully masked; its gradient must be exactly zero.
  Tensor mask = Tensor::from_mask({0, 1, 0, 1, 1, 1, 1, 1, 0, 0, 0, 0}, {3, 4});
  EXPECT_TRUE(gradcheck([&](auto& x) { return masked_fill(x[0], mask, -3.0); }, {rand({3, 4})}));
  Tensor row_mask = Tensor::from_mask({0, 1, 0}, {3, 1});  // broadcast over columns
  EXPECT_TRUE(gradcheck([&](auto& x) { return masked_fill(x[0], row_mask, 0.0); }, {rand({2, 3, 4})}));
  EXPECT_TRUE(gradcheck([&](auto& x) { return where(mask, x[0], x[1]); }, {rand({3, 4}), rand({4})}));
  // Softmax over masked scores where a row is fully masked must stay finite when followed by where.
  EXPECT_TRUE(gradcheck(
      [&](auto& x) {
        Tensor s = softmax(masked_fill(x[0], mask, -1e9), -1);
        return where(mask, Tensor::zeros({3, 4}, DType::F64), s);
      },
      {rand({3, 4})}));
}

TEST_F(GradCheck, SoftmaxAndLogSoftmax) {
  Tensor a = rand({2, 3, 5}, -3, 3);
  EXPECT_TRUE(gradcheck([](auto& x) { return softmax(x[0], -1); }, {a}));
  EXPECT_TRUE(gradcheck([](auto& x) { return softmax(x[0], 1); }, {a}));
  EXPECT_TRUE(gradcheck([](auto& x) { return log_softmax(x[0], -1); }, {a}));
  EXPECT_TRUE(gradcheck([](auto& x) { return log_softmax(x[0], 0); }, {a}));
}

TEST_F(GradCheck, DropoutWithFixedStream) {
  EXPECT_TRUE(gradcheck(
      [](auto& x) {
        Rng r(7);  // same mask in every evaluation
        return dropout(x[0], 0.4, true, r);
      },
      {rand({4, 6})}));
}

TEST_F(GradCheck, FusedDropoutAddAndReluWithFixedStream) {
  EXPECT_TRUE(gradcheck(
      [](auto& x) {
        Rng r(7);
        return add_dropout(x[0], x[1], 0.4, true, r);
      },
      {rand({4, 6}), rand({4, 6})}));
  // Inputs away from 0, where ReLU has no derivative for the finite differences to straddle.
  std::vector<double> away(24);
  for (size_t i = 0; i < away.size(); ++i) away[i] = (i % 3 == 0 ? -1.0 : 1.0) * (0.3 + 0.05 * static_cast<double>(i));
  EXPECT_TRUE(gradcheck(
      [](auto& x) {
        Rng r(7);
        return dropout_relu(x[0], 0.4, true, r);
      },
      {Tensor::from_vector(away, {4, 6})}));
}

TEST_F(GradCheck, LayerNormTrain) {
  EXPECT_TRUE(gradcheck([](auto& x) { return layer_norm(x[0], x[1], x[2]); }, {rand({3, 2, 6}), rand({6}), rand({6})}));
  EXPECT_TRUE(gradcheck([](auto& x) { return layer_norm(x[0], Tensor(), Tensor()); }, {rand({4, 5})}));
}

TEST_F(GradCheck, BatchNormTrainAndEval) {
  EXPECT_TRUE(gradcheck(
      [](auto& x) {
        Tensor rm = Tensor::zeros({5}, DType::F64), rv = Tensor::ones({5}, DType::F64);
        return batch_norm(x[0], x[1], x[2], rm, rv, true);
      },
      {rand({7, 5}), rand({5}), rand({5})}));
  EXPECT_TRUE(gradcheck(
      [](auto& x) {
        Tensor rm, rv;
        return batch_norm(x[0], Tensor(), Tensor(), rm, rv, true);
      },
      {rand({6, 3})}));
  Tensor rm = rand({5}), rv = rand({5}, 0.5, 2.0);
  EXPECT_TRUE(gradcheck([&](auto& x) { return batch_norm(x[0], x[1], x[2], rm, rv, false); },
                        {rand({7, 5}), rand({5}), rand({5})}));
}

TEST_F(GradCheck, CrossEntropyWeightsAndIgnoreIndex) {
  Tensor target = Tensor::from_vector(std::vector<int64_t>{2, -100, 0, 3, 1}, {5});
  Tensor w = Tensor::from_vector(std::vector<double>{0.5, 2.0, 1.0, 3.0}, {4});
  for (Reduction red : {Reduction::Mean, Reduction::Sum, Reduction::None}) {
    EXPECT_TRUE(gradcheck([&](auto& x) { return cross_entropy(x[0], target, w, -100, red); }, {rand({5, 4}, -3, 3)}));
    EXPECT_TRUE(gradcheck([&](auto& x) { return cross_entropy(x[0], target, Tensor(), -100, red); }, {rand({5, 4}, -3, 3)}));
  }
}

TEST_F(GradCheck, BceL1Mse) {
  for (Reduction red : {Reduction::Mean, Reduction::Sum, Reduction::None}) {
    EXPECT_TRUE(gradcheck([&](auto& x) { return bce_with_logits(x[0], x[1], red); }, {rand({3, 4}, -4, 4), rand({3, 4}, 0, 1)}));
    Tensor a = rand({3, 4});
    Tensor b = add(a, random_away_from_zero({3, 4}, rng_)).detach();
    EXPECT_TRUE(gradcheck([&](auto& x) { return l1_loss(x[0], x[1], red); }, {a, b}));
    EXPECT_TRUE(gradcheck([&](auto& x) { return mse_loss(x[0], x[1], red); }, {rand({3, 4}), rand({3, 4})}));
  }
}

TEST_F(GradCheck, AttentionWithMaskAndDropout) {
  // Batch item 1 has every key masked; item 0 masks one key.
  Tensor mask = Tensor::from_mask({0, 0, 1, 0, 1, 1, 1, 1}, {2, 4});
  for (bool train : {false, true}) {
    EXPECT_TRUE(gradcheck(
        [&](auto& x) {
          Rng r(11);
          return scaled_dot_product_attention(x[0], x[1], x[2], mask, 0.3, train, r);
        },
        {rand({2, 2, 4, 3}), rand({2, 2, 4, 3}), rand({2, 2, 4, 3})}));
    EXPECT_TRUE(gradcheck(
        [&](auto& x) {
          Rng r(11);
          return packed_attention(x[0], 2, mask, 0.3, train, r);
        },
        {rand({2, 4, 12})}));
  }
  // Different query and key lengths, no mask.
  EXPECT_TRUE(gradcheck(
      [&](auto& x) {
        Rng r(3);
        return scaled_dot_product_attention(x[0], x[1], x[2], Tensor(), 0.0, false, r);
      },
      {rand({1, 2, 3, 4}), rand({1, 2, 5, 4}), rand({1, 2, 5, 4})}));
}

TEST_F(GradCheck, LayerNormLinear) {
  EXPECT_TRUE(gradcheck([](auto& p) { return layer_norm_linear(p[0], p[1], p[2], 1e-5, p[3], p[4]); },
                        {rand({2, 3, 6}), rand({6}, 0.5, 1.5), rand({6}), rand({5, 6}), rand({5})}));
  // No affine LayerNorm, no bias.
  EXPECT_TRUE(gradcheck([](auto& p) { return layer_norm_linear(p[0], Tensor(), Tensor(), 1e-5, p[1]); },
                        {rand({7, 6}), rand({4, 6})}));
}

TEST_F(GradCheck, CheckpointedLinearBatchNormRelu) {
  // Two stages of the per-line MLP; the running statistics are updated by the forward pass only.
  Tensor rm = Tensor::zeros({4}, DType::F64), rv = Tensor::ones({4}, DType::F64);
  auto stages = [&](const std::vector<Tensor>& p, bool recompute) {
    Tensor none, mean = recompute ? none : rm, var = recompute ? none : rv;
    Tensor h = relu(batch_norm(linear(p[0], p[1], p[2]), p[3], p[4], mean, var, true));
    return relu(batch_norm(linear(h, p[5]), Tensor(), Tensor(), none, none, true));
  };
  EXPECT_TRUE(gradcheck([&](auto& p) { return checkpoint(p, stages); },
                        {rand({9, 3}), rand({4, 3}), rand({4}), rand({4}, 0.5, 1.5), rand({4}), rand({5, 4})}));
}

TEST_F(GradCheck, EncoderBlockComposite) {
  // A pre-norm encoder layer as the LPT builds it: every op chained, masked keys, dropout on.
  Tensor mask = Tensor::from_mask({0, 0, 0, 1, 0, 1, 1, 1}, {2, 4});
  Tensor pool_w = Tensor::from_vector(std::vector<double>{1. / 3, 1. / 3, 1. / 3, 0, 1, 0, 0, 0}, {2, 4, 1});
  EXPECT_TRUE(gradcheck(
      [&](auto& p) {
        Rng r(21);
        const Tensor& x = p[0];
        Tensor h = layer_norm(x, p[1], p[2]);
        Tensor qkv = linear(h, p[3], p[4]);
        Tensor a = packed_attention(qkv, 2, mask, 0.25, true, r);
        Tensor y = x + dropout(linear(a, p[5]), 0.25, true, r);
        Tensor f = linear(relu(linear(layer_norm(y, Tensor(), Tensor()), p[6])), p[7]);
        return sum((y + f) * pool_w, {1});
      },
      {rand({2, 4, 8}), rand({8}, 0.5, 1.5), rand({8}), rand({24, 8}), rand({24}), rand({8, 8}), rand({16, 8}),
       rand({8, 16})}));
}

}  // namespace
}  // namespace lc2wf
