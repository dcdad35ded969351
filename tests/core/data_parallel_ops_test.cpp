// What data-parallel training needs from the engine: dropout masks that do not depend on how a batch
// is cut into slices, a hook when a leaf's gradient is final, and BatchNorm statistics summed over
// processes (two threads stand in for two processes here; the trainer's MPI runs are in tests/train).
#include <gtest/gtest.h>

#include <barrier>
#include <cstring>
#include <map>
#include <thread>
#include <vector>

#include "core/autograd.h"
#include "core/ops.h"
#include "tests/core/gradcheck.h"

namespace lc2wf {
namespace {

Tensor rand32(const Shape& s, uint64_t seed) {
  Rng rng(seed);
  return test::random_tensor(s, rng, -1, 1, DType::F32);
}

std::vector<float> values(const Tensor& t) { return {t.data<float>(), t.data<float>() + t.numel()}; }

// Rows [first, first + count) of a (B, ...) tensor, as a new leaf.
Tensor rows(const Tensor& t, int64_t first, int64_t count) {
  Shape s = t.shape();
  const int64_t per = t.numel() / s[0];
  s[0] = count;
  std::vector<float> v(t.data<float>() + first * per, t.data<float>() + (first + count) * per);
  return Tensor::from_vector(v, s);
}

std::vector<float> concat(const std::vector<Tensor>& parts) {
  std::vector<float> out;
  for (const Tensor& p : parts) {
    const std::vector<float> v = values(p);
    out.insert(out.end(), v.begin(), v.end());
  }
  return out;
}

// Runs op on the whole batch and on the given slices of it (each slice restarting from the same
// counter, as the passes of one step do); every output and input gradient must be bitwise equal.
void expect_slices_match(const Tensor& x, const std::vector<std::pair<int64_t, int64_t>>& slices,
                         const std::function<Tensor(const Tensor&, Rng&)>& op) {
  const int64_t B = x.size(0);
  Rng whole_rng(77);
  whole_rng.reserve(12345);  // any stream position
  Tensor whole_x = x.detach().clone().set_requires_grad();
  Tensor whole = op(whole_x, whole_rng);
  sum(mul(whole, whole)).backward();

  Rng rng(77);
  rng.reserve(12345);
  const uint64_t start = rng.counter();
  std::vector<Tensor> outs, grads;
  for (const auto& [first, count] : slices) {
    rng.set_state(rng.seed(), start);
    rng.set_batch_slice(static_cast<uint64_t>(first), static_cast<uint64_t>(count), static_cast<uint64_t>(B));
    Tensor part_x = rows(x, first, count).set_requires_grad();
    Tensor y = op(part_x, rng);
    sum(mul(y, y)).backward();
    outs.push_back(y);
    grads.push_back(part_x.grad());
  }
  EXPECT_EQ(rng.counter(), whole_rng.counter()) << "a sliced pass must consume the whole batch's draws";
  EXPECT_EQ(concat(outs), values(whole));
  EXPECT_EQ(concat(grads), values(whole_x.grad()));
}

TEST(DataParallelOps, DropoutMasksDoNotDependOnBatchSlices) {
  // 21 elements per building: slice offsets are not multiples of the vector width.
  const Tensor x = rand32({5, 3, 7}, 1);
  auto op = [](const Tensor& t, Rng& rng) { return dropout(t, 0.4, true, rng); };
  expect_slices_match(x, {{0, 2}, {2, 2}, {4, 1}}, op);
  expect_slices_match(x, {{0, 1}, {1, 4}}, op);
}

TEST(DataParallelOps, AttentionDropoutMasksDoNotDependOnBatchSlices) {
  // (B, L, 3E), 2 heads: L = 9 keys and head size 4 (the reference kernel, odd rows), and L = 16 with head
  // size 8 (the fused kernel's 8-lane masks).
  for (const auto& [L, E] : {std::pair<int64_t, int64_t>{9, 8}, {16, 16}}) {
    const Tensor qkv = rand32({4, L, 3 * E}, 2 + static_cast<uint64_t>(L));
    auto op = [](const Tensor& t, Rng& rng) { return packed_attention(t, 2, Tensor(), 0.3, true, rng); };
    expect_slices_match(qkv, {{0, 1}, {1, 2}, {3, 1}}, op);
  }
}

TEST(DataParallelOps, UnslicedDrawsAreTheStreamAsBefore) {
  Rng a(5), b(5);
  const Rng::TensorDraws d = a.reserve_tensor(100);
  EXPECT_EQ(d.first, b.reserve(100));
  EXPECT_EQ(d.offset, 0u);
  a.set_batch_slice(0, 4, 4);  // the whole batch is no slice
  EXPECT_EQ(a.reserve_tensor(100).first, b.reserve(100));
  a.set_batch_slice(1, 2, 4);
  EXPECT_THROW(a.reserve_tensor(101), std::invalid_argument);  // not 2 equal buildings
  EXPECT_THROW(a.set_batch_slice(3, 2, 4), std::invalid_argument);
}

TEST(DataParallelOps, LeafHookFiresOnceWithTheFinalGradient) {
  Tensor a = rand32({6}, 3).set_requires_grad();
  Tensor b = rand32({6}, 4).set_requires_grad();
  Tensor unused = rand32({6}, 5).set_requires_grad();
  std::map<const TensorImpl*, std::vector<std::vector<float>>> seen;
  {
    LeafGradReadyHook hook([&](const TensorImpl* leaf) {
      if (leaf != a.impl() && leaf != b.impl()) return;  // the recomputation's own leaves
      seen[leaf].push_back(values((leaf == a.impl() ? a : b).grad()));
    });
    // a reaches the loss on three paths, b on one; the recomputed product builds a graph of its own.
    Tensor ab = checkpoint({a, b}, [](const std::vector<Tensor>& in, bool) { return mul(in[0], in[1]); });
    sum(add(add(ab, mul(a, a)), exp(a))).backward();
  }
  ASSERT_EQ(seen.count(a.impl()), 1u);
  ASSERT_EQ(seen.count(b.impl()), 1u);
  EXPECT_EQ(seen.count(unused.impl()), 0u);
  ASSERT_EQ(seen[a.impl()].size(), 1u);
  ASSERT_EQ(seen[b.impl()].size(), 1u);
  EXPECT_EQ(seen[a.impl()][0], values(a.grad()));
  EXPECT_EQ(seen[b.impl()][0], values(b.grad()));
  // No hook outside the guard.
  a.zero_grad();
  sum(mul(a, a)).backward();
  EXPECT_EQ(seen[a.impl()].size(), 1u);
}

// Two threads, one half of the rows each, summing through a shared buffer: the synchronised statistics
// and every gradient match one batch_norm over all rows up to rounding.
TEST(DataParallelOps, SynchronisedBatchNormMatchesOneBatch) {
  const int64_t M = 150, C = 5;
  Tensor x = rand32({M, C}, 6);
  // Offset channels: the sums of squares must not lose the variance.
  for (int64_t i = 0; i < M * C; ++i) x.data<float>()[i] += 40.0f * static_cast<float>(i % C);
  const Tensor w = rand32({C}, 7), bias = rand32({C}, 8), g = rand32({M, C}, 9);

  auto run = [&](const Tensor& xs, const Tensor& gs, Tensor& mean, Tensor& var, Tensor& dw, Tensor& db) {
    Tensor xin = xs.detach().clone().set_requires_grad();
    Tensor win = w.detach().clone().set_requires_grad(), bin = bias.detach().clone().set_requires_grad();
    Tensor y = batch_norm(xin, win, bin, mean, var, true, 0.1, 1e-5);
    sum(mul(y, gs)).backward();
    dw = win.grad();
    db = bin.grad();
    return std::pair<Tensor, Tensor>{y, xin.grad()};
  };
  Tensor mean_all = Tensor::zeros({C}), var_all = Tensor::ones({C}), dw_all, db_all;
  const auto [y_all, dx_all] = run(x, g, mean_all, var_all, dw_all, db_all);

  const int64_t split = 64;  // unequal halves
  std::barrier sync_point(2);
  std::vector<double> shared;
  std::vector<double> contributions[2];
  Tensor mean[2] = {Tensor::zeros({C}), Tensor::zeros({C})}, var[2] = {Tensor::ones({C}), Tensor::ones({C})};
  Tensor y[2], dx[2], dw[2], db[2];
  auto rank = [&](int r) {
    BatchNormSyncGuard guard([&, r](double* v, int64_t n) {
      contributions[r].assign(v, v + n);
      sync_point.arrive_and_wait();
      for (int64_t i = 0; i < n; ++i) v[i] = contributions[0][i] + contributions[1][i];
      sync_point.arrive_and_wait();
    });
    const int64_t first = r == 0 ? 0 : split, count = r == 0 ? split : M - split;
    std::tie(y[r], dx[r]) = run(rows(x, first, count), rows(g, first, count), mean[r], var[r], dw[r], db[r]);
  };
  std::thread other(rank, 1);
  rank(0);
  other.join();

  auto near = [](const std::vector<float>& a, const std::vector<float>& b, float tol, const char* what) {
    ASSERT_EQ(a.size(), b.size()) << what;
    for (size_t i = 0; i < a.size(); ++i) EXPECT_NEAR(a[i], b[i], tol * (1.0f + std::abs(b[i]))) << what << " " << i;
  };
  near(concat({y[0], y[1]}), values(y_all), 1e-4f, "output");
  near(concat({dx[0], dx[1]}), values(dx_all), 1e-4f, "dx");
  for (int r : {0, 1}) {
    near(values(mean[r]), values(mean_all), 1e-5f, "running_mean");
    near(values(var[r]), values(var_all), 1e-4f, "running_var");
  }
  // Parameter gradients stay per process: their sum is the whole batch's.
  near(values(add(dw[0], dw[1])), values(dw_all), 1e-3f, "dweight");
  near(values(add(db[0], db[1])), values(db_all), 1e-4f, "dbias");
}

}  // namespace
}  // namespace lc2wf
