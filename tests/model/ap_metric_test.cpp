#include "model/ap_metric.h"

#include <gtest/gtest.h>

namespace lc2wf {
namespace {

std::vector<RankedHit> hits(std::initializer_list<std::pair<double, bool>> list) {
  std::vector<RankedHit> out;
  for (const auto& [s, tp] : list) out.push_back({s, tp});
  return out;
}

TEST(ApMetric, VocApOfHandComputedList) {
  // TP FP FP TP of 3 GT: points (1/3, 1) (1/3, .5) (1/3, 1/3) (2/3, .5) -> AP = 1/3 * 1 + 1/3 * .5.
  EXPECT_NEAR(voc_average_precision(hits({{.9, true}, {.8, false}, {.7, false}, {.6, true}}), 3, ApTieRule::kListOrder),
              0.5, 1e-12);
  // Perfect ranking with full recall.
  EXPECT_NEAR(voc_average_precision(hits({{.9, true}, {.8, true}}), 2, ApTieRule::kGroupTies), 1.0, 1e-12);
  // Interpolation from the right: FP first, then two TP of 2 GT -> precision at recall 1/2 is lifted to 2/3.
  EXPECT_NEAR(voc_average_precision(hits({{.9, false}, {.8, true}, {.7, true}}), 2, ApTieRule::kListOrder),
              0.5 * (2.0 / 3.0) + 0.5 * (2.0 / 3.0), 1e-12);
}

TEST(ApMetric, InputOrderDoesNotMatterForDistinctScores) {
  const auto a = hits({{.6, true}, {.9, true}, {.7, false}, {.8, false}});
  const auto b = hits({{.9, true}, {.8, false}, {.7, false}, {.6, true}});
  EXPECT_DOUBLE_EQ(voc_average_precision(a, 3, ApTieRule::kListOrder), voc_average_precision(b, 3, ApTieRule::kListOrder));
}

TEST(ApMetric, TiedScoresGroupedOrInListOrder) {
  // Equal scores, TP listed first: list order gives (1/2, 1) then (1/2, 1/2) -> AP 0.5;
  // grouping evaluates only after both -> (1/2, 1/2) -> AP 0.25, whatever the order.
  const auto tp_first = hits({{1.0, true}, {1.0, false}});
  const auto fp_first = hits({{1.0, false}, {1.0, true}});
  EXPECT_NEAR(voc_average_precision(tp_first, 2, ApTieRule::kListOrder), 0.5, 1e-12);
  EXPECT_NEAR(voc_average_precision(fp_first, 2, ApTieRule::kListOrder), 0.25, 1e-12);
  EXPECT_NEAR(voc_average_precision(tp_first, 2, ApTieRule::kGroupTies), 0.25, 1e-12);
  EXPECT_NEAR(voc_average_precision(fp_first, 2, ApTieRule::kGroupTies), 0.25, 1e-12);
  // A tie group inside a longer list: .9 TP, then {.5 TP, .5 FP}, 4 GT -> (1/4, 1), (1/2, 2/3).
  EXPECT_NEAR(voc_average_precision(hits({{.9, true}, {.5, false}, {.5, true}}), 4, ApTieRule::kGroupTies),
              0.25 * 1.0 + 0.25 * (2.0 / 3.0), 1e-12);
}

TEST(ApMetric, EmptyPredictionsOrEmptyGroundTruth) {
  EXPECT_EQ(voc_average_precision({}, 5, ApTieRule::kGroupTies), 0.0);
  EXPECT_EQ(voc_average_precision(hits({{.9, false}}), 0, ApTieRule::kGroupTies), 0.0);
  const ApSummary s = summarize_hits({}, 4, 0.25, ApTieRule::kGroupTies);
  EXPECT_EQ(s.ap, 0.0);
  EXPECT_EQ(s.recall, 0.0);
  EXPECT_EQ(s.ground_truth, 4);
  EXPECT_EQ(s.predictions, 0);
}

TEST(ApMetric, JunctionMatchingGreedyInScoreOrder) {
  const std::vector<Vec3> gt{{0, 0, 0}, {10, 0, 0}, {0, 10, 0}};
  const std::vector<Vec3> pred{{0.1, 0, 0}, {10.3, 0, 0}, {0.05, 0, 0}, {0, 10.1, 0}};
  const std::vector<double> score{.9, .8, .7, .6};
  auto strict = match_junctions(pred, score, gt, 0.15);
  ASSERT_EQ(strict.size(), 4u);
  EXPECT_TRUE(strict[0].true_positive);
  EXPECT_FALSE(strict[1].true_positive);  // 0.3 m away
  EXPECT_FALSE(strict[2].true_positive);  // its nearest GT was already taken
  EXPECT_TRUE(strict[3].true_positive);
  const ApSummary s15 = summarize_hits(strict, 3, 0.15, ApTieRule::kGroupTies);
  EXPECT_NEAR(s15.ap, 0.5, 1e-12);
  EXPECT_NEAR(s15.recall, 2.0 / 3.0, 1e-12);
  // At 0.35 m: TP TP FP TP -> 1/3 + 1/3 + 1/3 * 3/4.
  const ApSummary s35 = summarize_hits(match_junctions(pred, score, gt, 0.35), 3, 0.35, ApTieRule::kGroupTies);
  EXPECT_NEAR(s35.ap, 2.0 / 3.0 + 0.25, 1e-12);
  EXPECT_NEAR(s35.recall, 1.0, 1e-12);
}

TEST(ApMetric, OnlyTheNearestGroundTruthIsTried) {
  // The second prediction is 0.2 m from the free GT vertex B but nearer to the taken A: still a FP.
  const std::vector<Vec3> gt{{0, 0, 0}, {0.3, 0, 0}};
  const std::vector<Vec3> pred{{0, 0, 0}, {0.1, 0, 0}};
  const auto h = match_junctions(pred, {.9, .8}, gt, 0.25);
  EXPECT_TRUE(h[0].true_positive);
  EXPECT_FALSE(h[1].true_positive);
  EXPECT_NEAR(voc_average_precision(h, 2, ApTieRule::kGroupTies), 0.5, 1e-12);
}

TEST(ApMetric, HigherScoreClaimsFirstWhateverTheIndex) {
  const std::vector<Vec3> gt{{0, 0, 0}};
  const std::vector<Vec3> pred{{0.1, 0, 0}, {0.01, 0, 0}};
  const auto h = match_junctions(pred, {.2, .7}, gt, 0.15);
  ASSERT_EQ(h.size(), 2u);
  EXPECT_EQ(h[0].score, .7);
  EXPECT_TRUE(h[0].true_positive);
  EXPECT_FALSE(h[1].true_positive);
}

TEST(ApMetric, ScoresAtOrBelowMinScoreAreDropped) {
  const std::vector<Vec3> gt{{0, 0, 0}};
  const auto h = match_junctions({{0, 0, 0}, {5, 0, 0}}, {0.0, 0.4}, gt, 0.15);
  ASSERT_EQ(h.size(), 1u);
  EXPECT_FALSE(h[0].true_positive);
}

TEST(ApMetric, EmptyGroundTruthMakesEveryPredictionFalse) {
  const auto h = match_junctions({{0, 0, 0}}, {.9}, {}, 0.15);
  ASSERT_EQ(h.size(), 1u);
  EXPECT_FALSE(h[0].true_positive);
}

TEST(ApMetric, SegmentDistanceUsesBestOrientation) {
  EXPECT_NEAR(segment_pair_distance({0, 0, 0}, {1, 0, 0}, {1, 0.1, 0}, {0, 0.2, 0}), 0.3, 1e-12);
  EXPECT_NEAR(segment_pair_distance({0, 0, 0}, {1, 0, 0}, {0, 0, 0.1}, {1, 0, 0.1}), 0.2, 1e-12);
}

TEST(ApMetric, EdgeMatchingWithReversedAndDuplicateEdges) {
  Wireframe gt;
  gt.junctions = {{0, 0, 0}, {4, 0, 0}, {4, 3, 0}};
  gt.edges = {{0, 1}, {1, 2}};
  ScoredWireframe pred;
  pred.wireframe.junctions = {{4.1, 0, 0}, {0, 0.05, 0}, {4, 3, 0}, {0, 0, 0}};
  pred.junction_scores = {1, 1, 1, 1};
  // e0 = reversed GT edge 0 (distance 0.15), e1 = duplicate of GT 0 (0.1), e2 = GT 1 off by 0.1.
  pred.wireframe.edges = {{0, 1}, {0, 3}, {0, 2}};
  pred.edge_scores = {.9, .8, .7};
  const auto h25 = match_edges(pred, gt, 0.25);
  ASSERT_EQ(h25.size(), 3u);
  EXPECT_TRUE(h25[0].true_positive);
  EXPECT_FALSE(h25[1].true_positive);  // GT edge 0 already taken
  EXPECT_TRUE(h25[2].true_positive);
  EXPECT_NEAR(voc_average_precision(h25, 2, ApTieRule::kGroupTies), 0.5 + 0.5 * (2.0 / 3.0), 1e-12);
  const auto h12 = match_edges(pred, gt, 0.12);
  EXPECT_FALSE(h12[0].true_positive);  // 0.15 > 0.12
  EXPECT_TRUE(h12[1].true_positive);
  EXPECT_TRUE(h12[2].true_positive);
}

}  // namespace
}  // namespace lc2wf
