// The training log's rewind on resume and the predicted-junction hand-off files.
#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "dataset/formats/errors.h"
#include "train/junction_handoff.h"
#include "train/run_log.h"
#include "train/stages.h"

using ::testing::HasSubstr;

namespace lc2wf {
namespace {

namespace fs = std::filesystem;

struct Scratch {
  fs::path dir = fs::temp_directory_path() / ("lc2wf_train_test_" + std::to_string(::getpid()));
  Scratch() {
    fs::remove_all(dir);
    fs::create_directories(dir);
  }
  ~Scratch() { fs::remove_all(dir); }
};

std::vector<nlohmann::json> read_lines(const fs::path& p) {
  std::vector<nlohmann::json> out;
  std::ifstream in(p);
  std::string line;
  while (std::getline(in, line)) out.push_back(nlohmann::json::parse(line));
  return out;
}

const std::vector<std::string> kOrder{"junction", "handoff", "edge"};

TEST(RunLog, RewindKeepsOnlyWhatTheCheckpointCovers) {
  Scratch s;
  RunLog log(s.dir / "log.jsonl");
  for (int step = 1; step <= 5; ++step) log.append({{"stage", "junction"}, {"type", "step"}, {"step", step}});
  log.append({{"stage", "handoff"}, {"type", "handoff"}, {"step", 0}});
  log.append({{"stage", "edge"}, {"type", "step"}, {"step", 1}});
  {
    std::ofstream torn(s.dir / "log.jsonl", std::ios::app);
    torn << "{\"stage\": \"junct";  // a line cut by kill -9
  }
  log.rewind("junction", 3, kOrder);
  const auto lines = read_lines(s.dir / "log.jsonl");
  ASSERT_EQ(lines.size(), 3u);
  EXPECT_EQ(lines.back()["step"], 3);
  log.append({{"stage", "junction"}, {"type", "step"}, {"step", 4}});
  EXPECT_EQ(read_lines(s.dir / "log.jsonl").size(), 4u);
}

TEST(RunLog, RewindSurvivesLinesThatAreNotOurs) {
  // A valid JSON line that is not an object, or has a non-string stage, ended --resume with a type error.
  Scratch s;
  RunLog log(s.dir / "log.jsonl");
  log.append({{"stage", "junction"}, {"type", "step"}, {"step", 1}});
  {
    std::ofstream odd(s.dir / "log.jsonl", std::ios::app);
    odd << "5\n[1]\n{\"stage\": 7, \"step\": \"x\"}\n\"junction\"\n";
  }
  EXPECT_NO_THROW(log.rewind("junction", 1, kOrder));
  const auto lines = read_lines(s.dir / "log.jsonl");
  ASSERT_EQ(lines.size(), 1u);  // an unknown stage ranks after every known one, so rewinding drops it
  EXPECT_EQ(lines[0]["step"], 1);
}

TEST(RunLog, FreshStageDropsItsOldLinesAndLaterStages) {
  Scratch s;
  RunLog log(s.dir / "log.jsonl");
  log.append({{"stage", "junction"}, {"type", "step"}, {"step", 1}});
  log.append({{"stage", "edge"}, {"type", "step"}, {"step", 1}});
  log.rewind("edge", 0, kOrder);
  const auto lines = read_lines(s.dir / "log.jsonl");
  ASSERT_EQ(lines.size(), 1u);
  EXPECT_EQ(lines[0]["stage"], "junction");
}

TEST(JunctionHandoff, RoundTrips) {
  Scratch s;
  PredictedJunctions p;
  p.positions = {Vec3(1.5, -2.25, 3.0), Vec3(0.1, 0.2, 0.3)};
  p.confidence = {0.9, 0.125};
  write_predicted_junctions(s.dir, "b1", p);
  const PredictedJunctions q = read_predicted_junctions(predicted_junctions_path(s.dir, "b1"));
  ASSERT_EQ(q.positions.size(), 2u);
  EXPECT_EQ(q.positions[0], p.positions[0]);
  EXPECT_EQ(q.positions[1], p.positions[1]);
  EXPECT_EQ(q.confidence, p.confidence);
  EXPECT_TRUE(q.offset_m.empty());  // a file without offsets (as older hand-offs wrote) stays readable
  p.offset_m = {0.75, 2.5};
  write_predicted_junctions(s.dir, "b2", p);
  EXPECT_EQ(read_predicted_junctions(predicted_junctions_path(s.dir, "b2")).offset_m, p.offset_m);
}

// A hand-off written before the offsets were kept still serves a run without the max_offset_m screen (so a
// run in progress resumes without predicting everything again), never one with it.
TEST(JunctionHandoff, OlderVersionServesOnlyWithoutTheOffsetScreen) {
  EXPECT_TRUE(handoff_version_usable(4, true));
  EXPECT_TRUE(handoff_version_usable(4, false));
  EXPECT_TRUE(handoff_version_usable(3, false));
  EXPECT_FALSE(handoff_version_usable(3, true));
  EXPECT_FALSE(handoff_version_usable(2, false));
  EXPECT_FALSE(handoff_version_usable(5, false));
}

TEST(JunctionHandoff, RejectsBadFilesNamingThem) {
  Scratch s;
  const fs::path bad = s.dir / "bad.json";
  for (const std::string text :
       {std::string("{\"format\": \"other\", \"version\": 1}"),
        std::string("{\"format\": \"lc2wf-predicted-junctions\", \"version\": 1, \"positions\": [[0,0,0]], \"confidences\": []}"),
        std::string("{\"format\": \"lc2wf-predicted-junctions\", \"version\": 1, \"positions\": [[0,0]], \"confidences\": [0.5]}"),
        std::string("{\"format\": \"lc2wf-predicted-junctions\", \"version\": 1, \"positions\": [[0,0,0]], \"confidences\": [1.5]}"),
        std::string("{\"format\": \"lc2wf-predicted-junctions\", \"version\": 1, \"positions\": [[0,0,0]], \"confidences\": [0.5], \"offsets\": [1, 2]}"),
        std::string("{\"format\": \"lc2wf-predicted-junctions\", \"version\": 1, \"positions\": [[0,0,0]], \"confidences\": [0.5], \"offsets\": [-1]}"),
        std::string("not json")}) {
    std::ofstream(bad) << text;
    try {
      read_predicted_junctions(bad);
      ADD_FAILURE() << "accepted: " << text;
    } catch (const DataError& e) {
      EXPECT_THAT(std::string(e.what()), HasSubstr(bad.string())) << e.what();
    }
  }
}

}  // namespace
}  // namespace lc2wf
