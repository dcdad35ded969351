#include "infer/eval_report_io.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "core/util/version.h"
#include "test_files.h"

using ::testing::HasSubstr;
using ::testing::Not;

namespace lc2wf {
namespace {

EvalReport small_report(bool strict) {
  EvalOptions o;
  o.strict_wed = strict;
  Evaluator ev(o);
  Wireframe gt;
  gt.junctions = {{0, 0, 0}, {3, 0, 0}, {3, 4, 0}};
  gt.edges = {{0, 1}, {1, 2}, {0, 2}};
  ev.add("exact", ScoredWireframe::with_unit_scores(gt), gt);
  ev.add("needs,quote", {}, gt, /*prediction_missing=*/true);
  return ev.report();
}

TEST(EvalReportIo, MarkdownHasBothTablesInPaperShape) {
  const std::string md = eval_markdown(small_report(false), "ours");
  EXPECT_THAT(md, HasSubstr("| method | v η=0.15 | v η=0.25 | v η=0.35 | v avg. | s η=0.25 | s η=0.35 | s η=0.50 | s avg. |"));
  // Half of the GT found with perfect precision: AP = recall = 50 % at every threshold.
  EXPECT_THAT(md, HasSubstr("| ours | 50.0/50.0 | 50.0/50.0 | 50.0/50.0 | 50.0/50.0 | 50.0/50.0 |"));
  EXPECT_THAT(md, HasSubstr("| method | +vertex | +edge | −edge | total |"));
  // Mean over 2 buildings: the missing one adds 3 vertices and 3 edges of 12 m in total.
  EXPECT_THAT(md, HasSubstr("| ours | 1.500 / 0.000 | 1.500 / 6.000 | 0.000 / 0.000 | 3.000 / 6.000 |"));
  EXPECT_THAT(md, HasSubstr("without a prediction: needs,quote"));
  EXPECT_THAT(md, Not(HasSubstr("Strict")));
  EXPECT_THAT(eval_markdown(small_report(true), "ours"), HasSubstr("Strict WED"));
}

TEST(EvalReportIo, JsonHoldsEveryNumber) {
  const nlohmann::json j = eval_json(small_report(true), "ours");
  EXPECT_EQ(j["buildings"], 2);
  EXPECT_EQ(j["missing_predictions"][0], "needs,quote");
  ASSERT_EQ(j["vertex"].size(), 3u);
  EXPECT_DOUBLE_EQ(j["vertex"][0]["threshold_raw"].get<double>(), 3.0);
  EXPECT_DOUBLE_EQ(j["edge"][2]["threshold_raw"].get<double>(), 10.0);
  EXPECT_DOUBLE_EQ(j["vertex"][1]["ap"].get<double>(), 0.5);
  EXPECT_EQ(j["vertex"][1]["ground_truth"], 6);
  EXPECT_DOUBLE_EQ(j["wed"]["add_edge_length"].get<double>(), 6.0);
  EXPECT_TRUE(j.contains("wed_strict"));
  EXPECT_EQ(j["per_building"][1]["wed"]["add_vertex"], 3);
  EXPECT_EQ(j["options"]["ties"], "list_order");
}

TEST(EvalReportIo, CsvRowPerBuildingWithQuoting) {
  const std::string csv = eval_per_building_csv(small_report(false));
  EXPECT_EQ(std::count(csv.begin(), csv.end(), '\n'), 3);
  EXPECT_EQ(csv.rfind("name,prediction_missing,gt_vertices", 0), 0u);
  EXPECT_THAT(csv, HasSubstr("\nexact,0,3,3,3,3,3,3,3,3,3,3,0,0,0,0,0,0,0,0\n"));
  EXPECT_THAT(csv, HasSubstr("\n\"needs,quote\",1,"));
}

TEST(EvalReportIo, WritesThreeFiles) {
  testing::ScratchDir dir("report");
  write_eval_outputs(dir.path() / "out", small_report(false), "ours");
  for (const char* f : {"metrics.md", "metrics.json", "per_building.csv"})
    EXPECT_FALSE(testing::read_text(dir.path() / "out" / f).empty()) << f;
  const auto j = nlohmann::json::parse(testing::read_text(dir.path() / "out" / "metrics.json"));
  EXPECT_EQ(j["method"], "ours");
  // Which lc2wf made the numbers.
  EXPECT_EQ(j["lc2wf_version"], lc2wf_version());
  EXPECT_EQ(j["commit"], lc2wf_git_commit());
  EXPECT_THAT(testing::read_text(dir.path() / "out" / "metrics.md"), HasSubstr(version_line()));
}

// A metrics file's inference record reads back as it was written (scoring saved predictions again keeps it).
TEST(EvalReportIo, InferenceRecordRoundTrips) {
  InferenceTiming s;
  s.buildings = 4;
  s.empty = 1;
  s.total_seconds = 2.0, s.max_seconds = 0.9, s.junction_seconds = 0.4, s.edge_seconds = 1.5, s.post_seconds = 0.1;
  s.pairs = 1200;
  s.threads = 2;
  s.precision = "bf16";
  s.pair_support = 0.1;
  s.min_confidence = 0.3, s.nms_radius_m = 0.6, s.max_offset_m = 1.25;
  s.sampling_passes = 2;
  s.test_time_views = 4;
  s.density_seeds = "release";
  s.edge_test_time_views = 2;
  s.max_segment_length_m = 1.5;
  s.cut = 3;
  s.cut_sampling_passes = 3;
  EXPECT_EQ(inference_json(inference_from_json(inference_json(s))), inference_json(s));
  EXPECT_THAT(inference_markdown(s), HasSubstr("2 sampling passes, release density seeds, 4 test-time views, 2 edge views, "
                                               "segments cut at 1.5 m (3 of 4 clouds cut, sampled in 3 passes)"));
  s.max_offset_m = std::numeric_limits<double>::infinity();  // every candidate: null in JSON
  EXPECT_TRUE(std::isinf(inference_from_json(inference_json(s)).max_offset_m));
  // Records written before the selection was kept were made with the release's.
  nlohmann::json old = inference_json(s);
  for (const char* key : {"min_confidence", "nms_radius_m", "max_offset_m", "sampling_passes", "test_time_views", "density_seeds",
                          "edge_test_time_views", "max_segment_length_m", "cut_clouds", "cut_sampling_passes"})
    old.erase(key);
  const InferenceTiming then = inference_from_json(old);
  EXPECT_EQ(then.sampling_passes, 1);
  EXPECT_EQ(then.test_time_views, 1);
  EXPECT_EQ(then.density_seeds, "release");
  EXPECT_EQ(then.edge_test_time_views, 1);
  EXPECT_EQ(then.max_segment_length_m, 0.0);
  EXPECT_EQ(then.cut, 0);
  EXPECT_EQ(then.cut_sampling_passes, 1);
  EXPECT_EQ(then.min_confidence, 0.85);
  EXPECT_EQ(then.nms_radius_m, 0.25);
  EXPECT_TRUE(std::isinf(then.max_offset_m));
  EXPECT_THROW(inference_from_json(nlohmann::json::object()), nlohmann::json::exception);
}

}  // namespace
}  // namespace lc2wf
