// The configs in configs/ resolve ("extends") and parse, share one key set, and bad keys/values are rejected by
// name; the weights' stored configs keep loading.
#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <set>
#include <string>

#include "train/config_extends.h"
#include "train/edge_step.h"
#include "train/stage_loop.h"
#include "train/train_config.h"

using ::testing::HasSubstr;

namespace lc2wf {
namespace {

namespace fs = std::filesystem;
const fs::path kConfigs = fs::path(LC2WF_SOURCE_DIR) / "configs";
const fs::path kModels = fs::path(LC2WF_SOURCE_DIR) / "models";

nlohmann::json read_json(const fs::path& p) {
  std::ifstream in(p);
  return nlohmann::json::parse(in);
}

void collect_keys(const nlohmann::json& j, const std::string& prefix, std::set<std::string>& out) {
  if (!j.is_object()) return;
  for (auto it = j.begin(); it != j.end(); ++it) {
    out.insert(prefix + it.key());
    collect_keys(it.value(), prefix + it.key() + ".", out);
  }
}

std::string error_of(const nlohmann::json& j) {
  try {
    TrainConfig::from_json(j);
  } catch (const std::invalid_argument& e) {
    return e.what();
  }
  return "";
}

// The constants of ../shared/spec/reference-lc2wf.md (sections 2 and 3): G = 256 junction samples of 32 lines,
// 512 pairs of 2 x 32 lines, AdamW lr 1e-3, 41 / 31 epochs at milestones [15, 30, 41] / [15, 25, 31], seed 1555.
TEST(TrainConfig, BaseHoldsThePaperSettings) {
  EXPECT_FALSE(read_json(kConfigs / "base.json").contains("extends"));  // the root every other config extends
  const TrainConfig c = TrainConfig::from_file(kConfigs / "base.json");
  EXPECT_DOUBLE_EQ(c.edge.optim.lr, 1e-3);
  EXPECT_TRUE(c.junction.schedule.drop_last);
  EXPECT_EQ(c.seed, 1555u);
  EXPECT_EQ(c.junction.net.lpt.patches, 256);
  EXPECT_EQ(c.junction.net.lpt.lines_per_patch, 32);
  EXPECT_EQ(c.edge.net.lpt.lines_per_patch, 64);
  EXPECT_EQ(c.edge.net.lpt.patches, 512);
  EXPECT_EQ(c.junction.schedule.batch_size, 16);
  EXPECT_EQ(c.edge.schedule.batch_size, 32);
  EXPECT_EQ(c.edge.schedule.micro_batch, 4);  // same batch and steps; bounds the edge step's memory
  EXPECT_FALSE(c.junction.schedule.cloud_augment.enabled);  // the paper has no cloud augmentation
  EXPECT_FALSE(c.edge.schedule.cloud_augment.enabled);
  EXPECT_EQ(c.junction.schedule.epochs, 41);
  EXPECT_EQ(c.edge.schedule.epochs, 31);
  EXPECT_EQ(c.junction.optim.milestones, (std::vector<int64_t>{15, 30, 41}));
  EXPECT_EQ(c.edge.optim.milestones, (std::vector<int64_t>{15, 25, 31}));
  EXPECT_EQ(c.junction.optim.optimizer, "adamw");
  EXPECT_DOUBLE_EQ(c.junction.optim.lr, 1e-3);
  EXPECT_EQ(c.junction.loss.kind, "release");
  EXPECT_EQ(c.precision, "auto");
  EXPECT_EQ(c.edge.pair_support, 0.0);     // the release classifies every pair
  EXPECT_EQ(c.edge.nms_radius_m, 0.25);    // NMS radius of the release's 5 raw units
  EXPECT_EQ(c.edge.min_confidence, 0.85);  // and pairs the junctions above 0.85  // bf16 only where the CPU has the dot product (evidence: train/README)
  // The networks are the nn defaults (the release's): base.json only spells them out.
  EXPECT_EQ(c.junction.net.to_json(), JunctionNetConfig().to_json());
  EXPECT_EQ(c.edge.net.to_json(), EdgeNetConfig().to_json());
}

// Every other config extends another and holds only what differs; resolved, each has base.json's keys and
// reads back as the same config.
TEST(TrainConfig, EveryConfigResolvesToTheSameKeys) {
  std::set<std::string> base_keys;
  collect_keys(read_json(kConfigs / "base.json"), "", base_keys);
  int others = 0;
  std::vector<fs::path> configs;
  for (const fs::path& dir : {kConfigs, fs::path(LC2WF_SOURCE_DIR) / "experiments" / "configs"})
    for (const auto& entry : fs::directory_iterator(dir)) configs.push_back(entry.path());
  for (const fs::path& path : configs) {
    const fs::directory_entry entry(path);
    const std::string name = entry.path().filename().string();
    if (entry.path().extension() != ".json" || name == "base.json") continue;
    ++others;
    EXPECT_TRUE(read_json(entry.path()).contains("extends")) << name;
    const nlohmann::json resolved = resolve_config_json(entry.path());
    std::set<std::string> keys;
    collect_keys(resolved, "", keys);
    EXPECT_EQ(keys, base_keys) << name;
    EXPECT_NO_THROW(TrainConfig::from_file(entry.path())) << name;
    EXPECT_EQ(TrainConfig::from_file(entry.path()).to_json(), resolved) << name;  // nothing left to defaults
  }
  EXPECT_GE(others, 12);
}

// The configs stored with the weights are whole configs written by lc2wf-train; they must keep loading.
TEST(TrainConfig, StoredWeightsConfigsLoad) {
  int stored = 0;
  for (const auto& entry : std::filesystem::directory_iterator(kModels)) {
    const fs::path config = entry.path() / "config.json";
    if (!fs::is_regular_file(config)) continue;
    ++stored;
    EXPECT_FALSE(read_json(config).contains("extends")) << config;
    EXPECT_NO_THROW(TrainConfig::from_file(config)) << config;
  }
  EXPECT_GE(stored, 1);
}

// The next experiment is base.json with local junction labels and nothing else changed.
TEST(TrainConfig, LocalLabelsIsBaseWithLocalPatchLabels) {
  nlohmann::json local = resolve_config_json(fs::path(LC2WF_SOURCE_DIR) / "experiments" / "configs" / "local-labels.json");
  EXPECT_EQ(local["junction"]["positive_radius_m"].get<double>(), 1.0);
  local["junction"]["positive_radius_m"] = -1.0;
  local["out"] = "runs/base";
  EXPECT_EQ(local, read_json(kConfigs / "base.json"));
}

// The cheaper option (experiments/README.md, "A cheaper edge stage") is base.json with 32 lines per pair patch and
// nothing else changed: its evidence holds only for that one difference.
TEST(TrainConfig, FastIsBaseWithHalfTheLinesPerPairPatch) {
  nlohmann::json fast = resolve_config_json(kConfigs / "fast.json");
  EXPECT_EQ(fast["edge"]["net"]["lpt"]["lines_per_patch"].get<int64_t>(), 32);
  EXPECT_EQ(TrainConfig::from_file(kConfigs / "fast.json").edge.net.lpt.lines_per_patch, 32);
  fast["edge"]["net"]["lpt"]["lines_per_patch"] = 64;
  fast["out"] = "runs/base";
  EXPECT_EQ(fast, read_json(kConfigs / "base.json"));
}

// A folder of small configs for the "extends" tests, removed afterwards.
class ExtendsTest : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() / ("lc2wf_extends_" + std::to_string(::getpid()));
    fs::remove_all(dir_);
    fs::create_directories(dir_ / "sub");
  }
  void TearDown() override { fs::remove_all(dir_); }
  fs::path write(const std::string& name, const nlohmann::json& j) {
    std::ofstream(dir_ / name) << j.dump(2);
    return dir_ / name;
  }
  // The message of the error reading `path`, or "" when it reads.
  static std::string error_reading(const fs::path& path) {
    try {
      TrainConfig::from_file(path);
    } catch (const std::exception& e) {
      return e.what();
    }
    return "";
  }
  fs::path dir_;
};

