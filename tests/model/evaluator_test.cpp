#include "model/evaluator.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>

using ::testing::HasSubstr;

namespace lc2wf {
namespace {

Wireframe segment(double x) {
  Wireframe w;
  w.junctions = {{x, 0, 0}, {x + 3, 0, 0}};
  w.edges = {{0, 1}};
  return w;
}

TEST(Evaluator, PoolsHitsAcrossBuildings) {
  Evaluator ev(EvalOptions{});
  // Building a: exact prediction with an extra isolated junction (ignored), scores .9/.8, edge .7.
  ScoredWireframe a = ScoredWireframe::with_unit_scores(segment(0));
  a.wireframe.junctions.push_back({50, 0, 0});
  a.junction_scores = {.9, .8, .99};
  a.edge_scores = {.7};
  ev.add("a", a, segment(0));
  // Building b: edge shifted by 0.3 m (junction FPs at 0.15/0.25, TPs at 0.35), junction scores .95.
  ScoredWireframe b = ScoredWireframe::with_unit_scores(segment(0.3));
  b.junction_scores = {.95, .95};
  b.edge_scores = {.95};
  ev.add("b", b, segment(0));
  ev.add("c", {}, segment(0), /*prediction_missing=*/true);

  const EvalReport r = ev.report();
  ASSERT_EQ(r.buildings.size(), 3u);
  EXPECT_EQ(r.buildings[0].pred_vertices, 2);
  EXPECT_EQ(r.missing_predictions(), std::vector<std::string>{"c"});
  // vAP at 0.15 m: ranked .95 FP, .95 FP, .9 TP, .8 TP of 6 GT -> (1/6, 1/3), (1/3, 1/2).
  EXPECT_EQ(r.vertex[0].true_positives, 2);
  EXPECT_EQ(r.vertex[0].ground_truth, 6);
  EXPECT_NEAR(r.vertex[0].ap, (1.0 / 3.0) * 0.5, 1e-12);
  EXPECT_NEAR(r.vertex[0].recall, 1.0 / 3.0, 1e-12);
  // At 0.35 m all four predictions are TPs: AP = recall = 4/6.
  EXPECT_NEAR(r.vertex[2].ap, 4.0 / 6.0, 1e-12);
  EXPECT_NEAR(r.vertex_recall_mean, (2.0 / 6 + 2.0 / 6 + 4.0 / 6) / 3.0, 1e-12);
  // sAP at 0.25 m: b's edge is 0.6 m off (FP, .95), a's exact (TP, .7) -> (1/3, 1/2).
  EXPECT_NEAR(r.edge[0].ap, 1.0 / 6.0, 1e-12);
  EXPECT_NEAR(r.edge[2].ap, 1.0 / 6.0, 1e-12);  // 0.6 m is still > 0.50 m
  // WED: a costs 0, b moves two junctions by 0.3 m (sqrt(6 raw)/20 each), c adds 2 vertices + a 3 m edge.
  EXPECT_NEAR(r.wed.move, 2.0 * std::sqrt(6.0) / 20.0 / 3.0, 1e-12);
  EXPECT_NEAR(r.wed.add_vertex, 2.0 / 3.0, 1e-12);
  EXPECT_NEAR(r.wed.add_edge_length, 1.0, 1e-12);
  EXPECT_NEAR(r.wed.total_num, (0 + 0 + 3) / 3.0, 1e-12);
}

TEST(Evaluator, EqualScoresRankInBuildingOrderByDefault) {
  // Two buildings with unit scores everywhere: a's prediction misses, b's hits. The release ranks the tie
  // in building order, so the AP depends on which building comes first.
  EXPECT_EQ(EvalOptions{}.ties, ApTieRule::kListOrder);
  for (const bool b_first : {false, true}) {
    Evaluator ev(EvalOptions{});
    ScoredWireframe miss = ScoredWireframe::with_unit_scores(segment(10)), hit = ScoredWireframe::with_unit_scores(segment(0));
    if (b_first) {
      ev.add("b", hit, segment(0));
      ev.add("a", miss, segment(0));
    } else {
      ev.add("a", miss, segment(0));
      ev.add("b", hit, segment(0));
    }
    const EvalReport r = ev.report();
    // Vertices: 2 misses and 2 hits of 4 GT, all scored 1. Hits first: precision 1 up to recall 1/2.
    EXPECT_NEAR(r.vertex[0].ap, b_first ? 0.5 : 0.25, 1e-12) << b_first;
  }
}

TEST(Evaluator, StrictWedOnlyWhenAsked) {
  EvalOptions o;
  o.strict_wed = true;
  Evaluator ev(o);
  ScoredWireframe p = ScoredWireframe::with_unit_scores(segment(0));
  p.wireframe.junctions.push_back({0, 0.1, 0});
  p.wireframe.edges.push_back({0, 2});
  p.junction_scores.push_back(1);
  p.edge_scores.push_back(1);
  ev.add("a", p, segment(0));
  const EvalReport r = ev.report();
  EXPECT_EQ(r.wed.total_num, 0.0);  // the degenerate edge and the duplicate junction are free in the release
  EXPECT_EQ(r.wed_strict.del_vertex, 1.0);
  EXPECT_EQ(r.wed_strict.del_edge, 1.0);
}

TEST(Evaluator, RejectsBadInputAndOptions) {
  Evaluator ev(EvalOptions{});
  ScoredWireframe p = ScoredWireframe::with_unit_scores(segment(0));
  p.edge_scores.clear();
  EXPECT_THROW(ev.add("x", p, segment(0)), std::invalid_argument);
  ScoredWireframe nan_score = ScoredWireframe::with_unit_scores(segment(0));
  nan_score.junction_scores[1] = std::nan("");
  EXPECT_THROW(ev.add("z", nan_score, segment(0)), std::invalid_argument);
  Wireframe bad_gt = segment(0);
  bad_gt.edges.push_back({0, 7});
  EXPECT_THROW(ev.add("y", ScoredWireframe{}, bad_gt), std::invalid_argument);
  EvalOptions o;
  o.edge_thresholds = {0.25, -1};
  try {
    o.Check();
    FAIL() << "negative threshold accepted";
  } catch (const std::invalid_argument& e) {
    EXPECT_THAT(std::string(e.what()), HasSubstr("edge_thresholds"));
  }
}

TEST(Evaluator, EmptySplitGivesZeros) {
  const EvalReport r = Evaluator(EvalOptions{}).report();
  EXPECT_EQ(r.vertex_ap_mean, 0.0);
  EXPECT_EQ(r.wed.total_dist, 0.0);
}

}  // namespace
}  // namespace lc2wf
