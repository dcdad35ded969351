// Module bookkeeping, checkpoint round trips, exact resume (weights, optimiser state and dropout
// stream) and the errors for missing, unexpected and misshaped tensors.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <set>
#include <string>

#include "core/ops.h"
#include "core/util/version.h"
#include "nn/checkpoint.h"
#include "nn/junction_net.h"
#include "nn/losses.h"
#include "nn/model_checkpoint.h"
#include "nn/safetensors.h"

using ::testing::HasSubstr;
using ::testing::Not;

namespace lc2wf {
namespace {

namespace fs = std::filesystem;

JunctionNetConfig tiny_config() {
  JunctionNetConfig c;
  c.lpt.lines_per_patch = 4;
  c.lpt.patches = 5;
  c.lpt.mlp_dims = {8, 16};
  c.lpt.hidden_dim = 16;
  c.lpt.num_heads = 2;
  c.lpt.ffn_dim = 16;
  c.lpt.dropout = 0.3;
  c.lpt.attn_dropout = 0.3;
  c.head.dims = {8};
  return c;
}

struct ToyBatch {
  Tensor x, mask;
  JunctionTargets targets;
};

ToyBatch toy_batch(uint64_t seed) {
  Rng rng(seed);
  const int64_t B = 2, G = 5, N = 4, F = 7;
  std::vector<float> x(B * G * N * F), off(B * G * 3);
  for (auto& v : x) v = static_cast<float>(rng.next_uniform(-1, 1));
  for (auto& v : off) v = static_cast<float>(rng.next_uniform(-0.1, 0.1));
  std::vector<uint8_t> mask(B * G * N);
  for (size_t i = 0; i < mask.size(); ++i) mask[i] = i % N == N - 1;
  std::vector<int64_t> labels(B * G);
  for (size_t i = 0; i < labels.size(); ++i) labels[i] = i % 2;
  return {Tensor::from_vector(x, {B, G, N, F}), Tensor::from_mask(mask, {B, G, N}),
          {Tensor::from_vector(labels, {B, G}), Tensor::from_vector(off, {B, G, 3})}};
}

void train_steps(JunctionNet& net, Optimizer& opt, int steps, uint64_t data_seed) {
  net.train();
  for (int s = 0; s < steps; ++s) {
    const ToyBatch b = toy_batch(data_seed + s);
    opt.zero_grad();
    junction_loss(net.forward(b.x, b.mask), b.targets, JunctionLossConfig{}).total.backward();
    opt.step();
  }
}

fs::path temp_dir(const std::string& name) {
  const fs::path dir = fs::temp_directory_path() / ("lc2wf_ckpt_" + name + "_" + std::to_string(::getpid()));
  fs::remove_all(dir);
  fs::create_directories(dir);
  return dir;
}

std::string load_error(const fs::path& path, Module& model) {
  try {
    load_checkpoint(path, model, nullptr, nullptr);
  } catch (const std::exception& e) {
    return e.what();
  }
  return "";
}

TEST(Module, NamesCountsAndModes) {
  JunctionNet net(tiny_config());
  std::set<std::string> names;
  for (auto& [name, p] : net.named_parameters()) names.insert(name);
  EXPECT_TRUE(names.count("lpt.mlp.0.fc.weight"));
  EXPECT_TRUE(names.count("lpt.enc1.layers.0.self_attn.in_proj_weight"));
  EXPECT_TRUE(names.count("lpt.enc1.layers.0.self_attn.out_proj.bias"));
  EXPECT_TRUE(names.count("lpt.enc2.norm.weight"));
  EXPECT_TRUE(names.count("cls_head.0.bn.weight"));
  EXPECT_TRUE(names.count("reg_head.out.weight"));
  std::set<std::string> buffers;
  for (auto& [name, b] : net.named_buffers()) buffers.insert(name);
  EXPECT_TRUE(buffers.count("lpt.mlp.1.bn.running_var"));
  // The paper-size junction model: the count of the PyTorch reference (tools/make_golden.py, 1x1 convs).
  EXPECT_EQ(JunctionNet(JunctionNetConfig{}).num_parameters(), 943909);
  net.eval();
  EXPECT_FALSE(net.is_training());
  net.train();
  EXPECT_TRUE(net.is_training());
}

TEST(Module, SameSeedSameWeightsDifferentSeedDifferentWeights) {
  JunctionNet a(tiny_config(), 5), b(tiny_config(), 5), c(tiny_config(), 6);
  const auto sa = a.state_dict(), sb = b.state_dict(), sc = c.state_dict();
  EXPECT_EQ(sa[0].second.to_vector(), sb[0].second.to_vector());
  EXPECT_NE(sa[0].second.to_vector(), sc[0].second.to_vector());
}

TEST(Checkpoint, RoundTripRestoresWeightsAndOutputs) {
  const fs::path dir = temp_dir("roundtrip");
  JunctionNet a(tiny_config(), 1);
  AdamW opt(a.named_parameters(), OptimConfig{});
  train_steps(a, opt, 2, 100);
  save_checkpoint(dir / "m.safetensors", a, a.config().to_json(), a.dropout_rng(), nullptr, {1, 2});
  EXPECT_FALSE(fs::exists(optimizer_state_path(dir / "m.safetensors")));

  const CheckpointInfo info = read_checkpoint_info(dir / "m.safetensors");
  EXPECT_EQ(info.position.epoch, 1);
  EXPECT_EQ(info.position.step, 2);
  EXPECT_FALSE(info.has_optimizer);
  JunctionNet b(JunctionNetConfig::from_json(info.config), 99);
  load_checkpoint(dir / "m.safetensors", b, nullptr, nullptr);
  a.eval();
  b.eval();
  const ToyBatch t = toy_batch(7);
  EXPECT_EQ(a.forward(t.x, t.mask).logits.to_vector(), b.forward(t.x, t.mask).logits.to_vector());
  for (const auto& entry : fs::directory_iterator(dir))
    EXPECT_THAT(entry.path().filename().string(), Not(HasSubstr(".tmp"))) << "temporary file left behind";
  fs::remove_all(dir);
}

// Every checkpoint names the lc2wf version and commit that wrote it; files from before (no such keys) load.
TEST(Checkpoint, RecordsVersionAndCommitAndLoadsFilesWithout) {
  const fs::path dir = temp_dir("version");
  JunctionNet a(tiny_config(), 1);
  AdamW opt(a.named_parameters(), OptimConfig{});
  save_checkpoint(dir / "m.safetensors", a, a.config().to_json(), a.dropout_rng(), &opt, {1, 2});
  for (const fs::path& p : {dir / "m.safetensors", optimizer_state_path(dir / "m.safetensors")}) {
    const SafetensorsFile file = read_safetensors(p);
    EXPECT_EQ(file.metadata.at("lc2wf_version"), lc2wf_version()) << p;
    EXPECT_EQ(file.metadata.at("commit"), lc2wf_git_commit()) << p;
  }
  for (const fs::path& p : {dir / "m.safetensors", optimizer_state_path(dir / "m.safetensors")}) {
    SafetensorsFile file = read_safetensors(p);
    file.metadata.erase("lc2wf_version");
    file.metadata.erase("commit");
    NamedTensors tensors(file.tensors.begin(), file.tensors.end());
    write_safetensors(p, tensors, file.metadata);
  }
  JunctionNet b(tiny_config(), 9);
  AdamW opt_b(b.named_parameters(), OptimConfig{});
  EXPECT_EQ(load_checkpoint(dir / "m.safetensors", b, nullptr, &opt_b).position.step, 2);
  fs::remove_all(dir);
}

TEST(Checkpoint, ResumeIsExact) {
  const fs::path dir = temp_dir("resume");
  JunctionNet a(tiny_config(), 1);
  AdamW opt_a(a.named_parameters(), OptimConfig{});
  train_steps(a, opt_a, 2, 100);
  save_checkpoint(dir / "m.safetensors", a, a.config().to_json(), a.dropout_rng(), &opt_a, {0, 2});
  train_steps(a, opt_a, 3, 200);  // dropout active: the result depends on the RNG stream too

  JunctionNet b(tiny_config(), 42);
  AdamW opt_b(b.named_parameters(), OptimConfig{});
  const CheckpointInfo info = load_checkpoint(dir / "m.safetensors", b, &b.dropout_rng(), &opt_b);
  EXPECT_TRUE(info.has_optimizer);
  EXPECT_EQ(opt_b.step_count(), 2);
  train_steps(b, opt_b, 3, 200);
  const auto sa = a.state_dict(), sb = b.state_dict();
  ASSERT_EQ(sa.size(), sb.size());
  for (size_t i = 0; i < sa.size(); ++i) EXPECT_EQ(sa[i].second.to_vector(), sb[i].second.to_vector()) << sa[i].first;
  fs::remove_all(dir);
}

TEST(Checkpoint, MismatchedOptimizerFileIsRefused) {
  const fs::path dir = temp_dir("mismatch");
  JunctionNet a(tiny_config(), 1);
  AdamW opt(a.named_parameters(), OptimConfig{});
  save_checkpoint(dir / "m.safetensors", a, {}, a.dropout_rng(), &opt, {0, 5});
  const fs::path other = dir / "other.safetensors";
  save_checkpoint(other, a, {}, a.dropout_rng(), &opt, {0, 6});
  fs::copy_file(optimizer_state_path(other), optimizer_state_path(dir / "m.safetensors"),
                fs::copy_options::overwrite_existing);
  AdamW opt_b(a.named_parameters(), OptimConfig{});
  EXPECT_THROW(load_checkpoint(dir / "m.safetensors", a, nullptr, &opt_b), std::runtime_error);
  fs::remove_all(dir);
}

TEST(Checkpoint, MissingExtraAndMisshapedTensorsAreNamed) {
  const fs::path dir = temp_dir("errors");
  JunctionNet net(tiny_config(), 1);
  const fs::path path = dir / "m.safetensors";
  save_checkpoint(path, net, {}, net.dropout_rng(), nullptr, {});
  SafetensorsFile file = read_safetensors(path);

  auto rewrite = [&](std::map<std::string, Tensor> tensors) {
    NamedTensors list(tensors.begin(), tensors.end());
    write_safetensors(path, list, file.metadata);
  };
  auto missing = file.tensors;
  missing.erase("lpt.enc1.norm.bias");
  rewrite(missing);
  EXPECT_THAT(load_error(path, net), HasSubstr("missing tensor 'lpt.enc1.norm.bias'"));

  auto extra = file.tensors;
  extra["lpt.bogus"] = Tensor::zeros({1});
  rewrite(extra);
  EXPECT_THAT(load_error(path, net), HasSubstr("unexpected tensor 'lpt.bogus'"));

  auto misshaped = file.tensors;
  misshaped["cls_head.out.weight"] = Tensor::zeros({3, 3});
  rewrite(misshaped);
  const std::string e = load_error(path, net);
  EXPECT_THAT(e, HasSubstr("'cls_head.out.weight' has shape [3, 3]")) << e;
  EXPECT_THAT(e, HasSubstr(path.string())) << e;

  write_safetensors(path, NamedTensors(file.tensors.begin(), file.tensors.end()), {{"format", "other"}});
  EXPECT_THAT(load_error(path, net), HasSubstr("not an lc2wf checkpoint"));
  fs::remove_all(dir);
}

// Regression: junction weights holding a NaN loaded fine; every cloud then failed in lc2wf-infer with
// "select_junctions: candidate 0 has a non-finite value", naming the cloud, not the weights (found by
// the adversarial corpus).
TEST(Checkpoint, AModelWithANonFiniteWeightIsRefusedNamingTheTensor) {
  const fs::path dir = temp_dir("non_finite");
  const JunctionNetConfig config = tiny_config();
  JunctionNet net(config, 1);
  const fs::path path = dir / "junction.safetensors";
  save_checkpoint(path, net, {{"stage", "junction"}, {"net", config.to_json()}}, net.dropout_rng(), nullptr, {});
  EXPECT_NO_THROW(load_junction_net(path));
  SafetensorsFile file = read_safetensors(path);
  file.tensors.at("cls_head.out.weight").data<float>()[1] = std::nanf("");
  write_safetensors(path, NamedTensors(file.tensors.begin(), file.tensors.end()), file.metadata);
  try {
    load_junction_net(path);
    ADD_FAILURE() << "a NaN weight was loaded";
  } catch (const std::runtime_error& e) {
    EXPECT_THAT(e.what(), HasSubstr(path.string() + ": tensor 'cls_head.out.weight' holds a non-finite value (element 1)"));
  }
  fs::remove_all(dir);
}

}  // namespace
}  // namespace lc2wf