TEST(ConfigMerge, ObjectsMergeKeyByKeyAndEverythingElseReplaces) {
  const nlohmann::json base = {{"a", {{"x", 1}, {"y", {1, 2, 3}}, {"z", {{"deep", "kept"}}}}}, {"b", "base"}};
  const nlohmann::json over = {{"a", {{"y", {9}}, {"z", {{"new", true}}}}}, {"c", 3}};
  const nlohmann::json merged = merge_config_json(base, over);
  EXPECT_EQ(merged, nlohmann::json::parse(
                        R"({"a": {"x": 1, "y": [9], "z": {"deep": "kept", "new": true}}, "b": "base", "c": 3})"));
  // An object over a number (and the reverse) replaces it whole.
  EXPECT_EQ(merge_config_json({{"a", 1}}, {{"a", {{"x", 1}}}}), nlohmann::json({{"a", {{"x", 1}}}}));
  EXPECT_EQ(merge_config_json({{"a", {{"x", 1}}}}, {{"a", 2}}), nlohmann::json({{"a", 2}}));
}

// A chain over two folders: paths are relative to the extending file; the nearest file wins.
TEST_F(ExtendsTest, ChainsResolveRelativeToEachFile) {
  nlohmann::json base = read_json(kConfigs / "base.json");
  base["data"]["dir"] = "clouds";
  write("sub/root.json", base);
  write("sub/middle.json", {{"extends", "root.json"}, {"seed", 7}, {"junction", {{"optim", {{"lr", 0.01}}}}}});
  const fs::path top = write("top.json", {{"extends", "sub/middle.json"}, {"junction", {{"epochs", 3}, {"optim", {{"milestones", {2}}}}}}});
  const TrainConfig c = TrainConfig::from_file(top);
  EXPECT_EQ(c.seed, 7u);
  EXPECT_EQ(c.data.dir, "clouds");
  EXPECT_EQ(c.junction.schedule.epochs, 3);
  EXPECT_DOUBLE_EQ(c.junction.optim.lr, 0.01);                            // from the middle file
  EXPECT_EQ(c.junction.optim.milestones, (std::vector<int64_t>{2}));      // an array replaces the base's
  EXPECT_DOUBLE_EQ(c.junction.optim.weight_decay, 1e-5);                  // the rest of the object is the root's
  EXPECT_EQ(c.edge.to_json(), TrainConfig::from_file(kConfigs / "base.json").edge.to_json());
  EXPECT_FALSE(resolve_config_json(top).contains("extends"));
}

