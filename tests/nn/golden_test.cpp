// The proof against an independent implementation: fixtures written by tools/make_golden.py from a
// PyTorch model (float64) are matched by our networks in float32 — outputs, BatchNorm running
// statistics, both junction losses, the edge loss and the gradient of every parameter.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include <nlohmann/json.hpp>

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

TEST(Golden, FullPaperDimensionsForward) {
  const SafetensorsFile f = read_safetensors(test::fixture("full_size_forward.safetensors"));
  NoGradGuard no_grad;
  JunctionNet junction{JunctionNetConfig{}};
  test::fill_hashed(junction);
  junction.eval();
  const JunctionOutput out = junction.forward(get(f, "junction.x"), get(f, "junction.mask"));
  EXPECT_TRUE(close(out.logits, get(f, "junction.logits")));
  EXPECT_TRUE(close(out.offsets, get(f, "junction.offsets")));

  EdgeNet edge{EdgeNetConfig{}};
  test::fill_hashed(edge);
  edge.eval();
  EXPECT_TRUE(close(edge.forward(get(f, "edge.x"), get(f, "edge.mask")), get(f, "edge.logits")));
}

}  // namespace
}  // namespace lc2wf
