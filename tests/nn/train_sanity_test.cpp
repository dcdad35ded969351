// Training sanity on a generated toy task: does a line patch hold a corner where three plane edges
// meet (and where)? A short AdamW run of a small junction model with dropout on must cut the loss and
// classify held-out patches far better than chance.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <string>

#include "core/ops.h"
#include "nn/junction_net.h"
#include "nn/losses.h"
#include "nn/optimizer.h"

namespace lc2wf {
namespace {

constexpr int64_t kB = 4, kG = 16, kN = 8, kF = 7;

using Vec = std::array<double, 3>;

Vec random_unit(Rng& rng) {
  for (;;) {
    Vec v{rng.next_uniform(-1, 1), rng.next_uniform(-1, 1), rng.next_uniform(-1, 1)};
    const double n = std::sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
    if (n > 0.1 && n <= 1.0) return {v[0] / n, v[1] / n, v[2] / n};
  }
}

double norm(const Vec& v) { return std::sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]); }

// Distance from the origin (the sample point) to segment ab.
double origin_segment_distance(const Vec& a, const Vec& b) {
  Vec ab{b[0] - a[0], b[1] - a[1], b[2] - a[2]};
  const double len2 = ab[0] * ab[0] + ab[1] * ab[1] + ab[2] * ab[2];
  double t = len2 > 0 ? -(a[0] * ab[0] + a[1] * ab[1] + a[2] * ab[2]) / len2 : 0.0;
  t = std::clamp(t, 0.0, 1.0);
  return norm({a[0] + t * ab[0], a[1] + t * ab[1], a[2] + t * ab[2]});
}

struct Batch {
  Tensor x, mask;
  JunctionTargets targets;
};

Batch make_batch(Rng& rng) {
  std::vector<float> x(kB * kG * kN * kF), offsets(kB * kG * 3, 0.0f);
  std::vector<uint8_t> mask(kB * kG * kN);
  std::vector<int64_t> labels(kB * kG);
  for (int64_t p = 0; p < kB * kG; ++p) {
    const bool corner = rng.next_uniform() < 0.5;
    labels[p] = corner;
    const Vec c{rng.next_uniform(-0.05, 0.05), rng.next_uniform(-0.05, 0.05), rng.next_uniform(-0.05, 0.05)};
    const std::array<Vec, 3> edges{random_unit(rng), random_unit(rng), random_unit(rng)};
    if (corner)
      for (int k = 0; k < 3; ++k) offsets[p * 3 + k] = static_cast<float>(c[k]);
    const int64_t valid = 3 + static_cast<int64_t>(rng.next_below(kN - 2));
    std::vector<std::array<Vec, 2>> lines;
    for (int64_t n = 0; n < valid; ++n) {
      Vec a, b;
      if (corner) {
        const Vec& d = edges[n % 3];
        const double s0 = rng.next_uniform(0.0, 0.02), s1 = rng.next_uniform(0.1, 0.3);
        for (int k = 0; k < 3; ++k) {
          a[k] = c[k] + d[k] * s0 + rng.next_uniform(-0.005, 0.005);
          b[k] = c[k] + d[k] * s1 + rng.next_uniform(-0.005, 0.005);
        }
      } else {
        const Vec d = random_unit(rng);
        const double len = rng.next_uniform(0.1, 0.3);
        const Vec m{rng.next_uniform(-0.2, 0.2), rng.next_uniform(-0.2, 0.2), rng.next_uniform(-0.2, 0.2)};
        for (int k = 0; k < 3; ++k) a[k] = m[k] - d[k] * len / 2, b[k] = m[k] + d[k] * len / 2;
      }
      if (norm(a) > norm(b)) std::swap(a, b);
      lines.push_back({a, b});
    }
    for (int64_t n = 0; n < kN; ++n) {
      const auto& [a, b] = lines[n < valid ? n : 0];  // padded slots repeat slot 0, as the release does
      float* f = &x[(p * kN + n) * kF];
      for (int k = 0; k < 3; ++k) f[k] = static_cast<float>(a[k]), f[3 + k] = static_cast<float>(b[k]);
      f[6] = static_cast<float>(origin_segment_distance(a, b));
      mask[p * kN + n] = n >= valid;
    }
  }
  return {Tensor::from_vector(x, {kB, kG, kN, kF}), Tensor::from_mask(mask, {kB, kG, kN}),
          {Tensor::from_vector(labels, {kB, kG}), Tensor::from_vector(offsets, {kB, kG, 3})}};
}

TEST(TrainSanity, JunctionModelLearnsToyCorners) {
  JunctionNetConfig config;
  config.lpt.lines_per_patch = kN;
  config.lpt.patches = kG;
  config.lpt.mlp_dims = {16, 16, 32};
  config.lpt.hidden_dim = 32;
  config.lpt.num_heads = 4;
  config.lpt.ffn_dim = 32;
  config.lpt.dropout = 0.1;
  config.lpt.attn_dropout = 0.1;
  config.head.dims = {16, 8};
  JunctionNet net(config, 11);
  OptimConfig oc;
  oc.lr = 3e-3;
  AdamW opt(net.named_parameters(), oc);
  const JunctionLossConfig lc;  // the paper's BCE + L2

  Rng data(2024);
  const int steps = 120;
  double first = 0.0, last = 0.0;
  net.train();
  for (int s = 0; s < steps; ++s) {
    const Batch b = make_batch(data);
    opt.zero_grad();
    const LossTerms loss = junction_loss(net.forward(b.x, b.mask), b.targets, lc);
    loss.total.backward();
    opt.step();
    if (s < 10) first += loss.total.item() / 10;
    if (s >= steps - 10) last += loss.total.item() / 10;
  }
  EXPECT_LT(last, 0.5 * first) << "loss " << first << " -> " << last;

  net.eval();
  NoGradGuard no_grad;
  Rng held_out(777);
  int correct = 0, total = 0;
  for (int i = 0; i < 4; ++i) {
    const Batch b = make_batch(held_out);
    const std::vector<double> logits = net.forward(b.x, b.mask).logits.to_vector();
    const std::vector<double> labels = b.targets.labels.to_vector();
    for (size_t p = 0; p < labels.size(); ++p, ++total)
      correct += (logits[2 * p + 1] > logits[2 * p]) == (labels[p] == 1.0);
  }
  RecordProperty("loss_first_steps", std::to_string(first));
  RecordProperty("loss_last_steps", std::to_string(last));
  RecordProperty("held_out_accuracy", std::to_string(static_cast<double>(correct) / total));
  EXPECT_GT(static_cast<double>(correct) / total, 0.85) << correct << " / " << total << " (chance 0.5)";
}

}  // namespace
}  // namespace lc2wf