TEST_F(ExtendsTest, ACycleIsAnErrorNamingTheFiles) {
  write("a.json", {{"extends", "b.json"}, {"seed", 1}});
  write("b.json", {{"extends", "a.json"}});
  const std::string err = error_reading(dir_ / "a.json");
  EXPECT_THAT(err, HasSubstr((dir_ / "a.json").string())) << err;
  EXPECT_THAT(err, HasSubstr("cycle")) << err;
  EXPECT_THAT(err, HasSubstr("b.json")) << err;
  write("self.json", {{"extends", "./self.json"}});
  EXPECT_THAT(error_reading(dir_ / "self.json"), HasSubstr("cycle"));
}

TEST_F(ExtendsTest, AMissingBaseIsAnErrorNamingBothFiles) {
  write("lost.json", {{"extends", "nowhere.json"}, {"seed", 1}});
  const std::string err = error_reading(dir_ / "lost.json");
  EXPECT_THAT(err, HasSubstr((dir_ / "lost.json").string() + ": \"extends\" names")) << err;
  EXPECT_THAT(err, HasSubstr("nowhere.json")) << err;
  EXPECT_THAT(err, HasSubstr("does not exist")) << err;
  write("number.json", {{"extends", 3}});
  EXPECT_THAT(error_reading(dir_ / "number.json"), HasSubstr("\"extends\" must name a config file"));
  EXPECT_THAT(error_reading(dir_ / "absent.json"), HasSubstr((dir_ / "absent.json").string() + ": no such config file"));
}

// Validation runs on the merged config, so an error still names the key the user wrote (and the file).
TEST_F(ExtendsTest, ErrorsStillNameTheUsersKey) {
  write("base.json", read_json(kConfigs / "base.json"));
  write("typo.json", {{"extends", "base.json"}, {"junction", {{"optim", {{"learning_rate", 0.1}}}}}});
  std::string err = error_reading(dir_ / "typo.json");
  EXPECT_THAT(err, HasSubstr((dir_ / "typo.json").string())) << err;
  EXPECT_THAT(err, HasSubstr("junction.optim")) << err;
  EXPECT_THAT(err, HasSubstr("learning_rate")) << err;
  write("bad.json", {{"extends", "base.json"}, {"edge", {{"batch_size", 0}}}});
  err = error_reading(dir_ / "bad.json");
  EXPECT_THAT(err, HasSubstr("edge.batch_size")) << err;
  write("broken.json", "not json");
  std::ofstream(dir_ / "broken.json") << "{\"seed\": ";
  write("on_broken.json", {{"extends", "broken.json"}});
  EXPECT_THAT(error_reading(dir_ / "on_broken.json"), HasSubstr((dir_ / "broken.json").string() + ": not valid JSON"));
}

