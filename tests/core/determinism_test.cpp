// Same inputs and seed -> bit-identical results at 1 and 2 threads.
#include <gtest/gtest.h>

#include <cstring>
#include <functional>

#include "core/ops.h"
#include "core/parallel.h"
#include "tests/core/gradcheck.h"
#include "tests/core/tiny_mlp.h"

namespace lc2wf {
namespace {

// Runs fn at the given thread count and returns every output tensor's bytes.
std::vector<std::vector<float>> run_at(int threads, const std::function<std::vector<Tensor>()>& fn) {
  int previous = num_threads();
  set_num_threads(threads);
  std::vector<Tensor> outs = fn();
  set_num_threads(previous);
  std::vector<std::vector<float>> bytes;
  for (const Tensor& t : outs) bytes.emplace_back(t.data<float>(), t.data<float>() + t.numel());
  return bytes;
}

void expect_bitwise_equal(const std::function<std::vector<Tensor>()>& fn) {
  auto one = run_at(1, fn);
  auto two = run_at(2, fn);
  ASSERT_EQ(one.size(), two.size());
  for (size_t i = 0; i < one.size(); ++i) {
    ASSERT_EQ(one[i].size(), two[i].size());
    EXPECT_EQ(std::memcmp(one[i].data(), two[i].data(), one[i].size() * sizeof(float)), 0) << "output " << i;
  }
}

Tensor rand32(const Shape& s, uint64_t seed) {
  Rng rng(seed);
  return test::random_tensor(s, rng, -1, 1, DType::F32);
}

TEST(Determinism, LinearForwardBackward) {
  expect_bitwise_equal([] {
    Tensor x = rand32({1000, 256}, 1).set_requires_grad();
    Tensor w = rand32({192, 256}, 2).set_requires_grad();
    Tensor b = rand32({192}, 3).set_requires_grad();
    Tensor y = linear(x, w, b);
    sum(mul(y, rand32({1000, 192}, 4))).backward();
    return std::vector<Tensor>{y, x.grad(), w.grad(), b.grad()};
  });
}

TEST(Determinism, AttentionWithMaskAndDropout) {
  expect_bitwise_equal([] {
    Tensor qkv = rand32({40, 32, 3 * 64}, 5).set_requires_grad();
    std::vector<uint8_t> m(40 * 32);
    for (size_t i = 0; i < m.size(); ++i) m[i] = (i % 32) >= 20 + (i / 32) % 12;
    Tensor mask = Tensor::from_mask(m, {40, 32});
    Rng rng(77);
    Tensor out = packed_attention(qkv, 4, mask, 0.1, true, rng);
    sum(mul(out, rand32({40, 32, 64}, 6))).backward();
    return std::vector<Tensor>{out, qkv.grad()};
  });
}

TEST(Determinism, BatchNormAndLayerNorm) {
  expect_bitwise_equal([] {
    Tensor x = rand32({3000, 64}, 7).set_requires_grad();
    Tensor w = rand32({64}, 8).set_requires_grad();
    Tensor rm = Tensor::zeros({64}), rv = Tensor::ones({64});
    Tensor y = layer_norm(batch_norm(x, w, Tensor(), rm, rv, true), w, Tensor());
    sum(mul(y, rand32({3000, 64}, 9))).backward();
    return std::vector<Tensor>{y, x.grad(), w.grad(), rm, rv};
  });
}

TEST(Determinism, RecomputeOps) {
  expect_bitwise_equal([] {
    Tensor x = rand32({2000, 64}, 20).set_requires_grad();
    Tensor nw = rand32({64}, 21).set_requires_grad(), w = rand32({96, 64}, 22).set_requires_grad();
    Tensor w2 = rand32({48, 96}, 23).set_requires_grad();
    Tensor rm = Tensor::zeros({96}), rv = Tensor::ones({96});
    Tensor y = checkpoint({x, nw, w, w2}, [&](const std::vector<Tensor>& p, bool recompute) {
      Tensor none, mean = recompute ? none : rm, var = recompute ? none : rv;
      Tensor h = layer_norm_linear(p[0], p[1], Tensor(), 1e-5, p[2]);
      return linear(relu(batch_norm(h, Tensor(), Tensor(), mean, var, true)), p[3]);
    });
    sum(mul(y, rand32({2000, 48}, 24))).backward();
    return std::vector<Tensor>{y, x.grad(), nw.grad(), w.grad(), w2.grad(), rm, rv};
  });
}

TEST(Determinism, Sums) {
  expect_bitwise_equal([] {
    Tensor x = rand32({700, 300, 5}, 10);
    return std::vector<Tensor>{sum(x), sum(x, {0}), sum(x, {0, 1}), mean(x, {2}), max(x, {1})};
  });
}

TEST(Determinism, MlpTrainingSteps) {
  expect_bitwise_equal([] {
    auto [x, y] = test::make_regression(2048, 8, 11);
    test::TinyMlp mlp(8, 128, 12);
    for (int i = 0; i < 3; ++i) mlp.step(x, y, 0.05);
    std::vector<Tensor> out;
    for (Tensor* p : mlp.params()) out.push_back(*p);
    return out;
  });
}

}  // namespace
}  // namespace lc2wf
