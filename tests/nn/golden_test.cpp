// The proof against an independent implementation: fixtures written by tools/make_golden.py from a
// PyTorch model (float64) are matched by our networks in float32 — outputs, BatchNorm running
// statistics, both junction losses, the edge loss and the gradient of every parameter.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>

#include <nlohmann/json.hpp>

#include "core/matmul_precision.h"
#include "core/ops.h"
#include "nn/edge_net.h"
#include "nn/junction_net.h"
#include "nn/losses.h"
#include "test_util.h"

namespace lc2wf {
namespace {

using test::close;
using test::get;
using test::with_prefix;

// Relative 1e-4 per tensor, with an absolute floor of 1e-6 of the largest gradient of the model: the
// biases in front of a BatchNorm have an exactly-zero gradient, which float32 only reaches up to
// rounding.
void expect_grads(const Module& model, const SafetensorsFile& f, const std::string& prefix) {
  const auto ref = with_prefix(f, prefix);
  const auto params = model.named_parameters();
  ASSERT_EQ(ref.size(), params.size());
  double scale = 0.0;
  for (const auto& [name, g] : ref)
    for (double v : g.to_vector()) scale = std::max(scale, std::abs(v));
  for (const auto& [name, p] : params) {
    ASSERT_TRUE(p.grad().defined()) << name;
    EXPECT_TRUE(close(p.grad(), ref.at(name), 1e-4, 1e-6 * scale)) << "gradient of " << name;
  }
}

void expect_running_stats(const Module& model, const SafetensorsFile& f) {
  const auto ref = with_prefix(f, "train.after.");
  ASSERT_FALSE(ref.empty());
  for (const auto& [name, b] : model.named_buffers()) EXPECT_TRUE(close(b, ref.at(name))) << name;
}

// bf16 bounds (GoldenBf16 below), relative to the largest reference value of each tensor.
// Measured worst cases: outputs 2.0e-2 (small junction net; 4.4e-3 at paper size), losses 3.2e-3, gradient
// norms 0.114 (the first MLP layer behind its BatchNorm, whose backward cancels most of the signal; 2.1e-2
// in the edge net).
constexpr double kBf16OutputTolerance = 0.05;
constexpr double kBf16LossTolerance = 0.01;
constexpr double kBf16GradientTolerance = 0.3;

TEST(Golden, JunctionTrainModeOutputsLossesAndGradients) {
  const SafetensorsFile f = read_safetensors(test::fixture("junction_small.safetensors"));
  const auto config = JunctionNetConfig::from_json(nlohmann::json::parse(f.metadata.at("config")));
  JunctionNet net(config, 7);
  net.load_state_dict(with_prefix(f, "init."), "junction_small init");
  net.train();
  const JunctionOutput out = net.forward(get(f, "input.x"), get(f, "input.mask"));
  EXPECT_TRUE(close(out.logits, get(f, "train.logits")));
  EXPECT_TRUE(close(out.offsets, get(f, "train.offsets")));
  expect_running_stats(net, f);

  const JunctionTargets targets{get(f, "target.labels"), get(f, "target.offsets")};
  for (const std::string kind : {"release", "paper"}) {
    SCOPED_TRACE(kind);
    JunctionLossConfig lc;
    lc.kind = kind;
    const LossTerms loss = junction_loss(out, targets, lc);
    EXPECT_TRUE(close(loss.classification, get(f, "loss." + kind + ".classification"), 1e-5, 0));
    EXPECT_TRUE(close(loss.regression, get(f, "loss." + kind + ".regression"), 1e-5, 0));
    EXPECT_TRUE(close(loss.total, get(f, "loss." + kind + ".total"), 1e-5, 0));
    net.zero_grad();
    loss.total.backward(Tensor(), /*retain_graph=*/true);
    expect_grads(net, f, "grad." + kind + ".");
  }
}

TEST(Golden, JunctionEvalModeUsesRunningStatistics) {
  const SafetensorsFile f = read_safetensors(test::fixture("junction_small.safetensors"));
  JunctionNet net(JunctionNetConfig::from_json(nlohmann::json::parse(f.metadata.at("config"))));
  net.load_state_dict(with_prefix(f, "eval.state."));
  net.eval();
  NoGradGuard no_grad;
  const JunctionOutput out = net.forward(get(f, "input.x"), get(f, "input.mask"));
  EXPECT_TRUE(close(out.logits, get(f, "eval.logits")));
  EXPECT_TRUE(close(out.offsets, get(f, "eval.offsets")));
}

TEST(Golden, EdgeTrainModeWeightedLossAndGradients) {
  const SafetensorsFile f = read_safetensors(test::fixture("edge_small.safetensors"));
  const auto config = EdgeNetConfig::from_json(nlohmann::json::parse(f.metadata.at("config")));
  ASSERT_EQ(config.lpt.pool, "mean_valid");
  EdgeNet net(config, 3);
  net.load_state_dict(with_prefix(f, "init."));
  net.train();
  const Tensor logits = net.forward(get(f, "input.x"), get(f, "input.mask"));
  EXPECT_TRUE(close(logits, get(f, "train.logits")));
  expect_running_stats(net, f);
  const Tensor loss = edge_loss(logits, get(f, "target.labels"), EdgeLossConfig{});
  EXPECT_TRUE(close(loss, get(f, "loss.edge"), 1e-5, 0));
  loss.backward();
  expect_grads(net, f, "grad.edge.");
}

TEST(Golden, EdgeEvalMode) {
  const SafetensorsFile f = read_safetensors(test::fixture("edge_small.safetensors"));
  EdgeNet net(EdgeNetConfig::from_json(nlohmann::json::parse(f.metadata.at("config"))));
  net.load_state_dict(with_prefix(f, "eval.state."));
  net.eval();
  NoGradGuard no_grad;
  EXPECT_TRUE(close(net.forward(get(f, "input.x"), get(f, "input.mask")), get(f, "eval.logits")));
}

// Both networks at the paper's sizes with the fixture's hashed weights, in eval mode.
struct PaperSizeOutputs {
  JunctionOutput junction;
  Tensor edge_logits;
};

PaperSizeOutputs paper_size_forward(const SafetensorsFile& f) {
  NoGradGuard no_grad;
  JunctionNet junction{JunctionNetConfig{}};
  test::fill_hashed(junction);
  junction.eval();
  EdgeNet edge{EdgeNetConfig{}};
  test::fill_hashed(edge);
  edge.eval();
  return {junction.forward(get(f, "junction.x"), get(f, "junction.mask")), edge.forward(get(f, "edge.x"), get(f, "edge.mask"))};
}

TEST(Golden, FullPaperDimensionsForward) {
  const SafetensorsFile f = read_safetensors(test::fixture("full_size_forward.safetensors"));
  const PaperSizeOutputs out = paper_size_forward(f);
  EXPECT_TRUE(close(out.junction.logits, get(f, "junction.logits")));
  EXPECT_TRUE(close(out.junction.offsets, get(f, "junction.offsets")));
  EXPECT_TRUE(close(out.edge_logits, get(f, "edge.logits")));
}

// bf16 mixed precision (core/matmul_precision.h) against the same float64 references: every GEMM operand
// is rounded to bf16 (2^-8 relative), so the bounds (kBf16*Tolerance, with the measured errors) are looser.
// Max abs error over the largest reference value.
double relative_error(const Tensor& actual, const Tensor& ref) {
  const std::vector<double> a = actual.to_vector(), b = ref.to_vector();
  double scale = 0.0, err = 0.0;
  for (size_t i = 0; i < a.size(); ++i) {
    if (!std::isfinite(a[i])) return INFINITY;
    scale = std::max(scale, std::abs(b[i]));
    err = std::max(err, std::abs(a[i] - b[i]));
  }
  return err / std::max(scale, 1e-30);
}

// Worst over the parameters of ||g - ref|| / ||ref|| (the error of a gradient's direction and length);
// tensors whose reference is ~0 (biases in front of a BatchNorm: exactly zero) are left out.
double worst_gradient_error(const Module& model, const SafetensorsFile& f, const std::string& prefix) {
  const auto ref = with_prefix(f, prefix);
  std::map<std::string, double> norms;
  double largest = 0.0;
  for (const auto& [name, g] : ref) {
    double n = 0.0;
    for (double v : g.to_vector()) n += v * v;
    largest = std::max(largest, norms[name] = std::sqrt(n));
  }
  double worst = 0.0;
  for (const auto& [name, p] : model.named_parameters()) {
    if (norms.at(name) < 1e-4 * largest) continue;
    const std::vector<double> a = p.grad().to_vector(), b = ref.at(name).to_vector();
    double err = 0.0;
    for (size_t i = 0; i < a.size(); ++i) err += (a[i] - b[i]) * (a[i] - b[i]);
    worst = std::max(worst, std::sqrt(err) / norms.at(name));
  }
  return worst;
}

TEST(GoldenBf16, JunctionAndEdgeWithinTheStatedTolerance) {
  MatmulPrecisionGuard bf16(MatmulPrecision::kBf16);
  {
    const SafetensorsFile f = read_safetensors(test::fixture("junction_small.safetensors"));
    JunctionNet net(JunctionNetConfig::from_json(nlohmann::json::parse(f.metadata.at("config"))), 7);
    net.load_state_dict(with_prefix(f, "init."));
    net.train();
    const JunctionOutput out = net.forward(get(f, "input.x"), get(f, "input.mask"));
    const double logits = relative_error(out.logits, get(f, "train.logits"));
    const double offsets = relative_error(out.offsets, get(f, "train.offsets"));
    JunctionLossConfig release;
    release.kind = "release";
    const LossTerms loss = junction_loss(out, {get(f, "target.labels"), get(f, "target.offsets")}, release);
    const double total = relative_error(loss.total, get(f, "loss.release.total"));
    loss.total.backward();
    const double grads = worst_gradient_error(net, f, "grad.release.");
    std::printf("junction bf16: logits %.2e offsets %.2e loss %.2e gradients %.2e\n", logits, offsets, total, grads);
    EXPECT_LT(logits, kBf16OutputTolerance);
    EXPECT_LT(offsets, kBf16OutputTolerance);
    EXPECT_LT(total, kBf16LossTolerance);
    EXPECT_LT(grads, kBf16GradientTolerance);
    EXPECT_GT(logits + offsets, 1e-5) << "no bf16 rounding happened";
  }
  {
    const SafetensorsFile f = read_safetensors(test::fixture("edge_small.safetensors"));
    EdgeNet net(EdgeNetConfig::from_json(nlohmann::json::parse(f.metadata.at("config"))), 3);
    net.load_state_dict(with_prefix(f, "init."));
    net.train();
    const Tensor logits = net.forward(get(f, "input.x"), get(f, "input.mask"));
    const double out = relative_error(logits, get(f, "train.logits"));
    const Tensor loss = edge_loss(logits, get(f, "target.labels"), EdgeLossConfig{});
    const double total = relative_error(loss, get(f, "loss.edge"));
    loss.backward();
    const double grads = worst_gradient_error(net, f, "grad.edge.");
    std::printf("edge bf16: logits %.2e loss %.2e gradients %.2e\n", out, total, grads);
    EXPECT_LT(out, kBf16OutputTolerance);
    EXPECT_LT(total, kBf16LossTolerance);
    EXPECT_LT(grads, kBf16GradientTolerance);
  }
  {
    const SafetensorsFile f = read_safetensors(test::fixture("full_size_forward.safetensors"));
    const PaperSizeOutputs out = paper_size_forward(f);
    const double j = std::max(relative_error(out.junction.logits, get(f, "junction.logits")),
                              relative_error(out.junction.offsets, get(f, "junction.offsets")));
    const double e = relative_error(out.edge_logits, get(f, "edge.logits"));
    std::printf("paper size bf16: junction %.2e edge %.2e\n", j, e);
    EXPECT_LT(j, kBf16OutputTolerance);
    EXPECT_LT(e, kBf16OutputTolerance);
  }
}

}  // namespace
}  // namespace lc2wf
