#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <stdexcept>
#include <string>

#include <nlohmann/json.hpp>

#include "nn/config.h"

using ::testing::HasSubstr;

namespace lc2wf {
namespace {

template <class F>
std::string error_of(F&& f) {
  try {
    f();
  } catch (const std::invalid_argument& e) {
    return e.what();
  }
  return "";
}

TEST(Config, DefaultsAreThePaperValues) {
  const JunctionNetConfig j;
  EXPECT_EQ(j.lpt.input_dim, 7);
  EXPECT_EQ(j.lpt.lines_per_patch, 32);
  EXPECT_EQ(j.lpt.patches, 256);
  EXPECT_EQ(j.lpt.mlp_dims, (std::vector<int64_t>{64, 64, 128, 128, 256}));
  EXPECT_EQ(j.lpt.hidden_dim, 256);
  EXPECT_EQ(j.lpt.num_heads, 8);
  EXPECT_EQ(j.lpt.ffn_dim, 256);
  EXPECT_DOUBLE_EQ(j.lpt.dropout, 0.5);
  EXPECT_DOUBLE_EQ(j.lpt.attn_dropout, 0.5);
  EXPECT_EQ(j.lpt.pool, "mean_all");
  EXPECT_EQ(j.head.dims, (std::vector<int64_t>{128, 64, 32}));
  EXPECT_DOUBLE_EQ(j.head.dropout, 0.1);
  const EdgeNetConfig e;
  EXPECT_EQ(e.lpt.input_dim, 6);
  EXPECT_EQ(e.lpt.lines_per_patch, 64);
  EXPECT_EQ(e.lpt.patches, 512);
  EXPECT_EQ(e.num_classes, 5);
  EXPECT_EQ(EdgeLossConfig{}.class_weights, (std::vector<double>{1, 3, 1, 1, 1}));
  EXPECT_EQ(JunctionLossConfig{}.kind, "paper");
  EXPECT_DOUBLE_EQ(JunctionLossConfig{}.reg_weight, 10.0);
  const OptimConfig o;
  EXPECT_EQ(o.optimizer, "adamw");
  EXPECT_DOUBLE_EQ(o.lr, 1e-3);
  EXPECT_DOUBLE_EQ(o.weight_decay, 1e-5);
  EXPECT_EQ(o.milestones, (std::vector<int64_t>{15, 30, 41}));
  EXPECT_NO_THROW(j.Check());
  EXPECT_NO_THROW(e.Check());
  EXPECT_NO_THROW(o.Check());
}

TEST(Config, SmallerModelIsOneJsonAway) {
  const auto j = nlohmann::json::parse(R"({"lpt": {"hidden_dim": 32, "mlp_dims": [8, 32], "num_heads": 4},
                                           "head": {"dims": [16]}})");
  const JunctionNetConfig c = JunctionNetConfig::from_json(j);
  EXPECT_EQ(c.lpt.hidden_dim, 32);
  EXPECT_EQ(c.lpt.mlp_dims, (std::vector<int64_t>{8, 32}));
  EXPECT_EQ(c.lpt.lines_per_patch, 32);  // untouched keys keep their defaults
  EXPECT_NO_THROW(c.Check());
  EXPECT_EQ(JunctionNetConfig::from_json(c.to_json()).to_json(), c.to_json());
}

TEST(Config, EdgeKeepsItsOwnDefaultsUnderPartialJson) {
  const EdgeNetConfig c = EdgeNetConfig::from_json(nlohmann::json::parse(R"({"lpt": {"hidden_dim": 256}})"));
  EXPECT_EQ(c.lpt.input_dim, 6);
  EXPECT_EQ(c.lpt.lines_per_patch, 64);
}

TEST(Config, UnknownKeysAndWrongTypesNameTheField) {
  EXPECT_THAT(error_of([] { JunctionNetConfig::from_json(nlohmann::json::parse(R"({"lpt": {"hiden_dim": 3}})")); }), HasSubstr("junction_net.lpt: unknown key 'hiden_dim'"));
  EXPECT_THAT(error_of([] { OptimConfig::from_json(nlohmann::json::parse(R"({"lr": "fast"})")); }), HasSubstr("optim.lr"));
  EXPECT_THAT(error_of([] { LptConfig::from_json(nlohmann::json::parse(R"({"num_heads": 2.5})")); }), HasSubstr("lpt.num_heads: expected an integer"));
  EXPECT_THAT(error_of([] { LptConfig::from_json(nlohmann::json::parse(R"({"mlp_dims": [8, "x"]})")); }), HasSubstr("lpt.mlp_dims[1]"));
  EXPECT_THAT(error_of([] { HeadConfig::from_json(nlohmann::json::parse("[1]")); }), HasSubstr("expected a JSON object"));
}

// Regression: integers were narrowed without a word (patches 4294967298 trained with 2 patches; -1 in an
// unsigned field) and absurd sizes in a checkpoint's config allocated gigabytes before failing.
TEST(Config, IntegersAreExactAndSizesBounded) {
  EXPECT_THAT(error_of([] { LptConfig::from_json(nlohmann::json::parse(R"({"patches": 4294967298})")).Check(); }), HasSubstr("lpt.patches must be in [1, 8192]"));
  EXPECT_THAT(error_of([] { LptConfig::from_json(nlohmann::json::parse(R"({"patches": 18446744073709551615})")); }), HasSubstr("lpt.patches: 18446744073709551615 is out of range"));
  EXPECT_THAT(error_of([] { LptConfig::from_json(nlohmann::json::parse(R"({"patches": 0.7})")); }), HasSubstr("lpt.patches: expected an integer"));
  EXPECT_THAT(error_of([] { LptConfig::from_json(nlohmann::json::parse(R"({"hidden_dim": true})")); }), HasSubstr("lpt.hidden_dim: expected an integer"));
  EXPECT_THAT(error_of([] { LptConfig::from_json(nlohmann::json::parse(R"({"lines_per_patch": 100000})")).Check(); }), HasSubstr("lpt.lines_per_patch must be in [1, 1024]"));
  EXPECT_THAT(error_of([] { LptConfig::from_json(nlohmann::json::parse(R"({"line_layers": 1000000})")).Check(); }), HasSubstr("lpt.line_layers must be in [1, 32]"));
  EXPECT_THAT(error_of([] { LptConfig::from_json(nlohmann::json::parse(R"({"mlp_dims": [64, 100000]})")).Check(); }), HasSubstr("lpt.mlp_dims"));
}

TEST(Config, CheckNamesTheBadField) {
  LptConfig l;
  l.num_heads = 7;
  EXPECT_THAT(error_of([&] { l.Check(); }), HasSubstr("lpt.num_heads"));
  l = LptConfig{};
  l.mlp_dims = {64, 128};
  EXPECT_THAT(error_of([&] { l.Check(); }), HasSubstr("lpt.mlp_dims"));
  l = LptConfig{};
  l.pool = "max";
  EXPECT_THAT(error_of([&] { l.Check(); }), HasSubstr("lpt.pool"));
  l = LptConfig{};
  l.dropout = 1.0;
  EXPECT_THAT(error_of([&] { l.Check(); }), HasSubstr("lpt.dropout"));
  JunctionLossConfig jl;
  jl.kind = "focal";
  EXPECT_THAT(error_of([&] { jl.Check(); }), HasSubstr("junction_loss.kind"));
  OptimConfig o;
  o.milestones = {30, 15};
  EXPECT_THAT(error_of([&] { o.Check(); }), HasSubstr("optim.milestones"));
  EdgeLossConfig el;
  el.class_weights = {1, -1};
  EXPECT_THAT(error_of([&] { el.Check(); }), HasSubstr("edge_loss.class_weights"));
}

// The patch distance travels with the weights; a stored config from before the key reads as the release's.
TEST(Config, PatchDistanceIsTheReleasesUnlessStored) {
  EXPECT_EQ(JunctionNetConfig{}.patch_distance, "infinite_line");
  const auto old = nlohmann::json::parse(R"({"lpt": {"hidden_dim": 32, "mlp_dims": [8, 32], "num_heads": 4}})");
  EXPECT_EQ(JunctionNetConfig::from_json(old).patch_distance, "infinite_line");
  auto stored = JunctionNetConfig{}.to_json();
  stored["patch_distance"] = "segment";
  EXPECT_EQ(JunctionNetConfig::from_json(stored).patch_distance, "segment");
  JunctionNetConfig bad;
  bad.patch_distance = "line";
  EXPECT_THAT(error_of([&] { bad.Check(); }), HasSubstr("junction_net.patch_distance"));
}

}  // namespace
}  // namespace lc2wf
