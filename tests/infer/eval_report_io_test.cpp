#include "infer/eval_report_io.h"

#include <gtest/gtest.h>

#include "test_files.h"

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
  EXPECT_NE(md.find("| method | v η=0.15 | v η=0.25 | v η=0.35 | v avg. | s η=0.25 | s η=0.35 | s η=0.50 | s avg. |"),
            std::string::npos);
  // Half of the GT found with perfect precision: AP = recall = 50 % at every threshold.
  EXPECT_NE(md.find("| ours | 50.0/50.0 | 50.0/50.0 | 50.0/50.0 | 50.0/50.0 | 50.0/50.0 |"), std::string::npos);
  EXPECT_NE(md.find("| method | +vertex | +edge | −edge | total |"), std::string::npos);
  // Mean over 2 buildings: the missing one adds 3 vertices and 3 edges of 12 m in total.
  EXPECT_NE(md.find("| ours | 1.500 / 0.000 | 1.500 / 6.000 | 0.000 / 0.000 | 3.000 / 6.000 |"), std::string::npos);
  EXPECT_NE(md.find("without a prediction: needs,quote"), std::string::npos);
  EXPECT_EQ(md.find("Strict"), std::string::npos);
  EXPECT_NE(eval_markdown(small_report(true), "ours").find("Strict WED"), std::string::npos);
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
  EXPECT_NE(csv.find("\nexact,0,3,3,3,3,3,3,3,3,3,3,0,0,0,0,0,0,0,0\n"), std::string::npos);
  EXPECT_NE(csv.find("\n\"needs,quote\",1,"), std::string::npos);
}

TEST(EvalReportIo, WritesThreeFiles) {
  testing::ScratchDir dir("report");
  write_eval_outputs(dir.path() / "out", small_report(false), "ours");
  for (const char* f : {"metrics.md", "metrics.json", "per_building.csv"})
    EXPECT_FALSE(testing::read_text(dir.path() / "out" / f).empty()) << f;
  EXPECT_EQ(nlohmann::json::parse(testing::read_text(dir.path() / "out" / "metrics.json"))["method"], "ours");
}

}  // namespace
}  // namespace lc2wf
