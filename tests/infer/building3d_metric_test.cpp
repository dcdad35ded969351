// Hand-computed cases for the Building3D-style metrics and the assignment solver behind them.
#include "infer/building3d_metric.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>

#include "infer/building3d_io.h"
#include "infer/hungarian.h"

using ::testing::HasSubstr;

namespace lc2wf {
namespace {

TEST(MinCostAssignment, SquareMatrixFindsTheCheapestPermutation) {
  // Rows 0 and 1 both prefer column 1; it goes to row 0 (1 + 2 + 2 = 5, against 4 + 0 + 2 = 6).
  EXPECT_EQ(min_cost_assignment({{4, 1, 3}, {2, 0, 5}, {3, 2, 2}}), (std::vector<int>{1, 0, 2}));
  // Greedy per row (row 0 -> its nearest column 0) would cost 1 + 10; the assignment costs 2 + 1.
  EXPECT_EQ(min_cost_assignment({{1, 2}, {1, 10}}), (std::vector<int>{1, 0}));
}

TEST(MinCostAssignment, MoreRowsThanColumnsLeavesTheCostliestRowOut) {
  // Two columns for three rows: row2->0 (0) + row1->1 (1) beats row0->0 + row1->1 (2).
  EXPECT_EQ(min_cost_assignment({{1, 5}, {2, 1}, {0, 9}}), (std::vector<int>{-1, 1, 0}));
  EXPECT_EQ(min_cost_assignment({{3, 0, 7}}), (std::vector<int>{1}));
  EXPECT_EQ(min_cost_assignment({{}, {}}), (std::vector<int>{-1, -1}));
  EXPECT_TRUE(min_cost_assignment({}).empty());
  EXPECT_THROW(min_cost_assignment({{1, 2}, {3}}), std::invalid_argument);
}

TEST(NormalisationFrame, CentroidAndMaximumRadiusOfTheCloudEndpoints) {
  const NormalisationFrame f = frame_of_segments({{{0, 0, 0}, {2, 0, 0}}, {{0, 2, 0}, {2, 2, 0}}});
  EXPECT_TRUE(f.centroid.isApprox(Vec3(1, 1, 0)));
  EXPECT_NEAR(f.radius, std::sqrt(2.0), 1e-12);
  EXPECT_EQ(frame_of_points({}).radius, 1.0);
  EXPECT_EQ(frame_of_points({{3, 3, 3}}).radius, 1.0);  // one point: no scale, keep 1
}

// GT: a 4 m square A(0,0) B(4,0) C(4,4) D(0,4); frame radius 10 m, so the 0.1 threshold is 1 m.
Wireframe square() {
  Wireframe w;
  w.junctions = {{0, 0, 0}, {4, 0, 0}, {4, 4, 0}, {0, 4, 0}};
  w.edges = {{0, 1}, {1, 2}, {2, 3}, {0, 3}};
  return w;
}

NormalisationFrame radius10() { return frame_of_points({{10, 0, 0}, {-10, 0, 0}}); }

ScoredWireframe prediction() {
  ScoredWireframe p;
  // p0 0.3 m from A, p1 0.4 m from B, p2 2 m above C (beyond 1 m), p3 far away.
  p.wireframe.junctions = {{0.3, 0, 0}, {4, 0.4, 0}, {4, 4, 2}, {9, 9, 0}};
  p.wireframe.edges = {{0, 1}, {1, 2}, {0, 3}, {0, 2}};
  p.junction_scores = {1, 1, 1, 1};
  p.edge_scores = {0.9, 0.8, 0.5, 0.71};  // (0,3) falls under the 0.7 cut, so p3 is no corner
  return p;
}

TEST(Building3dCounts, HandComputedSquare) {
  const Building3dCounts c = building3d_counts(prediction(), square(), radius10());
  EXPECT_EQ(c.pred_corners, 3);
  EXPECT_EQ(c.gt_corners, 4);
  EXPECT_EQ(c.tp_corners, 2);                      // p0-A and p1-B; p2-C is 0.2 normalised
  EXPECT_NEAR(c.corner_offset_sum, 0.7, 1e-12);    // 0.3 + 0.4 m
  EXPECT_EQ(c.pred_edges, 3);
  EXPECT_EQ(c.gt_edges, 4);
  EXPECT_EQ(c.tp_edges, 1);                        // only (p0, p1) -> AB has both ends matched
  // nWED: moves 0.3 + 0.4 + 2; (p1,p2)->BC and (p0,p1)->AB hit; (p0,p2)->AC costs 4*sqrt2; CD, DA missed: 8.
  EXPECT_NEAR(c.nwed, (2.7 + 4 * std::sqrt(2.0) + 8) / 16, 1e-12);
  EXPECT_TRUE(c.has_gt_edges);
}

TEST(Building3dCounts, ThresholdIsInNormalisedUnits) {
  // With a 30 m radius the threshold is 3 m: p2 (2 m off C) becomes a TP, and so do its edges.
  const Building3dCounts c = building3d_counts(prediction(), square(), frame_of_points({{30, 0, 0}, {-30, 0, 0}}));
  EXPECT_EQ(c.tp_corners, 3);
  EXPECT_NEAR(c.corner_offset_sum, 2.7, 1e-12);
  EXPECT_EQ(c.tp_edges, 2);  // AB and BC; (p0, p2) -> AC is no GT edge
}

TEST(Building3dSummary, PoolsCountsOverBuildings) {
  const Building3dCounts a = building3d_counts(prediction(), square(), radius10());
  const Building3dCounts empty = building3d_counts(ScoredWireframe{}, square(), radius10());
  EXPECT_EQ(empty.pred_corners, 0);
  EXPECT_EQ(empty.nwed, 1.0);  // nothing predicted: every GT edge is missing
  const Building3dSummary s = summarize_building3d({a, empty}, {}, "test points");
  EXPECT_EQ(s.buildings, 2);
  EXPECT_NEAR(s.cp, 2.0 / 3, 1e-12);
  EXPECT_NEAR(s.cr, 2.0 / 8, 1e-12);
  EXPECT_NEAR(s.cf1, 2 * (2.0 / 3) * 0.25 / (2.0 / 3 + 0.25), 1e-12);
  EXPECT_NEAR(s.ep, 1.0 / 3, 1e-12);
  EXPECT_NEAR(s.er, 1.0 / 8, 1e-12);
  EXPECT_NEAR(s.aco, 0.35, 1e-12);
  EXPECT_NEAR(s.nwed_mean, ((2.7 + 4 * std::sqrt(2.0) + 8) / 16 + 1.0) / 2, 1e-12);
  EXPECT_NEAR(s.mean_radius, 10.0, 1e-12);
}

TEST(Building3dSummary, EmptySetIsAllZero) {
  const Building3dSummary s = summarize_building3d({}, {}, "none");
  EXPECT_EQ(s.cf1, 0.0);
  EXPECT_EQ(s.aco, 0.0);
  EXPECT_EQ(s.nwed_mean, 0.0);
}

TEST(Building3dOptions, RejectsBadValues) {
  Building3dOptions o;
  o.distance_threshold = 0;
  EXPECT_THROW(o.Check(), std::invalid_argument);
  o = {};
  o.confidence_threshold = NAN;
  EXPECT_THROW(o.Check(), std::invalid_argument);
}

TEST(Building3dIo, SectionStatesFrameThresholdCutAndVariant) {
  Building3dReport r;
  r.per_building = {building3d_counts(prediction(), square(), radius10())};
  r.names = {"sq"};
  r.summary = summarize_building3d(r.per_building, {}, "line-cloud segment endpoints");
  const std::string md = building3d_markdown(r, "ours");
  for (const char* s : {"CP", "EF1", "ACO", "B3D-nWED", "line-cloud segment endpoints", "score > 0.7", "0.1 normalised",
                        "2023 calculator", "not the paper"})
    EXPECT_THAT(md, HasSubstr(s)) << s;
  const nlohmann::json j = building3d_json(r);
  EXPECT_NEAR(j["cp"].get<double>(), 2.0 / 3, 1e-12);
  EXPECT_EQ(j["per_building"][0]["name"], "sq");
  EXPECT_EQ(j["confidence_threshold"].get<double>(), 0.7);
}

}  // namespace
}  // namespace lc2wf
