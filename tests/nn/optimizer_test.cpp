// Optimisers against PyTorch trajectories (tests/data/nn/optimizers.safetensors) plus clipping and the
// learning-rate schedule.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>

#include "core/ops.h"
#include "nn/optimizer.h"
#include "test_util.h"

using ::testing::HasSubstr;

namespace lc2wf {
namespace {

using test::close;
using test::get;

// Sets p.grad to g through a real backward pass: d/dp sum(p * g) = g.
void set_grad(Tensor& p, const Tensor& g) {
  p.zero_grad();
  sum(mul(p, g)).backward();
}

void run_trajectory(const std::string& kind) {
  const SafetensorsFile f = read_safetensors(test::fixture("optimizers.safetensors"));
  Tensor w = get(f, "init.layer.weight").clone().detach().set_requires_grad(true);
  Tensor b = get(f, "init.layer.bias").clone().detach().set_requires_grad(true);
  OptimConfig c;
  c.optimizer = kind;
  c.lr = 0.01;
  c.weight_decay = 0.1;  // the name rule exempts "layer.bias"
  c.momentum = 0.9;
  auto opt = kind == "adamw" ? std::unique_ptr<Optimizer>(new AdamW({{"layer.weight", w}, {"layer.bias", b}}, c))
                             : std::unique_ptr<Optimizer>(new Sgd({{"layer.weight", w}, {"layer.bias", b}}, c));
  for (int i = 0; i < 3; ++i) {
    set_grad(w, get(f, "grad" + std::to_string(i) + ".layer.weight"));
    set_grad(b, get(f, "grad" + std::to_string(i) + ".layer.bias"));
    opt->step();
    const std::string prefix = kind + ".step" + std::to_string(i) + ".layer.";
    EXPECT_TRUE(close(w, get(f, prefix + "weight"), 1e-5, 1e-7)) << prefix;
    EXPECT_TRUE(close(b, get(f, prefix + "bias"), 1e-5, 1e-7)) << prefix;
  }
  EXPECT_EQ(opt->step_count(), 3);
}

TEST(Optimizer, AdamWMatchesPyTorch) { run_trajectory("adamw"); }
TEST(Optimizer, SgdMomentumMatchesPyTorch) { run_trajectory("sgd"); }

TEST(Optimizer, SkipsParametersWithoutGradient) {
  Tensor w = Tensor::ones({2}).set_requires_grad(true);
  AdamW opt({{"w", w}}, OptimConfig{});
  opt.step();
  EXPECT_EQ(w.to_vector(), (std::vector<double>{1.0, 1.0}));
}

TEST(Optimizer, StateRoundTripsAndRejectsWrongTensors) {
  Tensor w = Tensor::ones({2, 2}).set_requires_grad(true);
  AdamW opt({{"w", w}}, OptimConfig{});
  set_grad(w, Tensor::full({2, 2}, 0.5));
  opt.step();
  std::map<std::string, Tensor> state;
  for (auto& [name, t] : opt.state()) state[name] = t.clone();
  EXPECT_EQ(state.size(), 2u);
  EXPECT_TRUE(state.count("exp_avg.w") && state.count("exp_avg_sq.w"));

  Tensor w2 = Tensor::ones({2, 2}).set_requires_grad(true);
  AdamW opt2({{"w", w2}}, OptimConfig{});
  opt2.load_state(state, opt.step_count(), "test");
  EXPECT_EQ(opt2.step_count(), 1);
  EXPECT_EQ(opt2.state()[0].second.to_vector(), state["exp_avg.w"].to_vector());

  auto bad = state;
  bad.erase("exp_avg.w");
  EXPECT_THROW(
      {
        try {
          opt2.load_state(bad, 1, "f.optim");
        } catch (const std::invalid_argument& e) {
          EXPECT_THAT(std::string(e.what()), HasSubstr("exp_avg.w"));
          throw;
        }
      },
      std::invalid_argument);
  bad = state;
  bad["exp_avg.w"] = Tensor::zeros({4});
  EXPECT_THROW(opt2.load_state(bad, 1, "f.optim"), std::invalid_argument);
}

TEST(Optimizer, ClipGradNormScalesOnlyAboveTheLimit) {
  Tensor a = Tensor::zeros({2}).set_requires_grad(true);
  Tensor b = Tensor::zeros({1}).set_requires_grad(true);
  set_grad(a, Tensor::from_vector(std::vector<float>{3, 0}, {2}));
  set_grad(b, Tensor::from_vector(std::vector<float>{4}, {1}));
  EXPECT_NEAR(clip_grad_norm({a, b}, 10.0), 5.0, 1e-6);
  EXPECT_NEAR(a.grad().to_vector()[0], 3.0, 1e-6);  // below the limit: untouched
  EXPECT_NEAR(clip_grad_norm({a, b}, 1.0), 5.0, 1e-6);
  EXPECT_NEAR(a.grad().to_vector()[0], 0.6, 1e-5);
  EXPECT_NEAR(b.grad().to_vector()[0], 0.8, 1e-5);
}

TEST(Optimizer, MultiStepLRFollowsTheReleaseSchedule) {
  const MultiStepLR s(1e-3, {15, 30, 41}, 0.1);
  EXPECT_DOUBLE_EQ(s.lr_at(0), 1e-3);
  EXPECT_DOUBLE_EQ(s.lr_at(14), 1e-3);
  EXPECT_NEAR(s.lr_at(15), 1e-4, 1e-18);
  EXPECT_NEAR(s.lr_at(29), 1e-4, 1e-18);
  EXPECT_NEAR(s.lr_at(30), 1e-5, 1e-18);
  EXPECT_NEAR(s.lr_at(41), 1e-6, 1e-18);
}

}  // namespace
}  // namespace lc2wf