TEST(TrainConfig, RoundTripsThroughJson) {
  const TrainConfig c = TrainConfig::from_file(kConfigs / "small.json");
  EXPECT_EQ(TrainConfig::from_json(c.to_json()).to_json(), c.to_json());
}

TEST(TrainConfig, RejectsUnknownKeysByName) {
  nlohmann::json j = read_json(kConfigs / "base.json");
  j["junction"]["optim"]["learning_rate"] = 0.1;
  EXPECT_THAT(error_of(j), HasSubstr("junction.optim")) << error_of(j);
  EXPECT_THAT(error_of(j), HasSubstr("learning_rate"));
  j = read_json(kConfigs / "base.json");
  j["epochs"] = 3;
  EXPECT_THAT(error_of(j), HasSubstr("'epochs'")) << error_of(j);
}

TEST(TrainConfig, RejectsBadValuesByName) {
  struct Case {
    std::vector<std::string> path;
    nlohmann::json value;
    std::string expected;
  };
  const std::vector<Case> cases{
      {{"junction", "optim", "lr"}, -1.0, "junction.optim.lr"},
      {{"edge", "batch_size"}, 0, "edge.batch_size"},
      {{"data", "format"}, "csv", "data.format"},
      {{"threads"}, 0, "threads"},
      {{"precision"}, "fp16", "precision"},
      {{"junction", "net", "lpt", "hidden_dim"}, "wide", "junction.net.lpt.hidden_dim"},
      {{"edge", "net", "lpt", "lines_per_patch"}, 63, "edge.net.lpt.lines_per_patch"},
      {{"junction", "net", "lpt", "input_dim"}, 6, "junction.net.lpt.input_dim"},
      {{"edge", "cloud_augment", "drop_max"}, 1.5, "edge.cloud_augment.drop_max"},
      {{"junction", "cloud_augment", "enabled"}, "yes", "junction.cloud_augment.enabled"},
      {{"edge", "pair_support"}, 1.5, "edge.pair_support"},
      {{"edge", "min_confidence"}, -0.5, "edge.min_confidence"},
      {{"edge", "nms_radius_m"}, 0.0, "edge.nms_radius_m"},
      {{"edge", "max_offset_m"}, "far", "edge.max_offset_m"},
      {{"edge", "corner_radius_m"}, -0.3, "edge.corner_radius_m"},
      {{"edge", "footing_radius_m"}, -0.5, "edge.footing_radius_m"},
      {{"edge", "sampling_passes"}, 0, "edge.sampling_passes"},
      {{"edge", "test_time_views"}, 3, "edge.test_time_views"},
      {{"edge", "density_seeds"}, "dense", "edge.density_seeds"},
      {{"junction", "density_seeds"}, "4,0.5", "junction.density_seeds"},
      {{"edge", "density_seeds"}, 4, "edge.density_seeds"},
      {{"junction", "augment_rotate_z"}, "yes", "junction.augment_rotate_z"},
      {{"junction", "positive_radius_m"}, "near", "junction.positive_radius_m"},
  };
  for (const Case& c : cases) {
    nlohmann::json j = read_json(kConfigs / "base.json");
    nlohmann::json* node = &j;
    for (const auto& key : c.path) node = &(*node)[key];
    *node = c.value;
    const std::string err = error_of(j);
    EXPECT_THAT(err, HasSubstr(c.expected)) << "expected '" << c.expected << "' in: " << err;
  }
}

TEST(TrainConfig, MicroBatchRangesCoverTheBatch) {
  using R = std::vector<std::pair<int, int>>;
  EXPECT_EQ(micro_batch_ranges(32, 0), (R{{0, 32}}));
  EXPECT_EQ(micro_batch_ranges(32, 32), (R{{0, 32}}));
  EXPECT_EQ(micro_batch_ranges(10, 4), (R{{0, 4}, {4, 4}, {8, 2}}));
  EXPECT_EQ(micro_batch_ranges(3, 1), (R{{0, 1}, {1, 1}, {2, 1}}));
}

