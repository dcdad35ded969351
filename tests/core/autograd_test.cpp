// Tape semantics: accumulation, graph freeing, NoGradGuard, detach, and clear errors on misuse.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>

#include "core/autograd.h"
#include "core/ops.h"

using ::testing::HasSubstr;

namespace lc2wf {
namespace {

Tensor leaf(std::vector<double> v, Shape s) { return Tensor::from_vector(v, s).set_requires_grad(); }

TEST(Autograd, GradientsAccumulateAcrossBackwardCalls) {
  Tensor x = leaf({1, 2, 3}, {3});
  sum(x * x).backward();
  EXPECT_EQ(x.grad().to_vector(), (std::vector<double>{2, 4, 6}));
  sum(x * 3.0).backward();
  EXPECT_EQ(x.grad().to_vector(), (std::vector<double>{5, 7, 9}));
  x.zero_grad();
  EXPECT_FALSE(x.grad().defined());
}

TEST(Autograd, SharedSubexpressionsSumTheirContributions) {
  Tensor x = leaf({2}, {1});
  Tensor y = x * x;             // 4
  Tensor z = y * x + y * 2.0;   // x^3 + 2x^2
  sum(z).backward();
  EXPECT_DOUBLE_EQ(x.grad().item(), 3 * 4 + 4 * 2);  // 3x^2 + 4x
}

TEST(Autograd, GraphIsFreedUnlessRetained) {
  Tensor x = leaf({1, 2}, {2});
  Tensor loss = sum(exp(x));
  loss.backward(Tensor(), true);
  loss.backward();  // retained once, so a second pass works
  EXPECT_NEAR(x.grad().to_vector()[0], 2 * std::exp(1.0), 1e-12);
  EXPECT_THROW(loss.backward(), std::invalid_argument);
}

TEST(Autograd, GraphNodesAreReleasedAfterBackward) {
  int64_t before = live_node_count();
  {
    Tensor x = leaf({1, 2, 3}, {3});
    Tensor loss = sum(relu(x * 2.0 + 1.0));
    EXPECT_GT(live_node_count(), before);
    loss.backward();
  }
  EXPECT_EQ(live_node_count(), before);
}

TEST(Autograd, NoGradGuardRecordsNothing) {
  Tensor x = leaf({1, 2, 3}, {3});
  Tensor w = leaf({1, 1, 1, 1, 1, 1}, {2, 3});
  int64_t before = live_node_count();
  NoGradGuard guard;
  EXPECT_FALSE(grad_enabled());
  Tensor y = sum(softmax(linear(x.reshape({1, 3}), w), -1));
  EXPECT_FALSE(y.requires_grad());
  EXPECT_EQ(live_node_count(), before);
}

TEST(Autograd, GuardRestoresPreviousMode) {
  {
    NoGradGuard a;
    {
      NoGradGuard b;
    }
    EXPECT_FALSE(grad_enabled());
  }
  EXPECT_TRUE(grad_enabled());
}

TEST(Autograd, DetachStopsGradientsAndSharesStorage) {
  Tensor x = leaf({1, 2}, {2});
  Tensor d = x.detach();
  EXPECT_FALSE(d.requires_grad());
  EXPECT_EQ(d.data<double>(), x.data<double>());
  Tensor loss = sum(x * d);
  loss.backward();
  EXPECT_EQ(x.grad().to_vector(), (std::vector<double>{1, 2}));
}

TEST(Autograd, SeededBackwardOnNonScalar) {
  Tensor x = leaf({1, 2, 3}, {3});
  Tensor y = x * 2.0;
  y.backward(Tensor::from_vector(std::vector<double>{1, 0, -1}, {3}));
  EXPECT_EQ(x.grad().to_vector(), (std::vector<double>{2, 0, -2}));
}

TEST(Autograd, LeafAndRequiresGradFlags) {
  Tensor x = leaf({1}, {1});
  Tensor y = x * 2.0;
  EXPECT_TRUE(x.is_leaf());
  EXPECT_FALSE(y.is_leaf());
  EXPECT_TRUE(y.requires_grad());
  EXPECT_THROW(y.set_requires_grad(false), std::invalid_argument);
  Tensor c = Tensor::ones({2}) * 3.0;
  EXPECT_FALSE(c.requires_grad());
}

TEST(Autograd, IntermediateGradientDoesNotAliasLeafGradient) {
  Tensor x = leaf({1, 2}, {2});
  Tensor y = leaf({3, 4}, {2});
  sum(x + y).backward();
  x.grad().data<double>()[0] = 100;
  EXPECT_EQ(y.grad().to_vector()[0], 1.0);
}

TEST(Autograd, NodeReachedWithoutGradientStillReleasesItsInputs) {
  // y feeds two consumers; one of them passes no gradient back. x must still get the other path's.
  Tensor x = leaf({1, 2}, {2});
  Tensor y = x * 3.0;
  Tensor silent = Tensor::zeros({2}, DType::F64);
  record(silent, "silent", {y}, [](const Tensor&) -> std::vector<Tensor> { return {Tensor()}; });
  Tensor loss = sum(silent + y * 2.0);
  loss.backward();
  EXPECT_EQ(x.grad().to_vector(), (std::vector<double>{6, 6}));
}

TEST(Errors, ShapeMismatchNamesBothShapes) {
  Tensor a = Tensor::zeros({2, 3}), b = Tensor::zeros({4});
  try {
    add(a, b);
    FAIL() << "expected std::invalid_argument";
  } catch (const std::invalid_argument& e) {
    std::string msg = e.what();
    EXPECT_THAT(msg, HasSubstr("[2, 3]")) << msg;
    EXPECT_THAT(msg, HasSubstr("[4]")) << msg;
  }
  EXPECT_THROW(matmul(Tensor::zeros({2, 3}), Tensor::zeros({2, 3})), std::invalid_argument);
  EXPECT_THROW(linear(Tensor::zeros({2, 3}), Tensor::zeros({4, 2})), std::invalid_argument);
  EXPECT_THROW(Tensor::zeros({6}).reshape({4, -1}), std::invalid_argument);
  EXPECT_THROW(concat({Tensor::zeros({2, 3}), Tensor::zeros({3, 3})}, 1), std::invalid_argument);
  EXPECT_THROW(mse_loss(Tensor::zeros({3}), Tensor::zeros({3, 1})), std::invalid_argument);
  Tensor rm, rv;
  EXPECT_THROW(batch_norm(Tensor::zeros({1, 4}), Tensor(), Tensor(), rm, rv, true), std::invalid_argument);
  Rng rng(1);
  EXPECT_THROW(packed_attention(Tensor::zeros({2, 4, 12}), 5, Tensor(), 0.0, false, rng), std::invalid_argument);
}

TEST(Errors, WrongDtype) {
  EXPECT_THROW(add(Tensor::zeros({2}), Tensor::zeros({2}, DType::F64)), std::invalid_argument);
  EXPECT_THROW(exp(Tensor::zeros({2}, DType::I64)), std::invalid_argument);
  EXPECT_THROW(Tensor::zeros({2}).data<double>(), std::invalid_argument);
  EXPECT_THROW(Tensor::zeros({2}, DType::I64).set_requires_grad(), std::invalid_argument);
  EXPECT_THROW(masked_fill(Tensor::zeros({2}), Tensor::zeros({2}), 0.0), std::invalid_argument);
  EXPECT_THROW(cross_entropy(Tensor::zeros({2, 3}), Tensor::zeros({2})), std::invalid_argument);
  EXPECT_THROW(index_select(Tensor::zeros({2, 3}), 0, Tensor::zeros({2})), std::invalid_argument);
}

TEST(Errors, BadIndicesAndTargets) {
  Tensor a = Tensor::zeros({2, 3});
  EXPECT_THROW(index_select(a, 1, Tensor::from_vector(std::vector<int64_t>{3}, {1})), std::invalid_argument);
  EXPECT_THROW(gather(a, 1, Tensor::from_vector(std::vector<int64_t>{0, -1}, {2, 1})), std::invalid_argument);
  EXPECT_THROW(cross_entropy(a, Tensor::from_vector(std::vector<int64_t>{0, 3}, {2})), std::invalid_argument);
  EXPECT_THROW(sum(a, {2}), std::invalid_argument);
  EXPECT_THROW(a.item(), std::invalid_argument);
}

TEST(Errors, BackwardOnNonScalarWithoutSeed) {
  Tensor x = leaf({1, 2}, {2});
  Tensor y = x * 2.0;
  try {
    y.backward();
    FAIL() << "expected std::invalid_argument";
  } catch (const std::invalid_argument& e) {
    EXPECT_THAT(std::string(e.what()), HasSubstr("seed")) << e.what();
  }
  EXPECT_THROW(y.backward(Tensor::ones({3}, DType::F64)), std::invalid_argument);
  EXPECT_THROW(Tensor::ones({1}).backward(), std::invalid_argument);  // does not require grad
}

TEST(Errors, GradientShapeMismatchNamesBothShapes) {
  Tensor x = leaf({1, 2, 3}, {3});
  Tensor y = x * 1.0;
  Tensor out = Tensor::zeros({1}, DType::F64);
  // A deliberately wrong backward closure.
  record(out, "broken", {y}, [](const Tensor&) -> std::vector<Tensor> { return {Tensor::ones({2}, DType::F64)}; });
  try {
    out.backward();
    FAIL() << "expected std::invalid_argument";
  } catch (const std::invalid_argument& e) {
    std::string msg = e.what();
    EXPECT_THAT(msg, HasSubstr("[2]")) << msg;
    EXPECT_THAT(msg, HasSubstr("[3]")) << msg;
  }
}

}  // namespace
}  // namespace lc2wf
