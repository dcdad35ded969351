// Command-line contracts of lc2wf-synthetic-data, lc2wf-fit-height, lc2wf-infer and lc2wf-train --print-config: --help, usage
// errors (exit 2, naming the flag), data errors (exit 1, naming the file), and a deterministic synthetic dataset.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "tests/common/run_cli.h"

using ::testing::HasSubstr;

namespace lc2wf {
namespace {

namespace fs = std::filesystem;
using testing::run_cli;

const std::string kSynthetic = LC2WF_SYNTHETIC_DATA_BIN;
const std::string kInfer = LC2WF_INFER_BIN;
const std::string kFitHeight = LC2WF_FIT_HEIGHT_BIN;
const std::string kTrain = LC2WF_TRAIN_BIN;
const fs::path kConfigs = fs::path(LC2WF_SOURCE_DIR) / "configs";

std::string file_bytes(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

class CliContract : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() / ("lc2wf_train_cli_" + std::to_string(::getpid()));
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }
  fs::path dir_;
};

TEST_F(CliContract, SyntheticDataUsage) {
  auto r = run_cli(kSynthetic + " --help");
  EXPECT_EQ(r.code, 0);
  EXPECT_THAT(r.out, HasSubstr("Usage: lc2wf-synthetic-data"));
  r = run_cli(kSynthetic);
  EXPECT_EQ(r.code, 2);
  EXPECT_THAT(r.err, HasSubstr("-o OUT is required")) << r.err;
  r = run_cli(kSynthetic + " --out x --count 5x");
  EXPECT_EQ(r.code, 2);
  EXPECT_THAT(r.err, HasSubstr("--count needs a non-negative integer, got '5x'")) << r.err;
  r = run_cli(kSynthetic + " --out x --count 4 --val 2 --test 2");
  EXPECT_EQ(r.code, 2);
  EXPECT_THAT(r.err, HasSubstr("--count must exceed")) << r.err;
  r = run_cli(kSynthetic + " --out x --colour red");
  EXPECT_EQ(r.code, 2);
  EXPECT_THAT(r.err, HasSubstr("unknown option '--colour'")) << r.err;
}

TEST_F(CliContract, SyntheticDataIsDeterministicAndSplitsAsAsked) {
  for (const char* run : {"a", "b"}) {
    const auto r = run_cli(kSynthetic + " --quiet --count 5 --val 1 --test 1 --seed 7 --out " + (dir_ / run).string());
    ASSERT_EQ(r.code, 0) << r.err;
  }
  EXPECT_EQ(file_bytes(dir_ / "a/train.txt"), "synth_0000\nsynth_0001\nsynth_0002\n");
  EXPECT_EQ(file_bytes(dir_ / "a/val.txt"), "synth_0003\n");
  EXPECT_EQ(file_bytes(dir_ / "a/test.txt"), "synth_0004\n");
  for (int i = 0; i < 5; ++i) {
    const std::string name = "clouds/synth_000" + std::to_string(i) + ".lcloud";
    const std::string a = file_bytes(dir_ / "a" / name);
    EXPECT_FALSE(a.empty()) << name;
    EXPECT_EQ(a, file_bytes(dir_ / "b" / name)) << name;
  }
}

// lc2wf-fit-height on the synthetic clouds: a model every run writes the same, a broken cloud skipped by name
// (exit 1), and its model read by lc2wf-infer (a file that is not one: exit 3, naming it).
TEST_F(CliContract, FitHeightWritesADeterministicModel) {
  auto r = run_cli(kFitHeight + " --help");
  EXPECT_EQ(r.code, 0);
  EXPECT_THAT(r.out, HasSubstr("Usage: lc2wf-fit-height"));
  r = run_cli(kFitHeight + " " + dir_.string());
  EXPECT_EQ(r.code, 2);
  EXPECT_THAT(r.err, HasSubstr("-o MODEL.json is required")) << r.err;
  r = run_cli(kFitHeight + " -o " + (dir_ / "m.json").string() + " " + dir_.string());  // a folder without clouds: too few to fit
  EXPECT_EQ(r.code, 3);
  EXPECT_THAT(r.err, HasSubstr("needs at least 80 clouds")) << r.err;
  r = run_cli(kFitHeight + " -o " + (dir_ / "m.json").string());
  EXPECT_EQ(r.code, 2);
  EXPECT_THAT(r.err, HasSubstr("no cloud given")) << r.err;
  r = run_cli(kFitHeight + " -o " + (dir_ / "m.json").string() + " --folds 1 " + dir_.string());
  EXPECT_EQ(r.code, 2);
  EXPECT_THAT(r.err, HasSubstr("--folds")) << r.err;
  r = run_cli(kFitHeight + " -o " + (dir_ / "m.json").string() + " --ks 1,x " + dir_.string());
  EXPECT_EQ(r.code, 2);
  EXPECT_THAT(r.err, HasSubstr("--ks expects an integer, got 'x'")) << r.err;
  ASSERT_EQ(run_cli(kSynthetic + " -q --count 14 --out " + (dir_ / "data").string()).code, 0);
  r = run_cli(kFitHeight + " -q -o " + (dir_ / "a.json").string() + " --folds 3 --ks 1,3 " + (dir_ / "data").string());
  ASSERT_EQ(r.code, 0) << r.err;
  r = run_cli(kFitHeight + " -o " + (dir_ / "b.json").string() + " --folds 3 --ks 1,3 -j 1 " + (dir_ / "data").string());
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_THAT(r.err, HasSubstr("14 clouds (0 skipped)")) << r.err;
  EXPECT_EQ(file_bytes(dir_ / "a.json"), file_bytes(dir_ / "b.json"));  // whatever the thread count
  const nlohmann::json m = nlohmann::json::parse(file_bytes(dir_ / "a.json"));
  EXPECT_EQ(m["format"], "lc2wf-height-model");
  EXPECT_EQ(m["clouds"].size(), 14u);
  std::ofstream(dir_ / "data" / "clouds" / "broken.lcloud") << "not a cloud";
  r = run_cli(kFitHeight + " -o " + (dir_ / "c.json").string() + " --folds 3 --ks 1,3 " + (dir_ / "data").string());
  EXPECT_EQ(r.code, 1);
  EXPECT_THAT(r.err, HasSubstr("skipped " + (dir_ / "data" / "clouds" / "broken.lcloud").string())) << r.err;
  EXPECT_TRUE(fs::exists(dir_ / "c.json"));
  // lc2wf-infer refuses a height model that is not one before it reads any cloud.
  std::ofstream(dir_ / "not_a_model.json") << "[1, 2]";
  r = run_cli(kInfer + " --weights " + dir_.string() + " --height-model " + (dir_ / "not_a_model.json").string() + " -o " +
              (dir_ / "out").string() + " " + (dir_ / "data" / "clouds" / "synth_0000.lcloud").string());
  EXPECT_EQ(r.code, 3);
  EXPECT_THAT(r.err, HasSubstr("not_a_model.json: not an lc2wf-height-model file")) << r.err;
  r = run_cli(kInfer + " --weights " + dir_.string() + " --height-model '' -o " + (dir_ / "out").string() + " x.obj");
  EXPECT_EQ(r.code, 2);
  EXPECT_THAT(r.err, HasSubstr("--height-model needs a file or 'none'")) << r.err;
}

TEST_F(CliContract, InferUsageAndDataErrors) {
  auto r = run_cli(kInfer + " --help");
  EXPECT_EQ(r.code, 0);
  EXPECT_THAT(r.out, HasSubstr("Usage: lc2wf-infer"));
  r = run_cli(kInfer + " --weights w -o out");
  EXPECT_EQ(r.code, 2);
  EXPECT_THAT(r.err, HasSubstr("no line cloud given")) << r.err;
  r = run_cli(kInfer + " --weights w -o out --threads two c.lcloud");
  EXPECT_EQ(r.code, 2);
  EXPECT_THAT(r.err, HasSubstr("--threads needs a non-negative integer")) << r.err;
  r = run_cli(kInfer + " --weights w -o out --format ply c.lcloud");
  EXPECT_EQ(r.code, 2);
  EXPECT_THAT(r.err, HasSubstr("--format")) << r.err;
  r = run_cli(kInfer + " --weights w -o out --precision fp16 c.lcloud");
  EXPECT_EQ(r.code, 2);
  EXPECT_THAT(r.err, HasSubstr("--precision must be \"fp32\", \"bf16\" or \"auto\", got \"fp16\"")) << r.err;
  const std::map<std::string, std::vector<std::string>> bad_values = {
      {"--pair-support", {"1.5", "-0.1", "nan", "some"}},
      {"--min-confidence", {"1.5", "-0.1", "nan", "some"}},
      {"--nms-radius", {"0", "-0.1", "nan", "some"}},
      {"--max-offset", {"nan", "inf", "some"}},  // --max-offset <= 0 is valid: every candidate
      {"--corner-radius", {"-0.1", "nan", "inf", "some"}},
      {"--footing-radius", {"-0.1", "nan", "inf", "some"}}};
  for (const auto& [flag, values] : bad_values)
    for (const std::string& value : values) {
      r = run_cli(kInfer + " --weights w -o out " + flag + " " + value + " c.lcloud");
      EXPECT_EQ(r.code, 2) << flag << " " << value;
      EXPECT_THAT(r.err, HasSubstr(flag)) << r.err;
    }
  const fs::path weights = dir_ / "no_weights";
  fs::create_directories(weights);
  r = run_cli(kInfer + " --quiet --weights " + weights.string() + " -o " + (dir_ / "out").string() + " c.lcloud");
  EXPECT_EQ(r.code, 3);
  EXPECT_FALSE(fs::exists(dir_ / "out"));
  EXPECT_THAT(r.err, HasSubstr((weights / "junction.safetensors").string())) << r.err;
}

// --print-config prints the resolved config (its "extends" merged, -o applied) and trains nothing.
TEST_F(CliContract, TrainPrintsTheResolvedConfig) {
  auto r = run_cli(kTrain + " " + (kConfigs / "fast.json").string() + " --print-config -o " + (dir_ / "run").string());
  ASSERT_EQ(r.code, 0) << r.err;
  const nlohmann::json fast = nlohmann::json::parse(r.out);
  EXPECT_FALSE(fast.contains("extends"));
  EXPECT_EQ(fast["edge"]["net"]["lpt"]["lines_per_patch"], 32);
  EXPECT_EQ(fast["junction"]["net"]["lpt"]["lines_per_patch"], 32);  // base.json's
  EXPECT_EQ(fast["out"], (dir_ / "run").string());
  EXPECT_FALSE(fs::exists(dir_ / "run"));
  r = run_cli(kTrain + " " + (kConfigs / "base.json").string() + " --print-config");
  ASSERT_EQ(r.code, 0) << r.err;
  nlohmann::json base = nlohmann::json::parse(r.out);
  base["edge"]["net"]["lpt"]["lines_per_patch"] = 32;
  base["out"] = fast["out"];
  EXPECT_EQ(base, fast);  // fast.json is base.json with 32 lines per pair patch and its own folder
  std::ofstream(dir_ / "a.json") << R"({"extends": "b.json"})";
  std::ofstream(dir_ / "b.json") << R"({"extends": "a.json"})";
  r = run_cli(kTrain + " " + (dir_ / "a.json").string() + " --print-config");
  EXPECT_EQ(r.code, 3);
  EXPECT_THAT(r.err, HasSubstr((dir_ / "a.json").string() + ": \"extends\" cycle")) << r.err;
}

}  // namespace
}  // namespace lc2wf