TEST(TrainConfig, FileErrorsNameTheFile) {
  const fs::path p = fs::temp_directory_path() / ("lc2wf_bad_config_" + std::to_string(::getpid()) + ".json");
  std::ofstream(p) << "{\"seed\": ";
  try {
    TrainConfig::from_file(p);
    FAIL() << "expected an error";
  } catch (const std::runtime_error& e) {
    EXPECT_THAT(std::string(e.what()), HasSubstr(p.string()));
  }
  fs::remove(p);
}

// Regression: a number beyond a double (1e309) failed as "number overflow parsing '1e309'", naming no file
// (nlohmann reports it as out_of_range, not as a parse error; found by the adversarial corpus).
TEST(TrainConfig, ANumberBeyondADoubleNamesTheFile) {
  const fs::path p = fs::temp_directory_path() / ("lc2wf_overflow_config_" + std::to_string(::getpid()) + ".json");
  std::ofstream(p) << "{\"seed\": 1e309}";
  try {
    TrainConfig::from_file(p);
    FAIL() << "expected an error";
  } catch (const std::runtime_error& e) {
    EXPECT_THAT(std::string(e.what()), HasSubstr(p.string() + ": not valid JSON"));
    EXPECT_THAT(std::string(e.what()), HasSubstr("1e309"));
  }
  fs::remove(p);
}

// The edge stage's selection keys reach the one selection rule the hand-off pairs, validation and
// inference share; the release's post-processing keeps them too.
// augment_rotate_z turns the training samples about the vertical (off, as the release, by default).
TEST(TrainConfig, RotationAugmentReachesTheEdgeSamples) {
  EdgeStageConfig c;
  EXPECT_FALSE(edge_training_sample_options(c).augment.rotate_z);
  c.schedule.augment_rotate_z = true;
  EXPECT_TRUE(edge_training_sample_options(c).augment.rotate_z);
}

TEST(TrainConfig, EdgeSelectionKeysReachThePostProcessing) {
  for (const char* mode : {"sound", "release"}) {
    EdgeStageConfig c;
    c.post_process = mode;
    c.min_confidence = 0.5;
    c.nms_radius_m = 0.6;
    c.pair_support = 0.1;
    c.top_k = 40;
    c.max_offset_m = 1.0;
    c.corner_radius_m = 0.4;
    c.footing_radius_m = 0.7;
    c.sampling_passes = 2;
    c.test_time_views = 4;
    c.density_seeds = "6,0.45,0.25";
    const PostProcessOptions o = edge_post_process_options(c);
    EXPECT_EQ(o.selection.density_seeds.str(), "6,0.45,0.25") << mode;
    EXPECT_EQ(o.selection.sampling_passes, 2) << mode;
    EXPECT_EQ(o.selection.test_time_views, 4) << mode;
    EXPECT_DOUBLE_EQ(o.selection.min_confidence, 0.5) << mode;
    EXPECT_DOUBLE_EQ(o.selection.nms_radius_m, 0.6) << mode;
    EXPECT_DOUBLE_EQ(o.pair_support.min_support, 0.1) << mode;
    EXPECT_DOUBLE_EQ(o.selection.max_offset_m, 1.0) << mode;
    EXPECT_DOUBLE_EQ(o.selection.corner.radius_m, 0.4) << mode;
    EXPECT_DOUBLE_EQ(o.selection.footing.radius_m, 0.7) << mode;
    const JunctionSelectionOptions training = edge_training_selection(c);
    EXPECT_DOUBLE_EQ(training.nms_radius_m, 0.6) << mode;
    EXPECT_DOUBLE_EQ(training.corner.radius_m, 0.4) << mode << ": the training pairs come from the same selection";
    EXPECT_DOUBLE_EQ(training.footing.radius_m, 0.7) << mode;
    EXPECT_EQ(training.top_k, 40) << mode;
    c.max_offset_m = -1;  // <= 0: every candidate, whatever the options' default
    EXPECT_TRUE(std::isinf(edge_post_process_options(c).selection.max_offset_m)) << mode;
  }
}

}  // namespace
}  // namespace lc2wf
