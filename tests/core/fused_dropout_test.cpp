// The fused dropout ops are the composed ones, bit for bit: the same values, gradients and draws, so a
// model (and a training run resumed across the change) does not notice the fusion.
#include <gtest/gtest.h>

#include <cstring>

#include "core/ops.h"
#include "tests/core/gradcheck.h"

namespace lc2wf {
namespace {

Tensor rand32(const Shape& s, uint64_t seed) {
  Rng rng(seed);
  return test::random_tensor(s, rng, -1, 1, DType::F32);
}

void expect_same_bits(const Tensor& a, const Tensor& b, const char* what) {
  ASSERT_EQ(a.shape(), b.shape()) << what;
  EXPECT_EQ(std::memcmp(a.data<float>(), b.data<float>(), static_cast<size_t>(a.numel()) * sizeof(float)), 0) << what;
}

// Large enough to be cut into several parallel chunks; odd so that a vector loop has a tail.
const Shape kShape{37, 1031};

TEST(FusedDropout, AddDropoutIsAddOfDropoutBitForBit) {
  for (double p : {0.1, 0.5}) {
    Tensor x0 = rand32(kShape, 1), a0 = rand32(kShape, 2), w = rand32(kShape, 3);
    Tensor x1 = x0.detach(), a1 = a0.detach();
    for (Tensor* t : {&x0, &a0, &x1, &a1}) t->set_requires_grad(true);
    Rng r0(11), r1(11);
    const Tensor composed = add(x0, dropout(a0, p, true, r0));
    const Tensor fused = add_dropout(x1, a1, p, true, r1);
    expect_same_bits(composed, fused, "forward");
    EXPECT_EQ(r0.counter(), r1.counter());
    sum(mul(composed, w)).backward();
    sum(mul(fused, w)).backward();
    expect_same_bits(x0.grad(), x1.grad(), "dx");
    expect_same_bits(a0.grad(), a1.grad(), "da");
  }
}

TEST(FusedDropout, DropoutReluIsReluOfDropoutBitForBit) {
  for (double p : {0.1, 0.5}) {
    Tensor a0 = rand32(kShape, 4), w = rand32(kShape, 5);
    Tensor a1 = a0.detach();
    a0.set_requires_grad(true);
    a1.set_requires_grad(true);
    Rng r0(12), r1(12);
    const Tensor composed = relu(dropout(a0, p, true, r0));
    const Tensor fused = dropout_relu(a1, p, true, r1);
    expect_same_bits(composed, fused, "forward");
    EXPECT_EQ(r0.counter(), r1.counter());
    sum(mul(composed, w)).backward();
    sum(mul(fused, w)).backward();
    expect_same_bits(a0.grad(), a1.grad(), "da");
  }
}

TEST(FusedDropout, EvalModeZeroAndOneAndBadInput) {
  Tensor x = rand32({3, 5}, 6), a = rand32({3, 5}, 7);
  Rng r(1);
  expect_same_bits(add_dropout(x, a, 0.5, false, r), add(x, a), "eval add");
  expect_same_bits(dropout_relu(a, 0.5, false, r), relu(a), "eval relu");
  expect_same_bits(add_dropout(x, a, 0.0, true, r), add(x, a), "p = 0");
  expect_same_bits(add_dropout(x, a, 1.0, true, r), add(x, mul(a, 0.0)), "p = 1");
  EXPECT_EQ(r.counter(), 0u);  // no draw when nothing is dropped at random
  EXPECT_THROW(add_dropout(x, rand32({5, 3}, 8), 0.5, true, r), std::invalid_argument);
  EXPECT_THROW(dropout_relu(a, 1.5, true, r), std::invalid_argument);
  EXPECT_THROW(add_dropout(x, a, -0.1, false, r), std::invalid_argument);
}

}  // namespace
}  // namespace lc2wf
